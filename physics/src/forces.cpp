#include "forces.h"

#include <cmath>

namespace softbody {

ParticleState current_state(const SoftBody& body) {
    return {body.x.x.data(), body.x.y.data(), body.x.z.data(), body.v.x.data(), body.v.y.data(), body.v.z.data()};
}

void add_gravity(Vec3Array& force, float m, const Vec3& g) {
    const Vec3 weight = g * m;
    for (std::size_t i = 0; i < force.size(); ++i) force.add(i, weight);
}

void add_drag(Vec3Array& force, const ParticleState& s, std::size_t n, float rho, float C_D, float rest_radius) {
    double vx = 0.0, vy = 0.0, vz = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        vx += s.vx[i];
        vy += s.vy[i];
        vz += s.vz[i];
    }
    const Vec3 v_com{float(vx / double(n)), float(vy / double(n)), float(vz / double(n))};
    const float S = 3.14159265f * rest_radius * rest_radius;  // bounding sphere's cross-section
    const Vec3 F_drag = -0.5f * rho * C_D * S * length(v_com) * v_com;
    const Vec3 share = F_drag / static_cast<float>(n);
    for (std::size_t i = 0; i < n; ++i) force.add(i, share);
}

void add_grab(Vec3Array& force, const ParticleState& s, const Grab& grab, float m, float h) {
    const std::uint32_t p = grab.particle;
    const float k_grab = grab.stiffness > 0.0f ? grab.stiffness : m / (h * h) * 0.5f;
    const float c_grab = 2.0f * std::sqrt(k_grab * m) * 0.5f;
    const Vec3 x_p{s.x[p], s.y[p], s.z[p]}, v_p{s.vx[p], s.vy[p], s.vz[p]};
    force.add(p, k_grab * (grab.target - x_p) - c_grab * v_p);
}

}  // namespace softbody

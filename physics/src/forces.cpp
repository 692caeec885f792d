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

namespace {

// The backward-Euler step of dv/dt = -kappa |v| v from v* (the velocity without drag): the
// speed s' with s' + h kappa s'^2 = |v*|, in the form that does not cancel for small h kappa.
double implicit_drag_speed(double speed, double kappa, double h) {
    return 2.0 * speed / (1.0 + std::sqrt(1.0 + 4.0 * h * kappa * speed));
}

}  // namespace

void add_drag(Vec3Array& force, const ParticleState& s, std::size_t n, float rho, float C_D, float rest_radius, float m,
              float h) {
    double vx = 0.0, vy = 0.0, vz = 0.0, fx = 0.0, fy = 0.0, fz = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        vx += s.vx[i];
        vy += s.vy[i];
        vz += s.vz[i];
        fx += force.x[i];
        fy += force.y[i];
        fz += force.z[i];
    }
    const double M = double(m) * double(n);
    const double S = 3.14159265358979 * double(rest_radius) * double(rest_radius);  // bounding sphere's cross-section
    const double kappa = 0.5 * double(rho) * double(C_D) * S / M;                  // Eq. 23's -1/2 rho C_D S, per kg
    // The centre of mass's velocity after this step without drag, then with it (backward Euler).
    const Vec3d v_star = Vec3d{vx, vy, vz} / double(n) + Vec3d{fx, fy, fz} * (double(h) / M);
    const double speed = length(v_star);
    if (!(speed > 0.0)) return;
    const Vec3d v_new = v_star * (implicit_drag_speed(speed, kappa, double(h)) / speed);
    const Vec3 share = to_float((v_new - v_star) * (M / double(h) / double(n)));
    for (std::size_t i = 0; i < n; ++i) force.add(i, share);
}

void add_grab(Vec3Array& force, const ParticleState& s, const Grab& grab, float m, float h) {
    const std::uint32_t p = grab.particle;
    const float k_grab = grab.stiffness > 0.0f ? grab.stiffness : m / (h * h) * 0.5f;
    const float c_grab = 2.0f * std::sqrt(k_grab * m) * 0.5f;
    const Vec3 x_p{s.x[p], s.y[p], s.z[p]}, v_p{s.vx[p], s.vy[p], s.vz[p]};
    force.add(p, k_grab * (grab.target - x_p) - c_grab * v_p);
}

// ---------------------------------------------------------------------------------------------
// Rigid bodies
// ---------------------------------------------------------------------------------------------
void add_force_at(Wrench& w, const RigidMotion& m, const Vec3d& p, const Vec3d& F) {
    w.F += F;
    w.tau += cross(p - m.x, F);  // Eq. 27: tau = r x F
}

void add_rigid_gravity(Wrench& w, const RigidBody& body, const Vec3& g) { w.F += Vec3d(g) * body.mass; }

void add_rigid_drag(Wrench& w, const RigidBody& body, const RigidMotion& m, float rho, float h) {
    // Eq. 23: F_drag = -1/2 rho C_D S |v| v, by backward Euler (add_drag says why).
    const double kappa = 0.5 * rho * body.drag_coefficient * body.drag_area * body.inv_mass;
    const Vec3d v_star = m.v + w.F * (double(h) * body.inv_mass);
    const double speed = length(v_star);
    if (!(speed > 0.0) || body.inv_mass == 0.0) return;
    const Vec3d v_new = v_star * (implicit_drag_speed(speed, kappa, double(h)) / speed);
    w.F += (v_new - v_star) * (body.mass / double(h));
}

void add_rigid_grab(Wrench& w, const RigidBody& body, const RigidMotion& m, const Grab& grab, float h) {
    const Vec3d r = m.R * grab.point;
    const Vec3d p = m.x + r;
    // The mass the pull feels at that point: 1/m_eff = 1/m + |r|^2 J^-1 (bounded by its trace),
    // so the default spring is as brisk, and as stable, as the particle's grab.
    const double inv_m_eff = body.inv_mass + dot(r, r) * m.J_inv.trace();
    const double m_eff = inv_m_eff > 0.0 ? 1.0 / inv_m_eff : 0.0;
    const double k = grab.stiffness > 0.0f ? double(grab.stiffness) : m_eff / (double(h) * h) * 0.5;
    const double c = 2.0 * std::sqrt(k * m_eff) * 0.5;
    const Vec3d u = m.v + cross(m.omega, r);
    add_force_at(w, m, p, (Vec3d(grab.target) - p) * k - u * c);
}

// ---------------------------------------------------------------------------------------------
// Between bodies
// ---------------------------------------------------------------------------------------------
Vec3d link_force(const Link& link, const Vec3d& p_a, const Vec3d& u_a, const Vec3d& p_b, const Vec3d& u_b) {
    const Vec3d d = p_b - p_a;
    const double l = length(d);
    if (l == 0.0) return {};
    const Vec3d d_hat = d / l;
    const Vec3d F_spring = d_hat * (link.k * (l - link.l0));             // Eq. 21
    const Vec3d F_damp = d_hat * (link.c * dot(u_b - u_a, d_hat));        // Eq. 22
    return F_spring + F_damp;
}

}  // namespace softbody

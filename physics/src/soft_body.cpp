// Listing 8's set-up: a particle at every distinct vertex of the mesh, placed in the world.
#include "physics/soft_body.h"

#include <algorithm>
#include <cmath>

namespace softbody {

namespace {

void copy(const Vec3Array& from, Vec3Array& to) {
    to.x = from.x;
    to.y = from.y;
    to.z = from.z;
}

}  // namespace

void build_particles(SoftBody& body) {
    const Params& p = body.params;
    const std::size_t n = body.mesh.positions.size();
    body.rest.resize(n);
    // Turn the mesh about x, then y, then z (files written y-up need 90 degrees about x).
    const float to_rad = 3.14159265358979f / 180.0f;
    const float cx = std::cos(p.rotation.x * to_rad), sx = std::sin(p.rotation.x * to_rad);
    const float cy = std::cos(p.rotation.y * to_rad), sy = std::sin(p.rotation.y * to_rad);
    const float cz = std::cos(p.rotation.z * to_rad), sz = std::sin(p.rotation.z * to_rad);
    auto rotate = [&](Vec3 v) {
        v = {v.x, cx * v.y - sx * v.z, sx * v.y + cx * v.z};
        v = {cy * v.x + sy * v.z, v.y, -sy * v.x + cy * v.z};
        return Vec3{cz * v.x - sz * v.y, sz * v.x + cz * v.y, v.z};
    };
    Vec3 centre;
    for (std::size_t i = 0; i < n; ++i) {
        // Listing 8: the mesh's own coordinates, lifted by init_height.
        const Vec3 q = rotate(body.mesh.positions[i]) * p.scale + Vec3{0.0f, 0.0f, p.init_height};
        body.rest.set(i, q);
        centre += q;
    }
    centre = centre / static_cast<float>(n);
    body.rest_radius = 0.0f;
    for (std::size_t i = 0; i < n; ++i) body.rest_radius = std::max(body.rest_radius, length(body.rest[i] - centre));

    copy(body.rest, body.x);
    body.v.resize(n);
    for (std::size_t i = 0; i < n; ++i) body.v.set(i, p.initial_velocity);
    body.mass = p.particle_mass;
    body.inv_mass.assign(n, 1.0f / body.mass);
    for (std::uint32_t vertex : p.pinned) {
        const std::uint32_t particle = body.mesh.vertex_to_particle[vertex];
        body.inv_mass[particle] = 0.0f;
        body.v.set(particle, {});
    }

    body.verlet_step.resize(n);
    body.verlet_h = 0.0f;  // Verlet's step is made from v at the first step
    copy(body.x, body.x_tick_prev);
    body.force.resize(n);
    for (auto& a : body.accel) a.resize(n);
    body.contacts.clear();
}

void set_pinned(SoftBody& body, std::uint32_t particle, bool pinned) {
    if (particle >= body.particle_count()) return;
    body.inv_mass[particle] = pinned ? 0.0f : 1.0f / body.mass;
    if (pinned) {
        body.v.set(particle, {});
        body.verlet_step.set(particle, {});
    }
}

void set_particle_mass(SoftBody& body, float mass) {
    if (mass == body.mass) return;
    body.mass = mass;
    for (float& w : body.inv_mass) {
        if (w != 0.0f) w = 1.0f / mass;
    }
}

}  // namespace softbody

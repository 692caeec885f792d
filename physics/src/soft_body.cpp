// Listing 8's set-up: a particle at every distinct vertex of the mesh, placed in the world.
#include "physics/soft_body.h"

#include <algorithm>
#include <cmath>

#include "physics/portable_math.h"

namespace softbody {

namespace {

// The turn that takes the file's up axis to +z (a right angle about x or y, a half turn for -z).
Vec3 turn_up(const std::string& up, Vec3 v) {
    if (up == "y") return {v.x, -v.z, v.y};    // +90 degrees about x: y -> z
    if (up == "-y") return {v.x, v.z, -v.y};   // -90 degrees about x: -y -> z
    if (up == "x") return {-v.z, v.y, v.x};    // -90 degrees about y: x -> z
    if (up == "-x") return {v.z, v.y, -v.x};   // +90 degrees about y: -x -> z
    if (up == "-z") return {v.x, -v.y, -v.z};  // half a turn about x
    return v;                                  // z: as written
}

// Chooses the simulated particles when the mesh has more than the budget; keeps the last
// choice while the budget is the same (a reset does not redo it).
void choose_particles(SoftBody& body) {
    const std::size_t full = body.mesh.particle_count();
    const std::size_t budget = body.def.max_particles == 0 ? kMaxParticles : std::size_t(body.def.max_particles);
    if (full <= budget) {
        body.reduced.reset();
        body.reduced_budget = 0;
        body.skin.clear();
        body.particle_mesh = Mesh{};
        return;
    }
    if (body.reduced && body.reduced_budget == budget) return;
    body.reduced = std::make_shared<const ReducedMesh>(reduce_mesh(body.mesh, budget));
    body.reduced_budget = budget;
    RawMesh raw;
    raw.positions = body.reduced->positions;
    for (std::uint32_t index : body.reduced->triangles) raw.triangle_corners.push_back(Corner{std::int32_t(index), -1, -1});
    body.particle_mesh = build_mesh(raw, body.mesh.source + " (simulated particles)");
}

}  // namespace

std::string particle_cap_note(const SoftBody& body) {
    if (body.def.max_particles != 0 || !body.reduced) return "";
    return body.mesh.source + ": max_particles=all is capped at " + std::to_string(kMaxParticles) + " particles: its " +
           std::to_string(body.mesh.particle_count()) + " distinct vertices run on " + std::to_string(body.particle_count()) +
           " (--set max_particles=N, 4 to " + std::to_string(kMaxParticles) + ", for fewer)";
}

void build_particles(SoftBody& body) {
    body.built = body.def;
    const SoftBodyDef& p = body.def;
    choose_particles(body);
    const std::vector<Vec3>& source = body.reduced ? body.reduced->positions : body.mesh.positions;
    const std::size_t n = source.size();
    body.rest.resize(n);
    // Automatic size: centred, the largest side of the bounding box 1 m.
    body.scale_used = p.scale;
    body.file_centre = {};
    if (p.scale == 0.0f) {
        Vec3 lo = body.mesh.positions.front(), hi = lo;
        for (const Vec3& q : body.mesh.positions) {
            lo = {std::min(lo.x, q.x), std::min(lo.y, q.y), std::min(lo.z, q.z)};
            hi = {std::max(hi.x, q.x), std::max(hi.y, q.y), std::max(hi.z, q.z)};
        }
        const float side = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
        body.file_centre = (lo + hi) * 0.5f;
        body.scale_used = side > 0.0f && std::isfinite(1.0f / side) ? 1.0f / side : 1.0f;
    }
    const bool centred = p.scale == 0.0f, turned = p.up_axis != "z";
    // Turn the mesh about x, then y, then z, after its up axis is turned to +z.
    const float to_rad = 3.14159265358979f / 180.0f;
    const float cx = portable::cos(p.rotation.x * to_rad), sx = portable::sin(p.rotation.x * to_rad);
    const float cy = portable::cos(p.rotation.y * to_rad), sy = portable::sin(p.rotation.y * to_rad);
    const float cz = portable::cos(p.rotation.z * to_rad), sz = portable::sin(p.rotation.z * to_rad);
    auto rotate = [&](Vec3 v) {
        if (centred) v = v - body.file_centre;
        if (turned) v = turn_up(p.up_axis, v);
        v = {v.x, cx * v.y - sx * v.z, sx * v.y + cx * v.z};
        v = {cy * v.x + sy * v.z, v.y, -sy * v.x + cy * v.z};
        return Vec3{cz * v.x - sz * v.y, sz * v.x + cz * v.y, v.z};
    };
    Vec3 centre;
    for (std::size_t i = 0; i < n; ++i) {
        // Listing 8: the mesh's own coordinates, lifted by init_height.
        const Vec3 q = rotate(source[i]) * body.scale_used + Vec3{0.0f, 0.0f, p.init_height};
        body.rest.set(i, q);
        centre += q;
    }
    centre = centre / static_cast<float>(n);
    // `position` puts the centre of mass (every particle weighs the same: the mean) there,
    // instead of the file's place lifted by init_height.
    if (p.position) {
        const Vec3 shift = *p.position - centre;
        for (std::size_t i = 0; i < n; ++i) body.rest.set(i, body.rest[i] + shift);
        centre = *p.position;
    }
    body.rest_radius = 0.0f;
    for (std::size_t i = 0; i < n; ++i) body.rest_radius = std::max(body.rest_radius, length(body.rest[i] - centre));
    // The bindings' offsets are in the file's units: in metres they scale with the body.
    body.skin.clear();
    if (body.reduced) {
        body.skin = body.reduced->bindings;
        for (SkinBinding& b : body.skin) b.offset *= body.scale_used;
    }

    body.x = body.rest;
    body.v.resize(n);
    // Every particle moves with the body: v = v_0 + w x (x - c), a rigid motion at the start.
    const bool spin = p.angular_velocity.x != 0.0f || p.angular_velocity.y != 0.0f || p.angular_velocity.z != 0.0f;
    for (std::size_t i = 0; i < n; ++i) {
        body.v.set(i, spin ? p.initial_velocity + cross(p.angular_velocity, body.rest[i] - centre) : p.initial_velocity);
    }
    body.inv_mass.assign(n, 1.0f);
    apply_body_keys(body);
    for (std::uint32_t vertex : p.pinned) {
        const std::uint32_t particle = particle_of_vertex(body, vertex);
        body.inv_mass[particle] = 0.0f;
        body.v.set(particle, {});
    }

    body.verlet_step.resize(n);
    body.verlet_h = 0.0f;  // Verlet's step is made from v at the first step
    body.x_tick_prev = body.x;
    body.force.resize(n);
    for (auto& a : body.accel) a.resize(n);
    body.contacts.clear();
}

std::uint32_t particle_of_vertex(const SoftBody& body, std::uint32_t vertex) {
    const std::uint32_t full = body.mesh.vertex_to_particle[vertex];
    if (!body.reduced) return full;
    if (body.reduced->full_to_reduced[full] != kNotSimulated) return body.reduced->full_to_reduced[full];
    const SkinBinding& b = body.reduced->bindings[full];
    const std::size_t most = std::size_t(std::max_element(b.weights.begin(), b.weights.end()) - b.weights.begin());
    return b.particles[most];
}

std::uint32_t vertex_of_particle(const SoftBody& body, std::uint32_t particle) {
    const std::uint32_t full = body.reduced ? body.reduced->reduced_to_full[particle] : particle;
    const auto& map = body.mesh.vertex_to_particle;
    return std::uint32_t(std::find(map.begin(), map.end(), full) - map.begin());
}

void set_pinned(SoftBody& body, std::uint32_t particle, bool pinned) {
    if (particle >= body.particle_count()) return;
    body.inv_mass[particle] = pinned ? 0.0f : 1.0f / body.mass;
    if (pinned) {
        body.v.set(particle, {});
        body.verlet_step.set(particle, {});
    }
}

void apply_body_keys(SoftBody& body) {
    const SoftBodyDef& p = body.def;
    // r = 1 (and every value exactly the key's) unless the body is reduced.
    const float r = body.reduced ? float(body.mesh.particle_count()) / float(body.particle_count()) : 1.0f;
    body.stiffness = body.reduced ? p.stiffness * r : p.stiffness;
    body.damping = body.reduced ? p.damping * r : p.damping;
    const float mass = body.reduced ? p.particle_mass * r : p.particle_mass;
    body.mass = mass;
    for (float& w : body.inv_mass) {
        if (w != 0.0f) w = 1.0f / mass;
    }
}

}  // namespace softbody

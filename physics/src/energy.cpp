// What the world reports about itself: energies (for plots, tests and divergence), the centre
// of mass, and a hash of the whole state (equal hashes: identical runs).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "physics/collide.h"
#include "physics/world.h"

namespace softbody {

Energy World::energy() {
    Energy e;
    for (SoftBody& body : soft_) {
        const std::size_t n = body.particle_count();
        for (std::size_t i = 0; i < n; ++i) {
            const Vec3 v = body.v[i], x = body.x[i];
            const double m = body.inv_mass[i] == 0.0f ? 0.0 : body.mass;  // pinned particles do not move
            e.kinetic += 0.5 * m * double(dot(v, v));
            e.gravity -= double(body.mass) * double(dot(settings_.gravity, x));
        }
        const PairInput in{body.x.x.data(), body.x.y.data(), body.x.z.data(), body.v.x.data(), body.v.y.data(),
                           body.v.z.data(), body.rest.x.data(), body.rest.y.data(), body.rest.z.data(), n,
                           body.stiffness, body.damping};
        e.elastic += reference_kernel_ ? elastic_energy_reference(in) : body.kernel->elastic_energy(in);
    }
    // Rigid bodies: 1/2 |P|^2 / m + 1/2 L . w, and -m (g . x). Fixed ones do not move.
    for (std::size_t b = 0; b < rigid_.size(); ++b) {
        if (rigid_[b].fixed) continue;
        const RigidMotion m = rigid_motion(b);
        const double rotational = 0.5 * dot(m.L, m.omega);
        e.kinetic += 0.5 * dot(m.P, m.v) + rotational;
        e.rotational += rotational;
        e.gravity -= rigid_[b].mass * dot(Vec3d(settings_.gravity), m.x);
    }
    // Links: 1/2 k (l - l0)^2.
    for (const Link& link : links_) {
        const double stretch = length(link_end_position(link.b) - link_end_position(link.a)) - link.l0;
        e.elastic += 0.5 * link.k * stretch * stretch;
    }
    return e;
}

Vec3d World::momentum() const {
    Vec3d P;
    for (const SoftBody& body : soft_) {
        for (std::size_t i = 0; i < body.particle_count(); ++i) {
            if (body.inv_mass[i] != 0.0f) P += Vec3d(body.v[i]) * double(body.mass);
        }
    }
    for (std::size_t b = 0; b < rigid_.size(); ++b) P += rigid_motion(b).P;
    return P;
}

Vec3d World::angular_momentum() const {
    Vec3d L;
    for (const SoftBody& body : soft_) {
        for (std::size_t i = 0; i < body.particle_count(); ++i) {
            if (body.inv_mass[i] != 0.0f) L += cross(Vec3d(body.x[i]), Vec3d(body.v[i]) * double(body.mass));
        }
    }
    for (std::size_t b = 0; b < rigid_.size(); ++b) {
        const RigidMotion m = rigid_motion(b);
        L += cross(m.x, m.P) + m.L;  // about the origin: the orbit of the centre of mass, and the spin
    }
    return L;
}

Vec3 World::center_of_mass(std::size_t soft_body) const {
    const SoftBody& body = soft_[soft_body];
    double x = 0.0, y = 0.0, z = 0.0;
    const std::size_t n = body.particle_count();
    for (std::size_t i = 0; i < n; ++i) {
        x += body.x.x[i];
        y += body.x.y[i];
        z += body.x.z[i];
    }
    return {float(x / double(n)), float(y / double(n)), float(z / double(n))};
}

Vec3 World::center_of_mass() const {
    // Every particle and every moving rigid body, by mass (the origin when nothing moves).
    Vec3d sum;
    double mass = 0.0;
    for (std::size_t b = 0; b < soft_.size(); ++b) {
        const double m = double(soft_[b].mass) * double(soft_[b].particle_count());
        sum += Vec3d(center_of_mass(b)) * m;
        mass += m;
    }
    for (std::size_t b = 0; b < rigid_.size(); ++b) {
        if (rigid_[b].fixed) continue;
        sum += rigid_motion(b).x * rigid_[b].mass;
        mass += rigid_[b].mass;
    }
    return mass > 0.0 ? to_float(sum / mass) : Vec3{};
}

// The lowest point of any body: a soft body's lowest particle, a rigid body's lowest point of
// its collision shape as it is now (collide.h's lowest_z), fixed bodies included. A scene at
// rest on the ground reports the ground's height, less what the contacts let bodies sink.
float World::min_z() const {
    double lowest = std::numeric_limits<double>::infinity();
    for (const SoftBody& body : soft_) {
        for (float z : body.x.z) lowest = std::min(lowest, double(z));
    }
    for (std::size_t b = 0; b < rigid_.size(); ++b) {
        lowest = std::min(lowest, lowest_z(shapes_[b], pose_of(y_.data() + b * rigid::kStateSize)));
    }
    return std::isfinite(lowest) ? float(lowest) : 0.0f;  // 0 for a world without bodies
}

std::uint64_t World::state_hash() const {
    std::uint64_t hash = 1469598103934665603ull;
    auto mix = [&](const FloatArray& values) {
        for (float value : values) {
            std::uint32_t bits;
            std::memcpy(&bits, &value, sizeof bits);
            for (int b = 0; b < 4; ++b) hash = (hash ^ ((bits >> (8 * b)) & 0xFFu)) * 1099511628211ull;
        }
    };
    for (const SoftBody& body : soft_) {
        for (const auto* a : {&body.x, &body.v}) {
            mix(a->x);
            mix(a->y);
            mix(a->z);
        }
    }
    for (double value : y_) {
        std::uint64_t bits;
        std::memcpy(&bits, &value, sizeof bits);
        for (int b = 0; b < 8; ++b) hash = (hash ^ ((bits >> (8 * b)) & 0xFFu)) * 1099511628211ull;
    }
    return hash;
}

}  // namespace softbody

// What the world reports about itself: energies (for plots, tests and divergence), the centre
// of mass, and a hash of the whole state (equal hashes: identical runs).
#include <algorithm>
#include <cstring>

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
            e.gravity -= double(body.mass) * double(dot(params_.gravity, x));
        }
        const PairInput in{body.x.x.data(), body.x.y.data(), body.x.z.data(), body.v.x.data(), body.v.y.data(),
                           body.v.z.data(), body.rest.x.data(), body.rest.y.data(), body.rest.z.data(), n,
                           body.params.stiffness, body.params.damping};
        e.elastic += reference_kernel_ ? elastic_energy_reference(in) : body.kernel->elastic_energy(in);
    }
    return e;
}

Vec3 World::center_of_mass() const {
    double x = 0.0, y = 0.0, z = 0.0;
    const std::size_t n = particle_count();
    for (std::size_t i = 0; i < n; ++i) {
        x += body().x.x[i];
        y += body().x.y[i];
        z += body().x.z[i];
    }
    return {float(x / double(n)), float(y / double(n)), float(z / double(n))};
}

float World::min_z() const { return *std::min_element(body().x.z.begin(), body().x.z.end()); }

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
    return hash;
}

}  // namespace softbody

#include "soundness.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace softbody::app {

double lowest_point(const RigidBody& body, const Vec3d& x, const Mat3& R) {
    if (body.shape == ShapeKind::Sphere || !body.hull) return x.z - body.radius;
    // The hull's support point along -z, in body axes: R^T (0, 0, -1) is minus R's third row.
    const Vec3d down_in_body = -R.row(2);
    return x.z + dot(R.row(2), body.hull->support(down_in_body));
}

Soundness soundness(std::span<const RigidBody> defs, std::span<const BodyNow> now, std::optional<double> ground_height,
                    bool pyramid) {
    Soundness s;
    double deepest = 0.0, top_start = -std::numeric_limits<double>::infinity();
    std::size_t top = defs.size();
    for (std::size_t i = 0; i < defs.size() && i < now.size(); ++i) {
        const RigidBody& body = defs[i];
        if (body.fixed) continue;
        const BodyNow& b = now[i];
        ++s.bodies;
        if (ground_height) deepest = std::max(deepest, *ground_height - b.lowest_z);
        if (length(b.v) + length(b.omega) * body.bounding_radius > kMovingSpeed) ++s.moving;
        if (b.asleep) ++s.sleeping;
        const Mat3 J_world = b.R * body.J_body * b.R.transposed();  // Eq. 32's J, not its inverse
        s.kinetic_J += 0.5 * body.mass * dot(b.v, b.v) + 0.5 * dot(b.omega, J_world * b.omega);
        const double z0 = body.initial[rigid::X + 2];
        if (z0 > top_start) top_start = z0, top = i;
    }
    if (ground_height) s.penetration_m = deepest;
    if (pyramid && top < defs.size()) {
        const Vec3d x0{defs[top].initial[rigid::X], defs[top].initial[rigid::X + 1], defs[top].initial[rigid::X + 2]};
        s.top_moved_m = length(now[top].x - x0);
    }
    return s;
}

}  // namespace softbody::app

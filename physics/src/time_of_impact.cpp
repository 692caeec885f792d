// Poses between two ticks, and the time of impact by conservative advancement (collide.h).
#include <algorithm>
#include <cmath>

#include "physics/collide.h"
#include "physics/portable_math.h"

namespace softbody {

Pose pose_of(const double* state) {
    return {{state[rigid::X], state[rigid::X + 1], state[rigid::X + 2]},
            {state[rigid::Q], state[rigid::Q + 1], state[rigid::Q + 2], state[rigid::Q + 3]}};
}

Pose interpolate(const Pose& p0, const Pose& p1, double t) {
    return {p0.x + (p1.x - p0.x) * t, nlerp(p0.q, p1.q, t)};
}

namespace {

// The fastest rate, in radians per unit t, at which nlerp from q0 to q1 turns the body. With
// cos(alpha) = |q0 . q1| (alpha <= pi/2 on the shorter arc), the interpolated quaternion is
// beta(t) from q0 with tan(beta) = t sin(alpha) / (1 - t + t cos(alpha)); differentiating,
// beta' = sin(alpha) / ((1 - t)^2 + 2 t (1 - t) cos(alpha) + t^2), largest at t = 1/2, where
// the denominator is cos^2(alpha / 2): beta' <= 2 tan(alpha / 2). The body turns by 2 beta,
// about one fixed axis, so at most 4 tan(alpha / 2) per unit t (the whole turn 2 alpha when
// small; 4 against pi for a half turn).
double turn_rate_bound(const Quat& q0, const Quat& q1) {
    const double c = std::min(1.0, std::abs(dot(q0.normalized(), q1.normalized())));
    const double alpha = portable::acos(c);
    return 4.0 * portable::tan(0.5 * alpha);
}

}  // namespace

TimeOfImpact time_of_impact(const CollisionShape& a, const Pose& a0, const Pose& a1, const CollisionShape& b,
                            const Pose& b0, const Pose& b1, double tolerance, int max_iterations) {
    // How fast, per unit t, any point of a can close on any point of b: their relative linear
    // motion, plus each one's turning rate times its reach from its centre of mass (a sphere
    // turning about its centre changes nothing).
    const double linear = length((a1.x - a0.x) - (b1.x - b0.x));
    const double turn_a = a.is_sphere() ? 0.0 : turn_rate_bound(a0.q, a1.q) * a.bounding_radius;
    const double turn_b = b.is_sphere() ? 0.0 : turn_rate_bound(b0.q, b1.q) * b.bounding_radius;
    const double speed = linear + turn_a + turn_b;
    const auto at = [&](double t) { return separation_bound(a, interpolate(a0, a1, t), b, interpolate(b0, b1, t)); };
    TimeOfImpact result;
    double t = 0.0;
    for (int i = 1; i <= max_iterations; ++i) {
        const double d = at(t);
        result.t = t;
        result.separation = d;
        result.iterations = i;
        if (d <= tolerance) {
            result.outcome = TimeOfImpact::Outcome::Touching;
            return result;
        }
        // No point closes more than speed * dt in dt, so after (d - tolerance / 2) / speed
        // they are still at least tolerance / 2 apart: they have not touched.
        const double next = speed > 0.0 ? t + (d - 0.5 * tolerance) / speed : 2.0;
        if (!(next <= 1.0)) {
            result.outcome = TimeOfImpact::Outcome::Separate;
            result.t = 1.0;
            result.separation = at(1.0);
            return result;
        }
        t = next;
    }
    result.outcome = TimeOfImpact::Outcome::Stalled;  // t and separation: the last tried
    return result;
}

}  // namespace softbody

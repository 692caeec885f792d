// A quaternion q = w + i x + j y + k z in double: a rigid body's orientation (Eq. 35), kept of
// unit length by renormalisation (Listing 9).
#pragma once

#include <cmath>

#include "physics/mat3.h"
#include "physics/portable_math.h"
#include "physics/vec3.h"

namespace softbody {

struct Quat {
    double w = 1.0, x = 0.0, y = 0.0, z = 0.0;

    constexpr Quat() = default;
    constexpr Quat(double w_, double x_, double y_, double z_) : w(w_), x(x_), y(y_), z(z_) {}
    // The pure quaternion (0, v), as Eq. 35 writes the angular velocity.
    static constexpr Quat pure(const Vec3d& v) { return {0.0, v.x, v.y, v.z}; }
    // A turn of `angle` radians about the unit vector `axis`.
    static Quat from_axis_angle(const Vec3d& axis, double angle) {
        double s = 0.0, c = 0.0;
        portable::sin_cos(0.5 * angle, s, c);
        return {c, axis.x * s, axis.y * s, axis.z * s};
    }
    // Turns about x, then y, then z, by the given degrees (the soft body's `rotation` key).
    static Quat from_degrees_xyz(const Vec3d& degrees) {
        const double to_rad = 3.14159265358979323846 / 180.0;
        return from_axis_angle({0, 0, 1}, degrees.z * to_rad) * from_axis_angle({0, 1, 0}, degrees.y * to_rad) *
               from_axis_angle({1, 0, 0}, degrees.x * to_rad);
    }

    constexpr Quat operator+(const Quat& o) const { return {w + o.w, x + o.x, y + o.y, z + o.z}; }
    constexpr Quat operator-(const Quat& o) const { return {w - o.w, x - o.x, y - o.y, z - o.z}; }
    constexpr Quat operator*(double s) const { return {w * s, x * s, y * s, z * s}; }
    // The Hamilton product: (a * b) turns by b, then by a.
    constexpr Quat operator*(const Quat& o) const {
        return {w * o.w - x * o.x - y * o.y - z * o.z, w * o.x + x * o.w + y * o.z - z * o.y,
                w * o.y - x * o.z + y * o.w + z * o.x, w * o.z + x * o.y - y * o.x + z * o.w};
    }
    constexpr bool operator==(const Quat&) const = default;

    constexpr Quat conjugate() const { return {w, -x, -y, -z}; }
    constexpr double norm_squared() const { return w * w + x * x + y * y + z * z; }
    double norm() const { return std::sqrt(norm_squared()); }
    Quat normalized() const {
        const double n = norm();
        return n > 0.0 ? *this * (1.0 / n) : Quat{};
    }
    constexpr Vec3d vector() const { return {x, y, z}; }
    bool is_finite() const { return std::isfinite(w) && std::isfinite(x) && std::isfinite(y) && std::isfinite(z); }

    // The rotation matrix R (body to world) of a unit quaternion, by the usual formula, which
    // takes |q| = 1 for granted (Listing 9's ConvertToRotationMatrix). A quaternion that has
    // drifted from unit length gives a matrix that is no longer a rotation: it scales and
    // shears the body. That is why Listing 9 renormalises q every few steps.
    constexpr Mat3 to_matrix() const {
        const double xx = 2.0 * x * x, yy = 2.0 * y * y, zz = 2.0 * z * z;
        const double xy = 2.0 * x * y, xz = 2.0 * x * z, yz = 2.0 * y * z;
        const double wx = 2.0 * w * x, wy = 2.0 * w * y, wz = 2.0 * w * z;
        Mat3 r;
        r.m[0][0] = 1.0 - (yy + zz);
        r.m[0][1] = xy - wz;
        r.m[0][2] = xz + wy;
        r.m[1][0] = xy + wz;
        r.m[1][1] = 1.0 - (xx + zz);
        r.m[1][2] = yz - wx;
        r.m[2][0] = xz - wy;
        r.m[2][1] = yz + wx;
        r.m[2][2] = 1.0 - (xx + yy);
        return r;
    }
    // R v for a unit quaternion.
    constexpr Vec3d rotate(const Vec3d& v) const { return to_matrix() * v; }
};

constexpr Quat operator*(double s, const Quat& q) { return q * s; }
constexpr double dot(const Quat& a, const Quat& b) { return a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z; }

// Between a (t = 0) and b (t = 1) along the shorter arc, normalised: for drawing a body between
// two ticks.
inline Quat nlerp(const Quat& a, const Quat& b, double t) {
    const double sign = dot(a, b) < 0.0 ? -1.0 : 1.0;
    return (a * (1.0 - t) + b * (sign * t)).normalized();
}

}  // namespace softbody

// A 3x3 matrix in double, rows first: inertia tensors (Eq. 29-32) and rotation matrices.
#pragma once

#include <cmath>

#include "physics/vec3.h"

namespace softbody {

struct Mat3 {
    double m[3][3] = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};

    static constexpr Mat3 identity() { return diagonal({1.0, 1.0, 1.0}); }
    static constexpr Mat3 diagonal(const Vec3d& d) {
        Mat3 r;
        r.m[0][0] = d.x;
        r.m[1][1] = d.y;
        r.m[2][2] = d.z;
        return r;
    }
    // The matrix whose columns are a, b, c.
    static constexpr Mat3 from_columns(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
        Mat3 r;
        for (int i = 0; i < 3; ++i) {
            r.m[i][0] = a[i];
            r.m[i][1] = b[i];
            r.m[i][2] = c[i];
        }
        return r;
    }

    constexpr Vec3d row(int i) const { return {m[i][0], m[i][1], m[i][2]}; }
    constexpr Vec3d column(int j) const { return {m[0][j], m[1][j], m[2][j]}; }

    constexpr Mat3 operator+(const Mat3& o) const {
        Mat3 r;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) r.m[i][j] = m[i][j] + o.m[i][j];
        return r;
    }
    constexpr Mat3 operator-(const Mat3& o) const { return *this + o * -1.0; }
    constexpr Mat3 operator*(double s) const {
        Mat3 r;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) r.m[i][j] = m[i][j] * s;
        return r;
    }
    constexpr Mat3 operator*(const Mat3& o) const {
        Mat3 r;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) r.m[i][j] = m[i][0] * o.m[0][j] + m[i][1] * o.m[1][j] + m[i][2] * o.m[2][j];
        return r;
    }
    constexpr Vec3d operator*(const Vec3d& v) const {
        return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
    }
    constexpr bool operator==(const Mat3&) const = default;

    constexpr Mat3 transposed() const {
        Mat3 r;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) r.m[i][j] = m[j][i];
        return r;
    }
    constexpr double trace() const { return m[0][0] + m[1][1] + m[2][2]; }
    constexpr double determinant() const {
        return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
               m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    }
    // The inverse by cofactors; the zero matrix when the matrix is singular.
    constexpr Mat3 inverse() const {
        const double det = determinant();
        Mat3 r;
        if (det == 0.0) return r;
        const double s = 1.0 / det;
        r.m[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) * s;
        r.m[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) * s;
        r.m[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * s;
        r.m[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) * s;
        r.m[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * s;
        r.m[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) * s;
        r.m[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) * s;
        r.m[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) * s;
        r.m[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * s;
        return r;
    }
    bool is_finite() const {
        for (const auto& r : m)
            for (double v : r)
                if (!std::isfinite(v)) return false;
        return true;
    }
};

constexpr Mat3 operator*(double s, const Mat3& a) { return a * s; }

// a b^T
constexpr Mat3 outer(const Vec3d& a, const Vec3d& b) {
    Mat3 r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) r.m[i][j] = a[i] * b[j];
    return r;
}

// [a]x: the matrix with [a]x v = a x v.
constexpr Mat3 skew(const Vec3d& a) {
    Mat3 r;
    r.m[0][1] = -a.z;
    r.m[0][2] = a.y;
    r.m[1][0] = a.z;
    r.m[1][2] = -a.x;
    r.m[2][0] = -a.y;
    r.m[2][1] = a.x;
    return r;
}

}  // namespace softbody

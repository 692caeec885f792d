// A 3x3 matrix in double, rows first: inertia tensors (Eq. 29-32) and rotation matrices.
#pragma once

#include <cmath>
#include <utility>

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

// The eigenvalues of a symmetric matrix (ascending) and its eigenvectors as the columns of a
// rotation (cyclic Jacobi sweeps until the off-diagonal is rounding): for an inertia tensor,
// the principal moments and axes.
inline void symmetric_eigen(const Mat3& a, Vec3d& values, Mat3& vectors) {
    Mat3 A = a;
    Mat3 V = Mat3::identity();
    for (int sweep = 0; sweep < 32; ++sweep) {
        const double off = A.m[0][1] * A.m[0][1] + A.m[0][2] * A.m[0][2] + A.m[1][2] * A.m[1][2];
        const double scale = A.m[0][0] * A.m[0][0] + A.m[1][1] * A.m[1][1] + A.m[2][2] * A.m[2][2];
        if (!(off > 1e-30 * scale)) break;
        for (int p = 0; p < 2; ++p) {
            for (int q = p + 1; q < 3; ++q) {
                if (A.m[p][q] == 0.0) continue;
                // The rotation in the (p, q) plane that zeroes A_pq.
                const double theta = (A.m[q][q] - A.m[p][p]) / (2.0 * A.m[p][q]);
                const double t = (theta >= 0.0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
                const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
                Mat3 J = Mat3::identity();
                J.m[p][p] = c;
                J.m[q][q] = c;
                J.m[p][q] = s;
                J.m[q][p] = -s;
                A = J.transposed() * A * J;
                V = V * J;
            }
        }
    }
    int order[3] = {0, 1, 2};
    for (int i = 0; i < 3; ++i)
        for (int j = i + 1; j < 3; ++j)
            if (A.m[order[j]][order[j]] < A.m[order[i]][order[i]]) std::swap(order[i], order[j]);
    Mat3 sorted;
    for (int k = 0; k < 3; ++k) {
        values[k] = A.m[order[k]][order[k]];
        for (int r = 0; r < 3; ++r) sorted.m[r][k] = V.m[r][order[k]];
    }
    if (sorted.determinant() < 0.0) {
        for (int r = 0; r < 3; ++r) sorted.m[r][2] = -sorted.m[r][2];
    }
    vectors = sorted;
}

}  // namespace softbody

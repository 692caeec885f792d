// Volume, centre of mass and inertia tensor: Table 1's primitives in closed form, and closed
// triangle meshes by turning the volume integrals into sums over triangles.
#include "physics/mass_properties.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "physics/error.h"

namespace softbody {

namespace {

std::string nine_digits(double x) {
    std::ostringstream out;
    out.precision(9);
    out << x;
    return out.str();
}

void require_size(const char* what, double value) {
    if (!(value > 0.0) || !std::isfinite(value)) {
        throw InputError(std::string(what) + " must be a positive finite number, got " + nine_digits(value));
    }
}

// J about the centre of mass from J about another point o, when the centre lies at c from o
// (the parallel-axis theorem as a tensor): J_o = J_c + m (|c|^2 1 - c c^T).
Mat3 to_center(const Mat3& about_o, double mass, const Vec3d& c) {
    return about_o - (Mat3::identity() * dot(c, c) - outer(c, c)) * mass;
}

}  // namespace

// --- Table 1 ----------------------------------------------------------------------------------

MassProperties box_mass_properties(const Vec3d& size) {
    if (!(size.x > 0.0 && size.y > 0.0 && size.z > 0.0) || !is_finite(size)) {
        throw InputError("box size must be three positive finite numbers, got " + nine_digits(size.x) + " x " +
                         nine_digits(size.y) + " x " + nine_digits(size.z));
    }
    const double a = size.x, b = size.y, c = size.z;
    MassProperties out;
    out.volume = a * b * c;
    // J_xx = m (b^2 + c^2) / 12 and so on.
    out.inertia = Mat3::diagonal({b * b + c * c, a * a + c * c, a * a + b * b}) * (out.volume / 12.0);
    return out;
}

MassProperties sphere_mass_properties(double radius) {
    require_size("sphere radius", radius);
    const double r = radius;
    MassProperties out;
    out.volume = 4.0 / 3.0 * std::numbers::pi * r * r * r;
    out.inertia = Mat3::identity() * (0.4 * out.volume * r * r);  // 2/5 m r^2 about every axis
    return out;
}

MassProperties cylinder_mass_properties(double radius, double height) {
    require_size("cylinder radius", radius);
    require_size("cylinder height", height);
    const double r = radius, h = height;
    MassProperties out;
    out.volume = std::numbers::pi * r * r * h;
    // About its axis 1/2 m r^2; across it m (3 r^2 + h^2) / 12.
    const double across = out.volume * (3.0 * r * r + h * h) / 12.0;
    out.inertia = Mat3::diagonal({across, across, 0.5 * out.volume * r * r});
    return out;
}

// --- Closed triangle meshes -------------------------------------------------------------------
//
// Ten integrals over the solid give everything: 1, x, y, z, x^2, y^2, z^2, xy, yz, zx. The
// divergence theorem (integral over V of div F = integral over the surface of F . n) turns each
// into a surface integral, by choosing F with a single component whose derivative is the
// integrand:
//     int 1  = oint x n_x            int x = oint x^2/2 n_x       (y, z alike with n_y, n_z)
//     int x^2 = oint x^3/3 n_x       int xy = oint x^2 y/2 n_x
//     int yz = oint y^2 z/2 n_y      int zx = oint z^2 x/2 n_z
// On a triangle p0 p1 p2, write p = p0 + u (p1 - p0) + v (p2 - p0) over u, v >= 0, u + v <= 1;
// then n dA = d du dv with d = (p1 - p0) x (p2 - p0) (not normalised: its length is twice the
// area). In the barycentric weights l = (1 - u - v, u, v) a coordinate is s = sum l_i s_i, and
//     int int l0^a l1^b l2^c du dv = a! b! c! / (a + b + c + 2)!,
// which, summed over the monomials, gives for a coordinate s with corner values s0, s1, s2
//     int int s du dv     = f1 / 6,   f1 = s0 + s1 + s2
//     int int s^2 du dv   = f2 / 12,  f2 = s0^2 + s0 s1 + s1^2 + s2 f1     (every product of two)
//     int int s^3 du dv   = f3 / 20,  f3 = s0^3 + s0^2 s1 + s0 s1^2 + s1^3 + s2 f2   (of three)
//     int int s^2 t du dv = (t0 g0 + t1 g1 + t2 g2) / 60,  g_i = f2 + s_i (f1 + s_i)
// Each triangle adds d_x f1(x) / 6 to the volume, d_x f2(x) / 24 to int x, d_x f3(x) / 60 to
// int x^2, d_x (y . g(x)) / 120 to int xy, and so on; the constant divisors wait until the end.
// A triangle contributes in proportion to d, so a mesh facing inward gets every integral with
// the opposite sign, and flipping them all repairs it.
//
// The integrals are taken about a point inside the mesh's bounding box rather than the origin:
// about the origin, a body far from it has int x^2 ~ V |x|^2 nearly cancelling V |c|^2 in the
// parallel-axis step, and the tensor would lose digits in proportion.

namespace {

struct Subexpressions {
    double f1, f2, f3, g0, g1, g2;
};

Subexpressions subexpressions(double s0, double s1, double s2) {
    Subexpressions e{};
    const double t0 = s0 + s1;
    e.f1 = t0 + s2;
    const double t1 = s0 * s0;
    const double t2 = t1 + s1 * t0;  // s0^2 + s0 s1 + s1^2
    e.f2 = t2 + s2 * e.f1;
    e.f3 = s0 * t1 + s1 * t2 + s2 * e.f2;
    e.g0 = e.f2 + s0 * (e.f1 + s0);
    e.g1 = e.f2 + s1 * (e.f1 + s1);
    e.g2 = e.f2 + s2 * (e.f1 + s2);
    return e;
}

}  // namespace

MassProperties mesh_mass_properties(std::span<const Vec3d> vertices,
                                    std::span<const std::array<std::uint32_t, 3>> triangles) {
    const std::string who = "mesh mass properties: ";
    // The reference point: the centre of the bounding box of the corners in use.
    Vec3d lo{}, hi{};
    bool first = true;
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        for (const std::uint32_t v : triangles[t]) {
            if (v >= vertices.size()) {
                throw InputError(who + "triangle " + std::to_string(t) + " refers to vertex " + std::to_string(v) +
                                 ", but there are " + std::to_string(vertices.size()) + " vertices");
            }
            const Vec3d& p = vertices[v];
            if (!is_finite(p)) throw InputError(who + "vertex " + std::to_string(v) + " is not a finite point");
            if (first) {
                lo = hi = p;
                first = false;
            }
            for (int i = 0; i < 3; ++i) {
                lo[i] = std::min(lo[i], p[i]);
                hi[i] = std::max(hi[i], p[i]);
            }
        }
    }
    const Vec3d o = (lo + hi) * 0.5;
    const double diagonal = length(hi - lo);

    // Accumulated without the constant divisors: 6 V, 24 int x_i, 60 int x_i^2, 120 int x_i x_j.
    double volume6 = 0.0;
    Vec3d first24, second60, mixed120;  // mixed: xy, yz, zx
    for (const auto& tri : triangles) {
        const Vec3d p0 = vertices[tri[0]] - o, p1 = vertices[tri[1]] - o, p2 = vertices[tri[2]] - o;
        const Vec3d d = cross(p1 - p0, p2 - p0);
        const Subexpressions x = subexpressions(p0.x, p1.x, p2.x);
        const Subexpressions y = subexpressions(p0.y, p1.y, p2.y);
        const Subexpressions z = subexpressions(p0.z, p1.z, p2.z);
        volume6 += d.x * x.f1;
        first24 += Vec3d{d.x * x.f2, d.y * y.f2, d.z * z.f2};
        second60 += Vec3d{d.x * x.f3, d.y * y.f3, d.z * z.f3};
        mixed120 += Vec3d{d.x * (p0.y * x.g0 + p1.y * x.g1 + p2.y * x.g2),
                          d.y * (p0.z * y.g0 + p1.z * y.g1 + p2.z * y.g2),
                          d.z * (p0.x * z.g0 + p1.x * z.g1 + p2.x * z.g2)};
    }
    double volume = volume6 / 6.0;
    Vec3d first_moment = first24 / 24.0;
    Vec3d second_moment = second60 / 60.0;  // int x^2, int y^2, int z^2
    Vec3d products = mixed120 / 120.0;      // int xy, int yz, int zx
    // A mesh that faces inward: every integral with the opposite sign.
    if (volume < 0.0) {
        volume = -volume;
        first_moment = -first_moment;
        second_moment = -second_moment;
        products = -products;
    }
    // Rounding leaves a flat or empty mesh about 1e-16 diagonal^3 of volume; 1e-12 of the
    // bounding box's cube is far above that and far below any real solid.
    if (!(volume > 1e-12 * diagonal * diagonal * diagonal) || !std::isfinite(volume)) {
        throw InputError(who + "the mesh encloses no volume (" + std::to_string(triangles.size()) +
                         " triangles; is it closed?)");
    }

    MassProperties out;
    out.volume = volume;
    const Vec3d c = first_moment / volume;  // Eq. 20, from o
    out.center = o + c;
    // Eq. 29-31 about o: moments on the diagonal, minus the products off it.
    Mat3 about_o;
    about_o.m[0][0] = second_moment.y + second_moment.z;
    about_o.m[1][1] = second_moment.x + second_moment.z;
    about_o.m[2][2] = second_moment.x + second_moment.y;
    about_o.m[0][1] = about_o.m[1][0] = -products.x;
    about_o.m[1][2] = about_o.m[2][1] = -products.y;
    about_o.m[0][2] = about_o.m[2][0] = -products.z;
    out.inertia = to_center(about_o, volume, c);
    return out;
}

bool is_closed_oriented(std::span<const std::array<std::uint32_t, 3>> triangles) {
    if (triangles.empty()) return false;
    // Each directed edge once; then each one's reverse must be there too.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    edges.reserve(3 * triangles.size());
    for (const auto& t : triangles) {
        if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) return false;
        edges.emplace_back(t[0], t[1]);
        edges.emplace_back(t[1], t[2]);
        edges.emplace_back(t[2], t[0]);
    }
    std::sort(edges.begin(), edges.end());
    if (std::adjacent_find(edges.begin(), edges.end()) != edges.end()) return false;
    for (const auto& [a, b] : edges) {
        if (!std::binary_search(edges.begin(), edges.end(), std::pair{b, a})) return false;
    }
    return true;
}

}  // namespace softbody

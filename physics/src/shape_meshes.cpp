// Meshes of boxes, spheres, cylinders and hulls, made in code and welded like a loaded file.
#include "physics/shape_meshes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <mutex>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "physics/error.h"
#include "physics/portable_math.h"

namespace softbody {

namespace {

std::string six_digits(double x) {
    std::ostringstream out;
    out.precision(6);
    out << x;
    return out.str();
}

void require_mesh_size(const std::string& what, double value) {
    if (!(value > 0.0) || !std::isfinite(value)) {
        throw InputError(what + " must be a positive finite number, got " + six_digits(value));
    }
}

// Accumulates positions and triangles (position indices, optionally one normal per triangle).
struct Builder {
    RawMesh raw;

    std::int32_t vertex(const Vec3d& p) {
        raw.positions.push_back(to_float(p));
        return static_cast<std::int32_t>(raw.positions.size() - 1);
    }
    void triangle(std::int32_t a, std::int32_t b, std::int32_t c, std::int32_t normal = -1) {
        for (const std::int32_t v : {a, b, c}) raw.triangle_corners.push_back({v, normal, -1});
    }
};

}  // namespace

Mesh box_mesh(const Vec3d& size) {
    if (!(size.x > 0.0 && size.y > 0.0 && size.z > 0.0) || !is_finite(size)) {
        throw InputError("box size must be three positive finite numbers, got " + six_digits(size.x) + " x " +
                         six_digits(size.y) + " x " + six_digits(size.z));
    }
    Builder b;
    // Corner i has bit 0 for +x, bit 1 for +y, bit 2 for +z.
    for (int i = 0; i < 8; ++i) {
        b.vertex({(i & 1 ? 0.5 : -0.5) * size.x, (i & 2 ? 0.5 : -0.5) * size.y, (i & 4 ? 0.5 : -0.5) * size.z});
    }
    // The face at side s of axis a: with the next two axes e, f (cyclic, so e x f = a), the
    // corners (e, f) = (0,0), (1,0), (1,1), (0,1) go counter-clockwise seen from +a.
    for (int a = 0; a < 3; ++a) {
        const int e = (a + 1) % 3, f = (a + 2) % 3;
        for (int s = 0; s < 2; ++s) {
            std::array<std::int32_t, 4> quad{};
            const int steps[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
            for (int k = 0; k < 4; ++k) quad[k] = (s << a) | (steps[k][0] << e) | (steps[k][1] << f);
            if (s == 0) std::swap(quad[1], quad[3]);  // seen from -a: the other way round
            b.triangle(quad[0], quad[1], quad[2]);
            b.triangle(quad[0], quad[2], quad[3]);
        }
    }
    return build_mesh(b.raw, "box " + six_digits(size.x) + " x " + six_digits(size.y) + " x " + six_digits(size.z));
}

namespace {

void require_subdivisions(int subdivisions) {
    if (subdivisions < 0 || subdivisions > kMostSphereSubdivisions) {
        throw InputError("sphere subdivisions must be 0 to 5 (10 * 4^s + 2 vertices), got " + std::to_string(subdivisions));
    }
}

// The icosphere of radius 1 at one level: its vertices' directions, its faces, and it welded.
struct Icosphere {
    std::vector<Vec3d> directions;
    std::vector<std::array<std::uint32_t, 3>> faces;
    Mesh welded;  // radius 1; its particles are the directions in order (nothing welds)
};

Icosphere make_icosphere(int subdivisions) {
    // The icosahedron: the cyclic permutations of (0, +-1, +-phi), on the unit sphere.
    const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
    Icosphere ico;
    std::vector<Vec3d>& p = ico.directions;
    for (int axis = 0; axis < 3; ++axis) {
        for (const double s1 : {-1.0, 1.0}) {
            for (const double s2 : {-phi, phi}) {
                Vec3d v;
                v[(axis + 1) % 3] = s1;
                v[(axis + 2) % 3] = s2;
                p.push_back(normalize(v));
            }
        }
    }
    // Its faces: the triples of mutually adjacent corners (edge 2 before normalising, the
    // shortest distance between corners), turned to face outward.
    const double edge = length(p[0] - p[1]) < length(p[0] - p[2]) ? length(p[0] - p[1]) : length(p[0] - p[2]);
    auto adjacent = [&](std::size_t i, std::size_t j) { return std::abs(length(p[i] - p[j]) - edge) < 1e-9; };
    std::vector<std::array<std::uint32_t, 3>>& faces = ico.faces;
    for (std::uint32_t i = 0; i < 12; ++i) {
        for (std::uint32_t j = i + 1; j < 12; ++j) {
            for (std::uint32_t k = j + 1; k < 12; ++k) {
                if (!adjacent(i, j) || !adjacent(j, k) || !adjacent(i, k)) continue;
                if (dot(cross(p[j] - p[i], p[k] - p[i]), p[i]) > 0.0) {
                    faces.push_back({i, j, k});
                } else {
                    faces.push_back({i, k, j});
                }
            }
        }
    }
    // Each subdivision splits a triangle in four at its edges' midpoints, pushed out onto the
    // sphere; a midpoint is shared by the two triangles on its edge.
    for (int level = 0; level < subdivisions; ++level) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoint;
        auto middle = [&](std::uint32_t a, std::uint32_t c) {
            const auto key = std::minmax(a, c);
            auto [it, inserted] = midpoint.try_emplace(key, static_cast<std::uint32_t>(p.size()));
            if (inserted) p.push_back(normalize(p[a] + p[c]));
            return it->second;
        };
        std::vector<std::array<std::uint32_t, 3>> finer;
        for (const auto& [a, b, c] : faces) {
            const std::uint32_t ab = middle(a, b);
            const std::uint32_t bc = middle(b, c);
            const std::uint32_t ca = middle(c, a);
            finer.push_back({a, ab, ca});
            finer.push_back({b, bc, ab});
            finer.push_back({c, ca, bc});
            finer.push_back({ab, bc, ca});
        }
        faces = std::move(finer);
    }
    return ico;
}

RawMesh icosphere_raw(const Icosphere& ico, double radius) {
    Builder b;
    for (const Vec3d& v : ico.directions) b.vertex(v * radius);
    for (const auto& [i, j, k] : ico.faces) {
        b.triangle(static_cast<std::int32_t>(i), static_cast<std::int32_t>(j), static_cast<std::int32_t>(k));
    }
    return std::move(b.raw);
}

std::string sphere_source(double radius, int subdivisions) {
    return "sphere r " + six_digits(radius) + " (icosphere, " + std::to_string(subdivisions) + " subdivisions)";
}

// Each level made once, on first use, from any thread.
const Icosphere& icosphere(int subdivisions) {
    static std::array<std::once_flag, kMostSphereSubdivisions + 1> once;
    static std::array<Icosphere, kMostSphereSubdivisions + 1> spheres;
    const auto level = static_cast<std::size_t>(subdivisions);
    std::call_once(once[level], [&] {
        Icosphere ico = make_icosphere(subdivisions);
        ico.welded = build_mesh(icosphere_raw(ico, 1.0), sphere_source(1.0, subdivisions));
        spheres[level] = std::move(ico);
    });
    return spheres[level];
}

}  // namespace

RawMesh sphere_raw_mesh(double radius, int subdivisions) {
    require_mesh_size("sphere radius", radius);
    require_subdivisions(subdivisions);
    return icosphere_raw(icosphere(subdivisions), radius);
}

// The welded unit sphere with its positions scaled: welding the scaled vertices again would give
// the same particles, render vertices and normal slots (nothing welds at any radius, and a
// triangle's normal keeps its direction), as the tests check against build_mesh, at a tenth of
// the time. A pile of a thousand balls, each with its own radius, loads in a fraction of a second.
Mesh sphere_mesh(double radius, int subdivisions) {
    require_mesh_size("sphere radius", radius);
    require_subdivisions(subdivisions);
    const Icosphere& ico = icosphere(subdivisions);
    Mesh mesh = ico.welded;
    mesh.source = sphere_source(radius, subdivisions);
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) mesh.positions[i] = to_float(ico.directions[i] * radius);
    return mesh;
}

Mesh cylinder_mesh(double radius, double height, int segments) {
    require_mesh_size("cylinder radius", radius);
    require_mesh_size("cylinder height", height);
    constexpr int kMaxSegments = static_cast<int>(kMaxParticles / 2) - 1;  // 2 rings and 2 centres
    if (segments < 3 || segments > kMaxSegments) {
        throw InputError("cylinder segments must be 3 to " + std::to_string(kMaxSegments) + ", got " +
                         std::to_string(segments));
    }
    Builder b;
    const double half = 0.5 * height;
    // Corner k of the bottom ring is vertex k, of the top ring segments + k.
    for (const double z : {-half, half}) {
        for (int k = 0; k < segments; ++k) {
            const double angle = 2.0 * std::numbers::pi * k / segments;
            b.vertex({radius * portable::cos(angle), radius * portable::sin(angle), z});
        }
    }
    const std::int32_t bottom_center = b.vertex({0.0, 0.0, -half});
    const std::int32_t top_center = b.vertex({0.0, 0.0, half});
    for (std::int32_t k = 0; k < segments; ++k) {
        const std::int32_t next = (k + 1) % segments;
        const std::int32_t b0 = k, b1 = next, t0 = segments + k, t1 = segments + next;
        // The side: (ring tangent) x (up) points out.
        b.triangle(b0, b1, t1);
        b.triangle(b0, t1, t0);
        // The caps: counter-clockwise seen from above on top, from below at the bottom.
        b.triangle(top_center, t0, t1);
        b.triangle(bottom_center, b1, b0);
    }
    return build_mesh(b.raw, "cylinder r " + six_digits(radius) + " h " + six_digits(height) + " (" +
                                 std::to_string(segments) + " segments)");
}

Mesh hull_mesh(const ConvexHull& hull) {
    if (hull.vertices.empty() || hull.faces.empty()) throw InputError("hull mesh: the hull is empty");
    Builder b;
    for (const Vec3d& v : hull.vertices) b.vertex(v);
    // One file normal per face, shared by its triangles: build_mesh then gives each face its own
    // normal slots, so the hull is drawn flat, with every edge hard.
    for (const ConvexHull::Face& face : hull.faces) {
        b.raw.normals.push_back(to_float(face.normal));
        const auto normal = static_cast<std::int32_t>(b.raw.normals.size() - 1);
        for (std::size_t k = 1; k + 1 < face.vertices.size(); ++k) {
            b.triangle(static_cast<std::int32_t>(face.vertices[0]), static_cast<std::int32_t>(face.vertices[k]),
                       static_cast<std::int32_t>(face.vertices[k + 1]), normal);
        }
    }
    return build_mesh(b.raw, "convex hull (" + std::to_string(hull.vertices.size()) + " vertices, " +
                                 std::to_string(hull.faces.size()) + " faces)");
}

}  // namespace softbody

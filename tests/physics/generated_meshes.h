// Meshes the tests make themselves, as OBJ or OFF text: bodies like those users bring (a tall
// figure in millimetres or in kilometres, written y-up or z-up, with normal indices that name
// nothing) and bodies above a particle budget (a 12,000-vertex torus). Every size is known
// exactly, and no file of the repository is needed.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

namespace softbody::test {

enum class UpAxis { Y, Z };

// A polygon mesh in memory: positions and faces (0-based indices, 3 or 4 corners each).
struct PolyMesh {
    std::vector<std::array<double, 3>> positions;
    std::vector<std::vector<std::uint32_t>> faces;
};

// A surface of revolution about the up axis through the origin: `profile` holds (radius,
// height) pairs from bottom to top, and a radius of 0 is a pole (one vertex). `segments`
// vertices around each ring; faces wind counter-clockwise seen from outside.
inline PolyMesh revolve(const std::vector<std::array<double, 2>>& profile, int segments, UpAxis up) {
    constexpr double kTwoPi = 6.28318530717958647692;
    PolyMesh mesh;
    std::vector<std::vector<std::uint32_t>> rings;  // the vertices of each profile point
    for (const auto& [r, h] : profile) {
        std::vector<std::uint32_t> ring;
        const int count = r == 0.0 ? 1 : segments;
        for (int s = 0; s < count; ++s) {
            const double phi = kTwoPi * s / segments;
            const double a = r * std::cos(phi), b = r * std::sin(phi);
            ring.push_back(static_cast<std::uint32_t>(mesh.positions.size()));
            mesh.positions.push_back(up == UpAxis::Z ? std::array<double, 3>{a, b, h} : std::array<double, 3>{a, h, -b});
        }
        rings.push_back(ring);
    }
    for (std::size_t k = 0; k + 1 < rings.size(); ++k) {
        const auto &lower = rings[k], &upper = rings[k + 1];
        for (int s = 0; s < segments; ++s) {
            const int t = (s + 1) % segments;
            if (lower.size() == 1) {
                mesh.faces.push_back({lower[0], upper[t], upper[s]});
            } else if (upper.size() == 1) {
                mesh.faces.push_back({lower[s], lower[t], upper[0]});
            } else {
                mesh.faces.push_back({lower[s], lower[t], upper[t], upper[s]});
            }
        }
    }
    return mesh;
}

// A capsule standing on the origin: a cylinder of `radius` with hemispherical caps, `height`
// tall in all (height > 2 radius), its axis along `up`. A tall one reads as a standing figure:
// its longest extent is its up axis.
inline PolyMesh capsule(double radius, double height, UpAxis up, int segments = 24, int rings = 8) {
    constexpr double kHalfPi = 1.57079632679489661923;
    std::vector<std::array<double, 2>> profile = {{0.0, 0.0}};
    for (int i = 1; i <= rings; ++i) {  // the bottom cap, up to its equator
        const double theta = -kHalfPi + kHalfPi * i / rings;
        profile.push_back({radius * std::cos(theta), radius + radius * std::sin(theta)});
    }
    for (int i = 1; i <= rings; ++i) profile.push_back({radius, radius + (height - 2 * radius) * i / rings});
    for (int i = 1; i < rings; ++i) {  // the top cap, from its equator
        const double theta = kHalfPi * i / rings;
        profile.push_back({radius * std::cos(theta), height - radius + radius * std::sin(theta)});
    }
    profile.push_back({0.0, height});
    return revolve(profile, segments, up);
}

// A torus about the z axis: the tube's centre `major` from the axis, the tube `minor` thick;
// segments x sides vertices, every one distinct.
inline PolyMesh torus(double major, double minor, int segments, int sides) {
    constexpr double kTwoPi = 6.28318530717958647692;
    PolyMesh mesh;
    for (int s = 0; s < segments; ++s) {
        const double phi = kTwoPi * s / segments;
        for (int k = 0; k < sides; ++k) {
            const double theta = kTwoPi * k / sides;
            const double r = major + minor * std::cos(theta);
            mesh.positions.push_back({r * std::cos(phi), r * std::sin(phi), minor * std::sin(theta)});
        }
    }
    auto at = [&](int s, int k) { return static_cast<std::uint32_t>((s % segments) * sides + k % sides); };
    for (int s = 0; s < segments; ++s) {
        for (int k = 0; k < sides; ++k) mesh.faces.push_back({at(s, k), at(s + 1, k), at(s + 1, k + 1), at(s, k + 1)});
    }
    return mesh;
}

// Every position times `factor` (metres to millimetres: 1000; to kilometres: 0.001).
inline PolyMesh scaled(PolyMesh mesh, double factor) {
    for (auto& p : mesh.positions) {
        for (double& c : p) c *= factor;
    }
    return mesh;
}

struct ObjStyle {
    // Each face corner names a normal ("f 1//7 ..."), though the file defines none: as files cut
    // out of a larger one, or written by exporters that dropped the normals, have it.
    bool dangling_normals = false;
};

// As OBJ text: "v" lines with 9 significant digits (float's round trip), then "f" lines.
inline std::string to_obj(const PolyMesh& mesh, ObjStyle style = {}) {
    std::ostringstream out;
    out.precision(9);
    out << "# generated by the tests\n";
    for (const auto& p : mesh.positions) out << "v " << p[0] << " " << p[1] << " " << p[2] << "\n";
    std::size_t corner = 0;
    for (const auto& face : mesh.faces) {
        out << "f";
        for (std::uint32_t v : face) {
            out << " " << v + 1;
            if (style.dangling_normals) out << "//" << ++corner;
        }
        out << "\n";
    }
    return out.str();
}

// As OFF text.
inline std::string to_off(const PolyMesh& mesh) {
    std::ostringstream out;
    out.precision(9);
    out << "OFF\n" << mesh.positions.size() << " " << mesh.faces.size() << " 0\n";
    for (const auto& p : mesh.positions) out << p[0] << " " << p[1] << " " << p[2] << "\n";
    for (const auto& face : mesh.faces) {
        out << face.size();
        for (std::uint32_t v : face) out << " " << v;
        out << "\n";
    }
    return out.str();
}

}  // namespace softbody::test

// From a file's vertices to particles: weld coincident positions, then build the render
// vertices (with their normal slots) that map back onto the particles.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <unordered_map>
#include <vector>

#include "physics/error.h"
#include "physics/mesh.h"

namespace softbody {

namespace {

struct CellKey {
    std::int64_t x, y, z;
    bool operator==(const CellKey&) const = default;
};
struct CellHash {
    std::size_t operator()(const CellKey& k) const {
        std::uint64_t h = 1469598103934665603ull;
        for (std::int64_t v : {k.x, k.y, k.z}) h = (h ^ static_cast<std::uint64_t>(v)) * 1099511628211ull;
        return static_cast<std::size_t>(h);
    }
};

// Corners whose smooth normals are averaged together share a slot. With file normals, corners
// whose file normals agree (within about 1 degree) at one particle share one; without, a face
// within 40 degrees of the particle's average normal is smooth there and a sharper one keeps
// its own slot, so a cube keeps its edges and a sphere stays round.
constexpr float kSameNormalCos = 0.9998f;  // about 1 degree
constexpr float kCreaseCos = 0.766f;       // 40 degrees
constexpr float kSharpClusterCos = 0.94f;  // 20 degrees

Vec3 normalized(const Vec3& v) {
    const float l = length(v);
    if (l > 0.0f && std::isfinite(l)) return v / l;
    // |v|^2 overflowed or underflowed in float (a vector near 1e19 or 1e-19 long): in double.
    const double ld = std::sqrt(double(v.x) * v.x + double(v.y) * v.y + double(v.z) * v.z);
    if (!(ld > 0.0) || !std::isfinite(ld)) return Vec3{};
    return {float(v.x / ld), float(v.y / ld), float(v.z / ld)};
}

double distance(const Vec3& a, const Vec3& b) {
    const double dx = double(a.x) - b.x, dy = double(a.y) - b.y, dz = double(a.z) - b.z;
    return std::sqrt(dx * dx + dy * dy + dz * dz);
}

}  // namespace

Mesh build_mesh(const RawMesh& raw, const std::string& source) {
    if (raw.positions.empty()) throw InputError(source + ": the mesh has no vertices");
    Mesh mesh;
    mesh.source = source;
    mesh.warnings = raw.warnings;

    // --- Weld: one particle per distinct position -------------------------------------------
    Vec3 lo = raw.positions[0], hi = raw.positions[0];
    for (const Vec3& p : raw.positions) {
        if (!is_finite(p)) throw InputError(source + ": a vertex coordinate is not a finite number");
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    const double diagonal = distance(hi, lo);  // in double: hi - lo overflows float near +-3e38
    const double eps = diagonal > 0.0 ? 1e-6 * diagonal : 1.0;
    std::unordered_map<CellKey, std::vector<std::uint32_t>, CellHash> grid;
    mesh.vertex_to_particle.resize(raw.positions.size());
    for (std::size_t v = 0; v < raw.positions.size(); ++v) {
        const Vec3& p = raw.positions[v];
        // In double: p - lo never overflows there (in float it can, near +-3e38), and the
        // cell index stays within [0, 1e6].
        const CellKey cell{static_cast<std::int64_t>(std::floor((double(p.x) - lo.x) / eps)),
                           static_cast<std::int64_t>(std::floor((double(p.y) - lo.y) / eps)),
                           static_cast<std::int64_t>(std::floor((double(p.z) - lo.z) / eps))};
        std::int64_t found = -1;
        for (std::int64_t dx = -1; dx <= 1 && found < 0; ++dx) {
            for (std::int64_t dy = -1; dy <= 1 && found < 0; ++dy) {
                for (std::int64_t dz = -1; dz <= 1 && found < 0; ++dz) {
                    auto it = grid.find({cell.x + dx, cell.y + dy, cell.z + dz});
                    if (it == grid.end()) continue;
                    for (std::uint32_t particle : it->second) {
                        if (distance(mesh.positions[particle], p) <= eps) {
                            found = particle;
                            break;
                        }
                    }
                }
            }
        }
        if (found < 0) {
            found = static_cast<std::int64_t>(mesh.positions.size());
            if (mesh.positions.size() >= kMaxMeshParticles) {
                throw InputError(source + ": more than " + std::to_string(kMaxMeshParticles) +
                                 " distinct vertices; too many to load: use a smaller or decimated mesh");
            }
            mesh.positions.push_back(p);
            grid[cell].push_back(static_cast<std::uint32_t>(found));
        }
        mesh.vertex_to_particle[v] = static_cast<std::uint32_t>(found);
    }

    // --- Triangles on particles, dropping the ones that collapsed --------------------------
    struct Triangle {
        Corner corner[3];
        std::uint32_t particle[3];
        Vec3 normal;  // area-weighted, rest pose
    };
    // The normal is the cross product of two edges, about diagonal^2 long: in float that
    // overflows for meshes about 1e19 across and vanishes for ones about 1e-19 across. Outside
    // everyday sizes the edges are measured in diagonals instead (same directions, same
    // relative weights).
    const bool rescale = diagonal > 1e6 || diagonal < 1e-3;
    std::vector<Triangle> triangles;
    triangles.reserve(raw.triangle_corners.size() / 3);
    for (std::size_t t = 0; t + 2 < raw.triangle_corners.size(); t += 3) {
        Triangle tri{};
        for (int c = 0; c < 3; ++c) {
            tri.corner[c] = raw.triangle_corners[t + static_cast<std::size_t>(c)];
            const auto index = tri.corner[c].position;
            if (index < 0 || static_cast<std::size_t>(index) >= raw.positions.size()) {
                throw InputError(source + ": a face refers to a vertex that does not exist");
            }
            tri.particle[c] = mesh.vertex_to_particle[static_cast<std::size_t>(index)];
        }
        if (tri.particle[0] == tri.particle[1] || tri.particle[1] == tri.particle[2] ||
            tri.particle[0] == tri.particle[2]) {
            continue;
        }
        const Vec3& a = mesh.positions[tri.particle[0]];
        const Vec3& b = mesh.positions[tri.particle[1]];
        const Vec3& c = mesh.positions[tri.particle[2]];
        if (rescale) {
            const double ux = (double(b.x) - a.x) / diagonal, uy = (double(b.y) - a.y) / diagonal,
                         uz = (double(b.z) - a.z) / diagonal;
            const double vx = (double(c.x) - a.x) / diagonal, vy = (double(c.y) - a.y) / diagonal,
                         vz = (double(c.z) - a.z) / diagonal;
            tri.normal = {float(uy * vz - uz * vy), float(uz * vx - ux * vz), float(ux * vy - uy * vx)};
        } else {
            tri.normal = cross(b - a, c - a);
        }
        triangles.push_back(tri);
    }

    // --- Normal slots ------------------------------------------------------------------------
    std::vector<Vec3> average(mesh.positions.size());
    for (const Triangle& tri : triangles) {
        for (std::uint32_t p : tri.particle) average[p] += tri.normal;
    }
    struct Slot {
        Vec3 direction;
        std::uint32_t id;
    };
    std::vector<std::vector<Slot>> slots_at(mesh.positions.size());
    std::vector<std::int64_t> smooth_slot(mesh.positions.size(), -1);
    std::uint32_t slot_count = 0;
    auto slot_for = [&](std::uint32_t particle, const Corner& corner, const Vec3& face_normal) -> std::uint32_t {
        const bool has_file_normal = corner.normal >= 0 && static_cast<std::size_t>(corner.normal) < raw.normals.size() &&
                                     length(raw.normals[static_cast<std::size_t>(corner.normal)]) > 0.0f;
        Vec3 direction;
        float match_cos = kSameNormalCos;
        if (has_file_normal) {
            direction = normalized(raw.normals[static_cast<std::size_t>(corner.normal)]);
        } else {
            direction = normalized(face_normal);
            if (dot(direction, normalized(average[particle])) >= kCreaseCos) {
                if (smooth_slot[particle] < 0) smooth_slot[particle] = slot_count++;
                return static_cast<std::uint32_t>(smooth_slot[particle]);
            }
            match_cos = kSharpClusterCos;
        }
        for (const Slot& slot : slots_at[particle]) {
            if (dot(slot.direction, direction) >= match_cos) return slot.id;
        }
        slots_at[particle].push_back({direction, slot_count});
        return slot_count++;
    };

    // --- Render vertices: one per distinct (particle, normal slot, uv) ---------------------
    std::map<std::tuple<std::uint32_t, std::uint32_t, std::int32_t>, std::uint32_t> render_index;
    mesh.has_uvs = !raw.uvs.empty();
    mesh.triangles.reserve(triangles.size() * 3);
    for (const Triangle& tri : triangles) {
        for (int c = 0; c < 3; ++c) {
            const std::uint32_t slot = slot_for(tri.particle[c], tri.corner[c], tri.normal);
            const auto key = std::make_tuple(tri.particle[c], slot, tri.corner[c].uv);
            auto [it, inserted] = render_index.try_emplace(key, static_cast<std::uint32_t>(mesh.render_vertices.size()));
            if (inserted) {
                RenderVertex vertex;
                vertex.particle = tri.particle[c];
                vertex.normal_slot = slot;
                if (tri.corner[c].uv >= 0 && static_cast<std::size_t>(tri.corner[c].uv) < raw.uvs.size()) {
                    vertex.uv = raw.uvs[static_cast<std::size_t>(tri.corner[c].uv)];
                }
                mesh.render_vertices.push_back(vertex);
            }
            mesh.triangles.push_back(it->second);
        }
    }
    mesh.normal_slot_count = slot_count;
    return mesh;
}

std::vector<std::array<std::uint32_t, 3>> particle_triangles(const Mesh& mesh) {
    std::vector<std::array<std::uint32_t, 3>> out;
    out.reserve(mesh.triangle_count());
    for (std::size_t k = 0; k + 2 < mesh.triangles.size(); k += 3) {
        out.push_back({mesh.render_vertices[mesh.triangles[k]].particle, mesh.render_vertices[mesh.triangles[k + 1]].particle,
                       mesh.render_vertices[mesh.triangles[k + 2]].particle});
    }
    return out;
}

}  // namespace softbody

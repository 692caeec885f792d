// A particle budget by reduction: above a budget of particles, the simulation runs on a subset
// of the mesh's particles, and every full-resolution particle follows three simulated ones
// (skinning), so the full mesh is still what is drawn.
//
// All pairs cost N(N-1)/2 springs a force evaluation: a 36,000-vertex scan cannot run, but its
// shape carried by a few thousand particles spread over it can, and the scan drawn on top of
// them looks like the scan. mesh_reduce.cpp says how the particles are chosen and why.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "physics/mesh.h"
#include "physics/vec3.h"

namespace softbody {

// How one full-resolution particle follows three simulated ones: the point at barycentric
// weights on their triangle, plus `offset` along that triangle's unit normal (which turns and
// stretches with the body). Weights may fall outside [0, 1] (a point near, not on, the triangle).
struct SkinBinding {
    std::array<std::uint32_t, 3> particles{};  // indices into the reduced particles
    std::array<float, 3> weights{};            // sum to 1
    float offset = 0.0f;                       // m (mesh units), along normalize(cross(p1 - p0, p2 - p0))
    bool operator==(const SkinBinding&) const = default;
};

inline constexpr std::uint32_t kNotSimulated = std::numeric_limits<std::uint32_t>::max();

struct ReducedMesh {
    std::vector<Vec3> positions;                 // the simulated particles, a subset of the full mesh's positions
    std::vector<std::uint32_t> full_to_reduced;  // for each full particle kept as is: its reduced index, else kNotSimulated
    std::vector<std::uint32_t> reduced_to_full;  // for each simulated particle: the full particle it is
    std::vector<SkinBinding> bindings;           // one per full-resolution particle (kept ones bind to themselves exactly)
    // The triangulation of the simulated particles that the bindings of a surface's dropped
    // vertices use (3 reduced indices each; the full mesh's own triangles below the budget).
    // Empty for a point cloud.
    std::vector<std::uint32_t> triangles;

    std::size_t particle_count() const { return positions.size(); }
    bool operator==(const ReducedMesh&) const = default;
};

// The fewest particles a reduction keeps: a tetrahedron, the least that holds a 3-D shape.
inline constexpr std::size_t kMinReducedParticles = 4;

// Chooses at most `max_particles` particles from `full` (a welded Mesh; it may be a point cloud
// with no triangles) and binds every full particle to them. At or below the budget nothing
// changes: every particle is kept, in order, and binds to itself. Deterministic: the same input
// gives the same output (no threads, no randomness, no hash-order dependence). Throws
// InputError when max_particles < kMinReducedParticles and the mesh has more particles.
ReducedMesh reduce_mesh(const Mesh& full, std::size_t max_particles);

// The full-resolution positions from the simulated ones (header-inline, so the renderer can use
// it without linking the physics library): out[i] = sum_k w_k x[p_k] + offset * n, with n the
// unit normal of the binding's triangle as it is now. A kept particle (weights 1, 0, 0 on
// itself, offset 0) is copied exactly. x, y, z hold the reduced particles; out_* one entry per
// binding.
inline void apply_skinning(std::span<const SkinBinding> bindings, const float* x, const float* y, const float* z,
                           float* out_x, float* out_y, float* out_z) {
    for (std::size_t i = 0; i < bindings.size(); ++i) {
        const SkinBinding& b = bindings[i];
        const std::uint32_t p0 = b.particles[0], p1 = b.particles[1], p2 = b.particles[2];
        if (b.weights[1] == 0.0f && b.weights[2] == 0.0f && b.offset == 0.0f) {
            out_x[i] = x[p0];
            out_y[i] = y[p0];
            out_z[i] = z[p0];
            continue;
        }
        float px = b.weights[0] * x[p0] + b.weights[1] * x[p1] + b.weights[2] * x[p2];
        float py = b.weights[0] * y[p0] + b.weights[1] * y[p1] + b.weights[2] * y[p2];
        float pz = b.weights[0] * z[p0] + b.weights[1] * z[p1] + b.weights[2] * z[p2];
        if (b.offset != 0.0f) {
            const float ux = x[p1] - x[p0], uy = y[p1] - y[p0], uz = z[p1] - z[p0];
            const float vx = x[p2] - x[p0], vy = y[p2] - y[p0], vz = z[p2] - z[p0];
            const float nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
            const float length = std::sqrt(nx * nx + ny * ny + nz * nz);
            if (length > 0.0f) {  // a triangle crushed flat has no normal: the point stays on it
                const float s = b.offset / length;
                px += s * nx;
                py += s * ny;
                pz += s * nz;
            }
        }
        out_x[i] = px;
        out_y[i] = py;
        out_z[i] = pz;
    }
}

}  // namespace softbody

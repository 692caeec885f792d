// The overlays as lists of lines and spheres, built on the CPU each frame from the body's
// state. Internal to the renderer (tests may use it: it has no GL).
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "render/deform.h"
#include "render/frame.h"

namespace softbody::render {

struct LineInstance {
    glm::vec3 from;
    glm::vec3 to;
    glm::vec4 color;  // sRGB and opacity
    float width;      // pixels
};
static_assert(sizeof(LineInstance) == 44);

struct SphereInstance {
    glm::vec3 centre;
    float radius;     // m
    glm::vec4 color;  // sRGB and opacity
};
static_assert(sizeof(SphereInstance) == 32);

// Shape of the body this frame, for framing, shadows and marker sizes.
struct BodyShape {
    glm::vec3 centre_of_mass{0.0f};  // mean of the particles (they share one mass)
    glm::vec3 low{0.0f}, high{0.0f}; // bounding box
    float radius = 0.0f;             // largest distance from the centre of mass
    float rest_radius = 0.0f;        // the same at rest (marker sizes stay put), else radius
};
BodyShape measure_body(std::span<const glm::vec3> particles, const Vec3Span& rest);

// A fixed, readable sample of the every-pair springs. While there are at most `budget` pairs,
// all of them. Otherwise the springs along the surface (the mesh's triangle edges: they draw
// the body's shape, up to kMaxSurfaceSprings of them) plus `budget` pairs drawn by a fixed
// pseudo-random sequence (most of them cross the body, as the every-pair network does).
struct SpringSample {
    std::uint32_t i, j;
    bool surface;
};
inline constexpr std::size_t kMaxSurfaceSprings = 3000;
std::vector<SpringSample> sample_springs(const Mesh& mesh, std::size_t budget);

struct OverlayGeometry {
    std::vector<LineInstance> lines;          // depth tested
    std::vector<SphereInstance> spheres;      // depth tested
    std::vector<LineInstance> lines_on_top;   // drawn over everything
    std::vector<SphereInstance> spheres_on_top;
};

class OverlayBuilder {
public:
    // `surface`: the streamed vertices (positions and recomputed normals), empty when the body
    // has no surface this frame.
    void build(const Frame& frame, std::span<const glm::vec3> particles, std::span<const SurfaceVertex> surface,
               const BodyShape& shape, OverlayGeometry& out);

private:
    const Mesh* spring_mesh_ = nullptr;
    std::size_t spring_mesh_particles_ = 0, spring_mesh_triangles_ = 0, spring_budget_ = 0;
    std::vector<SpringSample> springs_;
    const Mesh* edge_mesh_ = nullptr;
    std::size_t edge_mesh_triangles_ = 0;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges_;  // the surface's edges, for wireframe
};

}  // namespace softbody::render

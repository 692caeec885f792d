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

// A soft body as drawn this frame: its particles, its streamed vertices (positions and
// recomputed normals; empty when it has no surface this frame) and its shape.
struct SoftBodyDrawn {
    std::span<const glm::vec3> particles;
    std::span<const SurfaceVertex> surface;
    BodyShape shape;
};

class OverlayBuilder {
public:
    // `scene_size`: the largest body's radius, which sizes the markers of rigid bodies, links
    // and contacts.
    void build(const Frame& frame, std::span<const SoftBodyDrawn> soft, float scene_size, OverlayGeometry& out);

private:
    // What one soft body's overlays keep between frames (the samples are costly to pick).
    struct SoftCache {
        const Mesh* spring_mesh = nullptr;
        std::size_t spring_mesh_particles = 0, spring_mesh_triangles = 0, spring_budget = 0;
        std::vector<SpringSample> springs;
        const Mesh* edge_mesh = nullptr;
        std::size_t edge_mesh_triangles = 0;
        std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;  // the surface's edges, for wireframe
    };
    void build_soft(const Frame& frame, const BodyView& body, const SoftBodyDrawn& drawn, bool first, SoftCache& cache,
                    OverlayGeometry& out);
    void build_rigid(const Frame& frame, float scene_size, OverlayGeometry& out);
    std::vector<SoftCache> soft_;
};

}  // namespace softbody::render

// The CPU half of drawing a deforming body: every frame, the particle positions become the
// render vertices' positions, and normals are recomputed from the deformed triangles, so the
// shading follows the squash and stretch. No GL here (the benchmark and tests use it alone).
//
// Normals: each triangle adds its area-weighted normal (the cross product of two edges) to
// the normal slot of each of its corners; a render vertex takes its slot's normalised sum.
// Corners that the mesh marks as one smooth slot are averaged (a sphere stays smooth); a
// hard edge gives each face its own slot (a cube keeps its edges).
#pragma once

#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "physics/mesh.h"
#include "render/frame.h"

namespace softbody::render {

// One streamed vertex, as the GPU reads it.
struct SurfaceVertex {
    glm::vec3 position;
    glm::vec3 normal;
};
static_assert(sizeof(SurfaceVertex) == 24, "streamed vertices are six packed floats");

// Particle positions for this frame: lerp(previous, current, alpha) when the previous tick is
// given, plus the debug offset. Throws std::invalid_argument when sizes disagree with the mesh.
void interpolate_positions(const BodyView& body, const glm::vec3& offset, std::vector<glm::vec3>& out);

class DeformedSurface {
public:
    // Recomputes every render vertex from the particle positions (one per mesh particle).
    void update(const Mesh& mesh, std::span<const glm::vec3> particles, bool flip_normals = false);
    const std::vector<SurfaceVertex>& vertices() const { return vertices_; }

private:
    std::vector<glm::vec3> slot_normals_;
    std::vector<SurfaceVertex> vertices_;
};

}  // namespace softbody::render

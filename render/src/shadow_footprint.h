// Where the sun's shadow map reaches the floor. The map covers the unit square of its texture
// coordinates; a floor point outside that square is lit by the sun whatever the bodies do
// (lighting.glsl, sun_visibility), so the floor there is drawn without the map's lookups.
#pragma once

#include <optional>

#include <glm/glm.hpp>

namespace softbody::render {

// An axis-aligned rectangle of the floor plane, in world x and y (m).
struct FloorRect {
    glm::vec2 centre{0.0f};
    glm::vec2 half_size{0.0f};
};

// The smallest axis-aligned rectangle of the plane z = height holding every point whose lookup
// (the point lifted by `lift` along +z, through `world_to_map`, an affine map to [0,1]^3) falls
// inside the map's square, grown by a margin against rounding; nothing when the map's square
// does not project onto the plane as a bounded region (the sun along the floor).
std::optional<FloorRect> shadow_footprint(const glm::mat4& world_to_map, float height, float lift);

// The overlap of two rectangles; nothing when they do not overlap.
std::optional<FloorRect> overlap(const FloorRect& a, const FloorRect& b);

}  // namespace softbody::render

#include "shadow_footprint.h"

#include <algorithm>
#include <cmath>

namespace softbody::render {

std::optional<FloorRect> shadow_footprint(const glm::mat4& world_to_map, float height, float lift) {
    // On the plane the lookup's texture coordinates are affine in (x, y): uv = A (x, y) + b.
    const glm::mat2 a{glm::vec2(world_to_map[0]), glm::vec2(world_to_map[1])};
    const glm::vec2 b = glm::vec2(world_to_map[2]) * (height + lift) + glm::vec2(world_to_map[3]);
    const float det = glm::determinant(a);
    const float scale = std::max(std::abs(a[0][0]) + std::abs(a[1][0]), std::abs(a[0][1]) + std::abs(a[1][1]));
    if (!std::isfinite(det) || std::abs(det) <= 1e-6f * scale * scale) return std::nullopt;
    const glm::mat2 inverse = glm::inverse(a);
    glm::vec2 low(INFINITY), high(-INFINITY);
    for (const glm::vec2 corner : {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(0, 1), glm::vec2(1, 1)}) {
        const glm::vec2 p = inverse * (corner - b);
        low = glm::min(low, p);
        high = glm::max(high, p);
    }
    if (!std::isfinite(low.x) || !std::isfinite(low.y) || !std::isfinite(high.x) || !std::isfinite(high.y)) {
        return std::nullopt;
    }
    // A hundredth of the extent and a millimetre: the shader's uv, made in single precision
    // from the same matrix, cannot land inside the square beyond that.
    const glm::vec2 half = 0.5f * (high - low);
    return FloorRect{0.5f * (low + high), half * 1.01f + glm::vec2(1e-3f)};
}

std::optional<FloorRect> overlap(const FloorRect& a, const FloorRect& b) {
    const glm::vec2 low = glm::max(a.centre - a.half_size, b.centre - b.half_size);
    const glm::vec2 high = glm::min(a.centre + a.half_size, b.centre + b.half_size);
    if (!(low.x < high.x && low.y < high.y)) return std::nullopt;
    return FloorRect{0.5f * (low + high), 0.5f * (high - low)};
}

}  // namespace softbody::render

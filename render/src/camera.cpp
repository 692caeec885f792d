#include "render/camera.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace softbody::render {

namespace {
constexpr float kMaxPitch = 1.55f;  // just short of 90 degrees: the up vector stays defined
constexpr float kMinDistance = 0.05f;
constexpr float kMaxDistance = 300.0f;
}  // namespace

glm::vec3 Camera::forward() const {
    // Looking down by `pitch` along the horizontal heading given by `yaw`.
    const float c = std::cos(pitch);
    return {-std::sin(yaw) * c, std::cos(yaw) * c, -std::sin(pitch)};
}

glm::vec3 Camera::eye() const { return target - forward() * distance; }

glm::vec3 Camera::right() const { return glm::normalize(glm::cross(forward(), glm::vec3(0.0f, 0.0f, 1.0f))); }

glm::vec3 Camera::up() const { return glm::cross(right(), forward()); }

glm::mat4 Camera::view() const { return glm::lookAt(eye(), target, glm::vec3(0.0f, 0.0f, 1.0f)); }

glm::mat4 Camera::projection(float aspect) const {
    return glm::perspective(fov_y, std::max(aspect, 1e-3f), near_plane, far_plane);
}

void Camera::frame(const glm::vec3& centre, float radius, float aspect, float fill) {
    target = centre;
    // The narrower of the two fields of view decides: the sphere must fit both ways.
    const float half_y = 0.5f * fov_y;
    const float half_x = std::atan(std::tan(half_y) * aspect);
    const float half = std::min(half_x, half_y);
    const float r = std::max(radius, 1e-3f) / std::clamp(fill, 0.05f, 1.0f);
    distance = std::clamp(r / std::sin(half), kMinDistance, kMaxDistance);
    near_plane = std::max(0.01f, 0.02f * distance);
    far_plane = std::max(400.0f, 60.0f * distance);
}

void Camera::orbit(float delta_yaw, float delta_pitch) {
    yaw += delta_yaw;
    pitch = std::clamp(pitch + delta_pitch, -kMaxPitch, kMaxPitch);
}

void Camera::zoom(float factor) { distance = std::clamp(distance * factor, kMinDistance, kMaxDistance); }

void Camera::pan(float dx, float dy) { target += right() * dx + up() * dy; }

}  // namespace softbody::render

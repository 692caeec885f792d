// An orbit camera around a target point, z up. The app drives it (orbit, zoom, pan from the
// mouse); frame() points it at a bounding sphere so the whole body is in view.
#pragma once

#include <glm/glm.hpp>

namespace softbody::render {

struct Camera {
    glm::vec3 target{0.0f, 0.0f, 1.0f};
    float yaw = -0.6f;        // rad, about +z; 0 looks along +y
    float pitch = 0.28f;      // rad above the horizon (looking down at the target)
    float distance = 6.0f;    // m from the target
    float fov_y = 0.70f;      // rad, vertical field of view
    float near_plane = 0.05f;
    float far_plane = 400.0f;

    glm::vec3 eye() const;
    glm::vec3 forward() const;  // unit, from the eye to the target
    glm::vec3 right() const;    // unit, horizontal
    glm::vec3 up() const;       // unit, completes the frame
    glm::mat4 view() const;
    glm::mat4 projection(float aspect) const;

    // Looks at a sphere from the current direction, from just far enough that it fills about
    // `fill` of the smaller side of the view (1 = touching the edges).
    void frame(const glm::vec3& centre, float radius, float aspect, float fill = 0.8f);

    void orbit(float delta_yaw, float delta_pitch);  // rad; pitch kept short of straight up/down
    void zoom(float factor);                         // distance *= factor, within limits
    void pan(float dx, float dy);                    // moves the target in the view plane, m
};

}  // namespace softbody::render

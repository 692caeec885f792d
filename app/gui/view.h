// How the session is looked at: the camera (framing, following the bodies, orbit and pan), what
// is drawn over the bodies, the mouse's picking and pulling, and the frame the renderer draws.
// No GLFW and no ImGui: the app shell feeds it the window's size and the controls' gestures.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "gui/session.h"
#include "render/frame.h"

namespace softbody::app {

// What the mouse is over: a particle of a soft body, or a point on a rigid body.
struct Pick {
    bool rigid = false;
    std::uint32_t body = 0;      // soft or rigid body index
    std::uint32_t particle = 0;  // soft
    Vec3d point;                 // rigid: body axes from the centre of mass
    float depth = 0.0f;          // along the view, m: the nearest pick wins
};

// Each integrator's colour in the comparison (the main world's too).
glm::vec3 integrator_color(Integrator integrator);

// The ray under pixel (x, y) of a width x height view: origin on the near plane, unit direction.
void mouse_ray(const render::Camera& camera, float x, float y, float width, float height, glm::vec3& origin, glm::vec3& direction);

class View {
public:
    render::Camera camera;
    render::Overlays overlays;
    render::Appearance appearance;
    // Camera follow: the view moves with the bodies' centre (every moving body's centre of mass,
    // weighted by mass), horizontally and smoothed, keeping them where the framing (or a pan)
    // put them in the view; it holds still while the mouse pulls a body. On by default for a
    // scene with one moving body (fixed bodies are scenery); the Display tool and T toggle it.
    bool follow = false;
    // Sleeping rigid bodies drawn dimmer (the Display tool): what the physics skips shows.
    bool dim_sleeping = true;
    // The compared worlds drawn over the main one instead of beside it.
    bool compare_overlaid = false;

    // A new scene: follow when one body moves, and frame it.
    void start(const Session& session);
    // The view's shape: width / height, and the fraction of its width to move a framed body
    // right by (to centre it in the part the panels leave free). Set by the shell each frame.
    void set_view(float aspect, float shift) {
        aspect_ = aspect;
        shift_ = shift;
    }
    // Points the camera at the bodies (and the compared copies) and the ground below them.
    void frame_body(const Session& session);
    void follow_bodies(const Session& session, double seconds);  // one frame's worth
    void pan(const Session& session, float dx, float dy);        // the camera's pan, which a follow keeps
    render::Frame make_frame(const Session& session) const;
    // Where the Add tool drops a body: above the bodies, where the camera looks.
    Vec3 drop_point(const World& world) const;

    // What is under pixel (x, y) of a width x height view: a soft body's particle drawn nearest,
    // within `radius` px, or the point of a rigid body's surface the ray meets first, whichever
    // is nearer the eye (picking.cpp).
    std::optional<Pick> pick(const World& world, float x, float y, float width, float height, float radius) const;
    void begin_grab(Session& session, const Pick& pick, float x, float y, float width, float height);
    void drag(Session& session, float x, float y, float width, float height);
    void end_grab(Session& session);

private:
    void keep_framing_offset(const World& world);
    glm::vec3 compared_offset(const Session& session, std::size_t k) const;

    float aspect_ = 1.6f, shift_ = 0.0f;
    float grab_depth_ = 0.0f;  // distance along the view direction of the grab plane
    glm::vec3 across_{1.0f, 0.0f, 0.0f};  // the compared copies stand along this, as framed
    float spacing_ = 1.0f;                // and this far apart
    // Where the camera's target sits from the bodies' centre, level: along the camera's right
    // and its level forward (m), so an orbit keeps the bodies where they are in the view.
    glm::vec2 follow_offset_{0.0f};
};

}  // namespace softbody::app

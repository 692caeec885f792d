// The view (view.h): framing, following the bodies, the frame drawn, and the mouse's pull.
// Picking is picking.cpp's.
#include "gui/view.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "body_view.h"

namespace softbody::app {

namespace {


// The camera's follow (Demo::follow_bodies): how long the view takes to catch up with the
// bodies, as the time constant of an exponential approach. Long enough that a bounce or a
// wobble does not shake the view, short enough that a rolling body stays in it (0.4 s behind
// at 1 m/s is 0.4 m).
constexpr double kFollowSeconds = 0.4;

// The centre of every body that moves (soft bodies and rigid bodies that are not fixed), each
// weighted by its mass; empty when nothing moves.
std::optional<glm::vec3> moving_centre(const World& world) {
    glm::dvec3 sum(0.0);
    double mass = 0.0;
    for (std::size_t b = 0; b < world.soft_body_count(); ++b) {
        const SoftBody& body = world.soft_body(b);
        const std::size_t n = body.particle_count();
        if (n == 0) continue;
        glm::dvec3 c(0.0);
        for (std::size_t i = 0; i < n; ++i) c += glm::dvec3(body.x.x[i], body.x.y[i], body.x.z[i]);
        const double m = double(body.mass) * double(n);
        sum += c / double(n) * m;
        mass += m;
    }
    for (std::size_t b = 0; b < world.rigid_body_count(); ++b) {
        if (world.rigid_body(b).fixed) continue;
        const Vec3d x = world.rigid_motion(b).x;
        sum += glm::dvec3(x.x, x.y, x.z) * world.rigid_body(b).mass;
        mass += world.rigid_body(b).mass;
    }
    if (!(mass > 0.0)) return std::nullopt;
    return glm::vec3(sum / mass);
}

std::size_t moving_body_count(const World& world) {
    std::size_t n = world.soft_body_count();
    for (std::size_t b = 0; b < world.rigid_body_count(); ++b) n += world.rigid_body(b).fixed ? 0 : 1;
    return n;
}

// The camera's level axes: its right, and its forward without the pitch.
void level_axes(const render::Camera& camera, glm::vec2& right, glm::vec2& forward) {
    const glm::vec3 r = camera.right();
    right = glm::normalize(glm::vec2(r.x, r.y));
    forward = glm::vec2(-right.y, right.x);  // z x right: the forward direction, level
}

// The inspector's arrows: each force at its particle (or centre of mass), one colour per
// equation, the largest six tenths of the bodies' radius long.
glm::vec3 equation_color(const std::string& equation) {
    if (equation == "Listing 8" || equation == "Listing 9") return {0.20f, 0.55f, 0.95f};  // weight: blue
    if (equation == "Eq. 21") return {0.90f, 0.20f, 0.20f};                               // springs: red
    if (equation == "Eq. 22") return {0.95f, 0.60f, 0.10f};                               // dampers: orange
    if (equation == "Eq. 23") return {0.55f, 0.80f, 0.95f};                               // drag: sky
    if (equation == "Eq. 24" || equation == "Eq. 25") return {0.60f, 0.30f, 0.80f};       // friction: purple
    if (equation == "contact" || equation == "Eq. 37" || equation == "Eq. 38") return {0.20f, 0.70f, 0.35f};  // green
    return {0.45f, 0.45f, 0.45f};
}

}  // namespace

// The ray under pixel (x, y): origin on the near plane, unit direction.
void mouse_ray(const render::Camera& camera, float x, float y, float width, float height, glm::vec3& origin,
               glm::vec3& direction) {
    const glm::mat4 inverse = glm::inverse(camera.projection(width / height) * camera.view());
    const float nx = 2.0f * x / width - 1.0f, ny = 1.0f - 2.0f * y / height;
    glm::vec4 near = inverse * glm::vec4(nx, ny, -1.0f, 1.0f), far = inverse * glm::vec4(nx, ny, 1.0f, 1.0f);
    near /= near.w;
    far /= far.w;
    origin = glm::vec3(near);
    direction = glm::normalize(glm::vec3(far) - glm::vec3(near));
}

glm::vec3 integrator_color(Integrator integrator) {
    switch (integrator) {
        case Integrator::Verlet: return {0.93f, 0.45f, 0.24f};           // orange, the demo's own
        case Integrator::SymplecticEuler: return {0.24f, 0.52f, 0.86f};  // blue
        case Integrator::ExplicitEuler: return {0.66f, 0.36f, 0.84f};    // purple
        case Integrator::RK4: return {0.32f, 0.72f, 0.40f};              // green
    }
    return {0.5f, 0.5f, 0.5f};
}

void View::start(const Session& session) {
    // A scene that says where to look from (its "view"): the camera turns there, then frames.
    const SceneView& look = session.lesson().view;
    if (look.yaw) camera.yaw = float(*look.yaw * 3.14159265358979323846 / 180.0);
    if (look.pitch) camera.pitch = float(*look.pitch * 3.14159265358979323846 / 180.0);
    follow = moving_body_count(session.world()) == 1;  // one body: the view goes where it goes
    frame_body(session);
}

glm::vec3 View::compared_offset(const Session& session, std::size_t k) const {
    if (compare_overlaid || k >= session.compared().size()) return glm::vec3(0.0f);
    return across_ * (spacing_ * float(k + 1));
}

void View::frame_body(const Session& session) {
    const World& world = session.world();
    const float aspect = aspect_, shift = shift_;
    // Frame the bodies and the ground below them, so the whole fall is in view.
    WorldBounds bounds = world_bounds(world);
    if (session.comparing()) {
        // The copies side by side across the view, each a few body sizes from the last.
        spacing_ = 3.5f * std::max(bounds.radius, 0.3f);
        glm::vec3 across = glm::cross(camera.forward(), glm::vec3(0.0f, 0.0f, 1.0f));
        across.z = 0.0f;
        across_ = glm::length(across) > 1e-3f ? glm::normalize(across) : glm::vec3(1.0f, 0.0f, 0.0f);
    }
    if (session.comparing() && !compare_overlaid) {
        // The copies beside it too: the sphere around all of them.
        glm::vec3 low = bounds.centre - bounds.radius, high = bounds.centre + bounds.radius;
        for (std::size_t k = 0; k < session.compared().size(); ++k) {
            low = glm::min(low, bounds.centre + compared_offset(session, k) - bounds.radius);
            high = glm::max(high, bounds.centre + compared_offset(session, k) + bounds.radius);
        }
        bounds.centre = 0.5f * (low + high);
        bounds.radius = 0.5f * glm::length(high - low);
    }
    const glm::vec3 com = bounds.centre;
    const float radius = std::max(bounds.radius, 0.25f);
    const float ground = world.settings().ground_height;
    const float bottom = world.settings().ground ? std::min(ground, com.z - radius) : com.z - radius;
    const float top = com.z + radius;
    const glm::vec3 centre{com.x, com.y, 0.5f * (top + bottom)};
    camera.frame(centre, std::max(0.5f * (top - bottom), radius) * 1.15f, aspect * (1.0f - 2.0f * shift));
    const float view_width = 2.0f * camera.distance * std::tan(0.5f * camera.fov_y) * aspect;
    camera.pan(-shift * view_width, 0.0f);
    keep_framing_offset(world);
}

// The target approaches the bodies' centre plus the offset the framing gave it, level, with
// the time constant kFollowSeconds: 1 - exp(-t / tau) of the way each frame, which is the same
// motion whatever the frame rate. Its height is left alone, so the ground stays where it is in
// the view while a body bounces. While the mouse pulls a body the camera holds still: moving
// it would move the point the body is pulled toward, and the body after it.
void View::follow_bodies(const Session& session, double seconds) {
    if (!follow || session.world().grab() || !(seconds > 0.0)) return;
    const std::optional<glm::vec3> centre = moving_centre(session.world());
    if (!centre) return;
    glm::vec2 right, forward;
    level_axes(camera, right, forward);
    const glm::vec2 wanted = glm::vec2(*centre) + right * follow_offset_.x + forward * follow_offset_.y;
    const float a = float(1.0 - std::exp(-seconds / kFollowSeconds));
    const glm::vec2 now = glm::vec2(camera.target) + (wanted - glm::vec2(camera.target)) * a;
    camera.target.x = now.x;
    camera.target.y = now.y;
}

void View::pan(const Session& session, float dx, float dy) {
    (void)session;
    const glm::vec3 before = camera.target;
    camera.pan(dx, dy);
    // Following, the pan moves where the bodies sit in the view, and the follow keeps that.
    glm::vec2 right, forward;
    level_axes(camera, right, forward);
    const glm::vec2 moved(camera.target - before);
    follow_offset_ += glm::vec2(glm::dot(moved, right), glm::dot(moved, forward));
}

void View::keep_framing_offset(const World& world) {
    const std::optional<glm::vec3> centre = moving_centre(world);
    if (!centre) return;
    glm::vec2 right, forward;
    level_axes(camera, right, forward);
    const glm::vec2 d = glm::vec2(camera.target) - glm::vec2(*centre);
    follow_offset_ = {glm::dot(d, right), glm::dot(d, forward)};
}

Vec3 View::drop_point(const World& world) const {
    const WorldBounds bounds = world_bounds(world);
    const float top = world.soft_body_count() + world.rigid_body_count() > 0 ? bounds.centre.z + bounds.radius : 0.0f;
    const float size = 0.5f;
    const WorldSettings& settings = world.settings();
    return {camera.target.x, camera.target.y, std::max(top, settings.ground ? settings.ground_height : 0.0f) + size + 0.3f};
}

render::Frame View::make_frame(const Session& session) const {
    render::Frame frame;
    const World& w = session.world();
    const float alpha = float(session.alpha());
    world_view(w, alpha, frame);
    if (dim_sleeping) {
        // Half way to a mid grey, and darker: still the body's own colour, but plainly resting.
        for (std::size_t b = 0; b < w.rigid_body_count(); ++b) {
            if (w.rigid_asleep(b)) frame.rigid_bodies[b].color = glm::mix(frame.rigid_bodies[b].color, glm::vec3(0.35f), 0.55f);
        }
    }
    frame.camera = camera;
    frame.overlays = overlays;
    frame.appearance = appearance;
    // The ground as the physics has it (the Display tool can hide it, not move it).
    frame.appearance.ground = appearance.ground && w.settings().ground;
    frame.appearance.ground_height = w.settings().ground_height;
    if (session.comparing()) {
        // Every world in its integrator's colour, the copies beside the main one (or over it).
        const glm::vec3 own = integrator_color(w.settings().integrator);
        for (render::BodyView& v : frame.soft_bodies) v.color = own;
        for (render::RigidBodyView& v : frame.rigid_bodies) {
            if (!v.fixed) v.color = own;
        }
        for (std::size_t k = 0; k < session.compared().size(); ++k) {
            const ComparedWorld& c = session.compared()[k];
            const glm::vec3 offset = compared_offset(session, k), color = integrator_color(c.setup.integrator);
            const World& copy = *c.world;
            const float a = copy.status() == Status::Ok ? alpha : 1.0f;
            for (std::size_t b = 0; b < copy.soft_body_count(); ++b) {
                render::BodyView v = soft_body_view(copy.soft_body(b), a);
                v.offset = offset;
                v.color = color;
                frame.soft_bodies.push_back(v);
            }
            for (std::size_t b = 0; b < copy.rigid_body_count(); ++b) {
                render::RigidBodyView v = rigid_body_view(copy, b, a);
                v.position += offset;
                v.previous_position += offset;
                if (!v.fixed) v.color = color;
                frame.rigid_bodies.push_back(v);
            }
        }
    }
    if (const auto& grab = w.grab()) {
        frame.overlays.grab = true;
        frame.overlays.grab_target = to_glm(grab->target);
        if (grab->rigid) {
            const RigidMotion m = w.rigid_motion(grab->body);
            frame.overlays.grab_on_rigid = true;
            frame.overlays.grab_point = to_glm(m.x + m.R * grab->point);
        } else {
            frame.overlays.grab_particle = grab->particle;
        }
    }
    const float size = std::max(world_bounds(w).radius, 0.05f);
    if (const auto in = session.particle_inspection()) {
        float largest = 0.0f;
        for (const ForceTerm& t : in->terms) largest = std::max(largest, length(t.force));
        for (const ForceTerm& t : in->terms) {
            if (largest > 0.0f && length(t.force) > 1e-3f * largest) {
                frame.arrows.push_back({to_glm(Vec3d(in->x)), to_glm(Vec3d(t.force)) * (0.6f * size / largest), equation_color(t.equation)});
            }
        }
        frame.arrows.push_back({to_glm(Vec3d(in->x)), glm::vec3(0.0f, 0.0f, 0.04f * size), glm::vec3(0.1f), 6.0f});  // the marker
    }
    if (const auto in = session.rigid_inspection()) {
        const Vec3d centre = w.rigid_motion(in->body).x;
        double largest = 0.0;
        for (const WrenchTerm& t : in->terms) largest = std::max(largest, length(t.force));
        for (const WrenchTerm& t : in->terms) {
            if (largest > 0.0 && length(t.force) > 1e-3 * largest) {
                frame.arrows.push_back({to_glm(centre), to_glm(t.force) * float(0.6 * size / largest), equation_color(t.equation)});
            }
        }
    }
    return frame;
}

// --- The mouse's pull ----------------------------------------------------------------------

void View::begin_grab(Session& session, const Pick& pick, float x, float y, float width, float height) {
    const World& world = session.world();
    Grab grab;
    glm::vec3 at;
    if (pick.rigid) {
        const RigidMotion m = world.rigid_motion(pick.body);
        at = to_glm(m.x + m.R * pick.point);
        grab.rigid = true;
        grab.body = pick.body;
        grab.point = pick.point;
    } else {
        at = to_glm(world.soft_body(pick.body).x[pick.particle]);
        grab.body = pick.body;
        grab.particle = pick.particle;
    }
    grab_depth_ = glm::dot(at - camera.eye(), camera.forward());
    grab.target = {at.x, at.y, at.z};
    session.set_grab(grab);
    drag(session, x, y, width, height);
}

void View::drag(Session& session, float x, float y, float width, float height) {
    if (!session.world().grab()) return;
    glm::vec3 origin, direction;
    mouse_ray(camera, x, y, width, height, origin, direction);
    // Where the ray meets the plane facing the camera at the grabbed particle's depth.
    const float along = glm::dot(direction, camera.forward());
    if (along <= 1e-4f) return;
    const float t = (grab_depth_ - glm::dot(origin - camera.eye(), camera.forward())) / along;
    const glm::vec3 target = origin + direction * t;
    Grab grab = *session.world().grab();
    grab.target = {target.x, target.y, target.z};
    session.set_grab(grab);
}

void View::end_grab(Session& session) {
    if (!session.world().grab()) return;
    session.set_grab(std::nullopt);
}

}  // namespace softbody::app

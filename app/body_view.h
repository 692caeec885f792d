// The renderer's read-only view of a World: spans over the physics' own arrays for the soft
// bodies, each rigid body's state at the last two ticks, the links and the contacts. Shared
// by every command that draws (the window and `softbody render`).
#pragma once

#include <algorithm>
#include <array>

#include "physics/convex_hull.h"
#include "physics/world.h"
#include "render/frame.h"

namespace softbody::app {

inline render::Vec3Span span_of(const Vec3Array& a) { return {a.x.data(), a.y.data(), a.z.data(), a.size()}; }

// Soft bodies' colours after the first, sRGB: the first is the appearance's orange (as the demo
// has always drawn its one body), the others distinct from it, from one another and from the
// rigid bodies' palette below.
inline glm::vec3 soft_body_color(std::size_t i) {
    // Brighter or deeper than the rigid bodies' muted hues: lime, crimson, sky, ivory, navy,
    // magenta (a soft ball and a rigid ball dropped side by side must not both be blue).
    static constexpr std::array<glm::vec3, 6> kPalette{{{0.66f, 0.86f, 0.20f},
                                                        {0.86f, 0.20f, 0.30f},
                                                        {0.52f, 0.80f, 0.98f},
                                                        {0.93f, 0.93f, 0.88f},
                                                        {0.22f, 0.28f, 0.62f},
                                                        {0.90f, 0.25f, 0.75f}}};
    return kPalette[(i - 1) % kPalette.size()];
}

inline glm::vec3 to_glm(const Vec3& v) { return {v.x, v.y, v.z}; }

// `alpha` in [0, 1]: how far from the previous tick to the latest one to draw the body.
// `index`: the body's place among the soft bodies, for its colour when it sets none.
inline render::BodyView soft_body_view(const SoftBody& body, float alpha = 1.0f, std::size_t index = 0) {
    render::BodyView view;
    view.mesh = &body.mesh;
    if (body.reduced) {
        // Simulated on fewer particles than the mesh has: the mesh drawn by skinning.
        view.mesh = &body.particle_mesh;
        view.surface = &body.mesh;
        view.skin = body.skin;
    }
    view.positions = span_of(body.x);
    view.previous_positions = span_of(body.x_tick_prev);
    view.alpha = alpha;
    view.velocities = span_of(body.v);
    if (body.force.size() == body.particle_count()) view.forces = span_of(body.force);
    view.rest_positions = span_of(body.rest);
    view.inverse_masses = {body.inv_mass.data(), body.inv_mass.size()};
    if (body.def.color) view.color = to_glm(*body.def.color);
    else if (index > 0) view.color = soft_body_color(index);
    return view;
}

// Rigid bodies' colours, sRGB: distinct from one another and from the soft bodies' orange.
inline glm::vec3 rigid_body_color(std::size_t i) {
    static constexpr std::array<glm::vec3, 8> kPalette{{{0.24f, 0.52f, 0.80f},
                                                        {0.95f, 0.76f, 0.26f},
                                                        {0.38f, 0.70f, 0.44f},
                                                        {0.60f, 0.44f, 0.80f},
                                                        {0.28f, 0.70f, 0.70f},
                                                        {0.86f, 0.52f, 0.64f},
                                                        {0.56f, 0.60f, 0.34f},
                                                        {0.74f, 0.40f, 0.30f}}};
    return kPalette[i % kPalette.size()];
}

inline glm::vec3 to_glm(const Vec3d& v) { return {float(v.x), float(v.y), float(v.z)}; }

inline render::RigidBodyView rigid_body_view(const World& world, std::size_t i, float alpha = 1.0f) {
    const RigidBody& body = world.rigid_body(i);
    const double* now = world.rigid_state(i);
    const double* before = world.rigid_previous_state(i);
    const RigidMotion m = world.rigid_motion(i);
    render::RigidBodyView view;
    view.mesh = &body.render_mesh;
    view.position = {float(now[rigid::X]), float(now[rigid::X + 1]), float(now[rigid::X + 2])};
    view.previous_position = {float(before[rigid::X]), float(before[rigid::X + 1]), float(before[rigid::X + 2])};
    view.orientation = {float(now[rigid::Q]), float(now[rigid::Q + 1]), float(now[rigid::Q + 2]), float(now[rigid::Q + 3])};
    view.previous_orientation = {float(before[rigid::Q]), float(before[rigid::Q + 1]), float(before[rigid::Q + 2]),
                                 float(before[rigid::Q + 3])};
    view.alpha = alpha;
    view.color = body.color ? to_glm(*body.color) : rigid_body_color(i);
    view.radius = float(body.bounding_radius);
    view.mass = float(body.mass);
    view.fixed = body.fixed;
    view.velocity = to_glm(m.v);
    view.angular_velocity = to_glm(m.omega);
    view.angular_momentum = to_glm(m.L);
    return view;
}

// Every body of the world, its links and its last contacts, into `frame`.
inline void world_view(const World& world, float alpha, render::Frame& frame) {
    frame.soft_bodies.clear();
    for (std::size_t b = 0; b < world.soft_body_count(); ++b) frame.soft_bodies.push_back(soft_body_view(world.soft_body(b), alpha, b));
    frame.rigid_bodies.clear();
    for (std::size_t b = 0; b < world.rigid_body_count(); ++b) frame.rigid_bodies.push_back(rigid_body_view(world, b, alpha));
    frame.links.clear();
    for (const Link& link : world.links()) {
        frame.links.push_back({to_glm(world.link_end_position(link.a)), to_glm(world.link_end_position(link.b)), float(link.l0)});
    }
    frame.contacts.clear();
    for (const RigidContact& c : world.contacts()) frame.contacts.push_back({to_glm(c.point), to_glm(c.normal), float(c.normal_impulse)});
}

// How the renderer's ground matches the physics' ground.
inline void match_ground(const WorldSettings& settings, render::Appearance& look) {
    look.ground = settings.ground;
    look.ground_height = settings.ground_height;
}

// A sphere holding every body as it is now: a soft body's centre of mass and reach when it is
// alone (as the demo has always framed it), else the bounding spheres of all and the points in
// the world that springs hang from.
struct WorldBounds {
    glm::vec3 centre{0.0f};
    float radius = 0.0f;
};
inline WorldBounds world_bounds(const World& world) {
    WorldBounds bounds;
    if (world.soft_body_count() == 1 && world.rigid_body_count() == 0) {
        const Vec3 c = world.center_of_mass(0);
        const Vec3Array& x = world.soft_body(0).x;
        for (std::size_t i = 0; i < x.size(); ++i) bounds.radius = std::max(bounds.radius, length(x[i] - c));
        bounds.centre = {c.x, c.y, c.z};
        return bounds;
    }
    glm::vec3 low(0.0f), high(0.0f);
    bool first = true;
    const auto add = [&](const glm::vec3& c, float r) {
        low = first ? c - r : glm::min(low, c - r);
        high = first ? c + r : glm::max(high, c + r);
        first = false;
    };
    for (std::size_t b = 0; b < world.soft_body_count(); ++b) {
        const Vec3Array& x = world.soft_body(b).x;
        for (std::size_t i = 0; i < x.size(); ++i) add({x.x[i], x.y[i], x.z[i]}, 0.0f);
    }
    // A rigid body's hull corners where it is (a sphere: its centre and radius): a long thin
    // wall then counts for its own extent, not for the sphere about it.
    for (std::size_t b = 0; b < world.rigid_body_count(); ++b) {
        const RigidBody& body = world.rigid_body(b);
        const RigidMotion m = world.rigid_motion(b);
        if (!body.hull) {
            add(to_glm(m.x), float(body.bounding_radius));
            continue;
        }
        for (const Vec3d& v : body.hull->vertices) add(to_glm(m.x + m.R * v), 0.0f);
    }
    // A spring's end fixed in the world (the point a ball hangs from): in view with what hangs.
    for (const Link& link : world.links()) {
        for (const LinkEnd* end : {&link.a, &link.b}) {
            if (end->kind == LinkEnd::Kind::World) add(to_glm(end->point), 0.0f);
        }
    }
    bounds.centre = 0.5f * (low + high);
    bounds.radius = 0.5f * glm::length(high - low);
    return bounds;
}

// The camera framed on the sphere to keep in view: the bodies now, and where they will land on
// the floor below (`softbody render` and the Python module's pictures).
inline void frame_body(const World& world, float aspect, render::Camera& camera, float zoom) {
    const WorldSettings& params = world.settings();
    const WorldBounds bounds = world_bounds(world);
    const glm::vec3 c = bounds.centre;
    const float r = std::max(bounds.radius, 1e-3f);
    glm::vec3 centre = c;
    float radius = r;
    bool pinned = false;
    for (std::size_t b = 0; b < world.soft_body_count(); ++b) pinned = pinned || !world.soft_body(b).def.pinned.empty();
    if (pinned) {
        // A pinned body hangs: room below it for the sag, not the whole way to the floor.
        centre.z -= 0.4f * r;
        radius = 1.4f * r;
    } else if (params.ground && c.z - params.ground_height > 0.0f) {
        const glm::vec3 landed(c.x, c.y, std::min(c.z, params.ground_height + 0.6f * r));
        centre = 0.5f * (centre + landed);
        radius = 0.5f * glm::length(glm::vec3(c.x, c.y, c.z) - landed) + r;
    }
    // One body is framed with room to squash and roll; a group of bodies is its own margin.
    const bool alone = world.soft_body_count() + world.rigid_body_count() == 1;
    camera.frame(centre, std::max(radius, (alone ? 1.6f : 1.0f) * r), aspect, 0.85f);
    camera.zoom(zoom);
}

}  // namespace softbody::app

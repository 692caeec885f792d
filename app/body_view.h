// The renderer's read-only view of a World: spans over the physics' own arrays, nothing copied.
// Shared by every command that draws (the window and `softbody render`).
#pragma once

#include "physics/world.h"
#include "render/frame.h"

namespace softbody::app {

inline render::Vec3Span span_of(const Vec3Array& a) { return {a.x.data(), a.y.data(), a.z.data(), a.size()}; }

// `alpha` in [0, 1]: how far from the previous tick to the latest one to draw the body.
inline render::BodyView body_view(const World& world, float alpha = 1.0f) {
    render::BodyView view;
    view.mesh = &world.mesh();
    view.positions = span_of(world.positions());
    view.previous_positions = span_of(world.previous_tick_positions());
    view.alpha = alpha;
    view.velocities = span_of(world.velocities());
    if (world.forces().size() == world.particle_count()) view.forces = span_of(world.forces());
    view.rest_positions = span_of(world.rest_positions());
    view.inverse_masses = {world.inverse_masses().data(), world.inverse_masses().size()};
    return view;
}

// How the renderer's ground matches the physics' ground.
inline void match_ground(const Params& params, render::Appearance& look) {
    look.ground = params.ground;
    look.ground_height = params.ground_height;
}

}  // namespace softbody::app

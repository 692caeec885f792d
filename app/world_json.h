// The JSON that describes a world's bodies, shared by `softbody simulate`'s summary and the
// app's: one entry per body, with the fields app/README.md#softbody-simulate lists.
#pragma once

#include <nlohmann/json.hpp>

#include "physics/world.h"

namespace softbody::app {

nlohmann::ordered_json vec_json(const Vec3d& v);

// name, shape, mass, fixed, position, orientation (w, x, y, z), velocity, angular_velocity,
// angular_momentum (about its centre of mass), inertia (J in world axes, Eq. 32, rows),
// kinetic_energy (translational plus rotational).
nlohmann::ordered_json rigid_body_json(const World& world, std::size_t b);

// Every rigid body's entry, in order.
nlohmann::ordered_json rigid_bodies_json(const World& world);

// Every soft body's entry: name, mesh, vertices (in the file), mesh_particles (its distinct
// positions), particles (simulated: fewer when above max_particles), scale (used; "auto" sizes
// it), scale_auto, up_axis.
nlohmann::ordered_json soft_bodies_json(const World& world);

}  // namespace softbody::app

// Internal to the physics library: a soft body's particles against the rigid bodies, as
// RigidContacts for the solver (contact_solver.h) with the particle on side a (Eq. 38 with no
// rotation term for body 1) and the rigid body on side b.
#pragma once

#include <span>
#include <vector>

#include "physics/arrays.h"
#include "physics/collide.h"
#include "physics/contact.h"
#include "physics/defs.h"
#include "physics/rigid_body.h"
#include "physics/soft_body.h"

namespace softbody {

// Appends a contact for every particle of `body` (soft body number `soft`) within reach of a
// rigid body's surface where the tick began (`start`; the particles where they are now): within
// how far the particle can move in the tick h (its speed, gravity, what the forces of its last
// tick (body.x_tick_prev to x) did, and a millimetre) plus the rigid body's speculative margin (ground_contact.h). A particle
// inside a shape goes out along the nearest surface's normal (point_contact).
// Friction is Eq. 24 and 25 with the world's mu_s and mu_d, unless the rigid body sets
// `friction`, which then serves as both: the contact's static_friction is mu_s when the particle
// was at rest on the surface as the tick began (slower than 0.1 mm/s across it, as at the
// ground), mu_d when it was sliding. Restitution is the larger of the world's and the rigid
// body's.
void particle_rigid_contacts(const SoftBody& body, std::int32_t soft, std::span<const RigidBody> bodies, std::span<const CollisionShape> shapes,
                             std::span<const double> start, const WorldSettings& world, double h, std::vector<RigidContact>& out);

// RK4's stage state of every soft body (x_tmp, v_stage) kept out of the rigid bodies its
// particles have contacts with: a particle the stage takes inside a body's surface (its plane at
// the contact, carried with the body from where the contacts were found, `found`, to its stage
// state, `stage`) is put back on it, and its velocity into the body removed. The contacts act
// after the step (contact_solver.h), but the stages' spring forces are found at these states: let
// through the surface, a ball landing on a box was squeezed in its stages far more than the
// contacts then let it be, and the springs' answer to that came back as speed (as for the
// ground: ground_contact.h).
void hold_stage_off_rigid(std::span<SoftBody> soft, std::span<const RigidContact> contacts, std::span<const RigidBody> bodies,
                          std::span<const double> found, std::span<const double> stage);

}  // namespace softbody

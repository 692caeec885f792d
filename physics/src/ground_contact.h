// Internal to the physics library: bodies against the ground plane z = ground_height, with
// normal n = (0, 0, 1).
//
// A soft body's particles:
//   During the force evaluation: Coulomb friction, Eq. 24 (static) and Eq. 25 (dynamic), for
//   particles touching the ground and pressed into it.
//   After the step: static friction holds, a slide stops without reversing, and the ground
//   pushes back with restitution (impulse-momentum).
#pragma once

#include <vector>

#include "forces.h"
#include "manifold.h"
#include "physics/contact.h"
#include "physics/defs.h"
#include "physics/rigid_body.h"
#include "physics/soft_body.h"

namespace softbody {

// Adds friction to body.force, whose entries must hold everything else by now (F_applied).
// With `record`, remembers each particle in contact (body.contacts) for resolve_ground_contacts;
// without (RK4's stages 1 to 3), acts on those particles as that record says.
void apply_ground_friction(SoftBody& body, const ParticleState& s, const WorldSettings& world, bool record);

// RK4's stage state (body.x_tmp, v_stage) held on the ground for the particles that touched it,
// pressed in, as the step began (body.contacts): not below it, not moving into it. The ground
// holds such a particle through the whole step; a stage that took it below would feel its
// springs push it back out instead of the ground, and no friction (F_n > 0 there), so the
// stages' forces disagreed with one another and the velocity they summed to with the way the
// particle went: a particle lying still under a stack reported 0.27 m/s along the ground.
void hold_stage_on_ground(SoftBody& body, const WorldSettings& world);

// After a step of h: x and v are set together, and Verlet's step with them, so position and
// velocity stay consistent (x_n - x_{n-1} = v h): v is the velocity the next positions follow.
// A particle below the ground, or on it moving into it, is put on it; it bounces at e times the
// speed it met the ground with (from body.x_step_start and v_step_start, where the step began),
// else its normal velocity is zero.
void resolve_ground_contacts(SoftBody& body, const WorldSettings& world, float h);

// How far a rigid body's points can move in a step (or tick) of h, from where it was at the start:
// h (|v| + |w| R) for its motion then, h^2 |g| for gravity's, and a millimetre. A contact is
// made for points closer than that, before they touch (a speculative contact), so that the
// solver can stop them at the surface, however fast they come.
double speculative_margin(const RigidBody& body, const RigidMotion& start, double h, double g);

// A rigid body against the ground: the points of its shape within the speculative margin of
// it where the tick began (a sphere's lowest point; the vertices of its hull, at most four kept:
// the deepest, and those that span the largest area with it), with their gap then. The ground is
// static (1/m = 0, J^-1 = 0); the contacts go to the solver (contact_solver.h), with the body's
// restitution and friction or the world's. `start`: the body's state as the tick began; `h`: the tick.
void rigid_ground_contacts(const RigidBody& body, std::uint32_t index, const double* start, const WorldSettings& world, double h,
                           std::vector<RigidContact>& out);
// The same from the body's motion where the tick began (rigid_motion of `start`), worked out
// already.
void rigid_ground_contacts(const RigidBody& body, std::uint32_t index, const RigidMotion& start, const WorldSettings& world, double h,
                           std::vector<RigidContact>& out);

}  // namespace softbody

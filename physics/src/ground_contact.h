// Internal to the physics library: a soft body's particles against the ground plane
// z = ground_height, with normal n = (0, 0, 1).
//   During the force evaluation: Coulomb friction, Eq. 24 (static) and Eq. 25 (dynamic), for
//   particles touching the ground and pressed into it.
//   After the step: static friction holds, a slide stops without reversing, and the ground
//   pushes back with restitution (impulse-momentum).
#pragma once

#include "forces.h"
#include "physics/params.h"
#include "physics/soft_body.h"

namespace softbody {

// Adds friction to body.force, whose entries must hold everything else by now (F_applied).
// With `record`, remembers each particle in contact (body.contacts) for resolve_ground_contacts.
void apply_ground_friction(SoftBody& body, const ParticleState& s, const Params& world, bool record);

// After a step of h: x and v are set together, and Verlet's step with them, so position and
// velocity stay consistent (x_n - x_{n-1} = v h).
void resolve_ground_contacts(SoftBody& body, const Params& world, float h);

}  // namespace softbody

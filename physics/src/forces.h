// Internal to the physics library: the forces on a soft body's particles other than its springs
// and dampers (pair_forces.h) and the ground's friction (ground_contact.h). Each is a small
// function that adds its force to `force`, one entry per particle.
#pragma once

#include "physics/arrays.h"
#include "physics/vec3.h"
#include "physics/world.h"

namespace softbody {

// The particles' state as a force sees it: positions and velocities, one array per axis. It
// points at the body's own arrays, or at an integrator's stage (RK4).
struct ParticleState {
    const float *x, *y, *z, *vx, *vy, *vz;
};
ParticleState current_state(const SoftBody& body);

// Listing 8's CalcForce, gravity: the weight m g of every particle.
void add_gravity(Vec3Array& force, float m, const Vec3& g);

// Eq. 23, aerodynamic drag F = -1/2 rho C_D S |v| v, with v the centre-of-mass velocity and S
// the cross-section of the body's bounding sphere at rest, shared among the particles in
// proportion to mass (they share one mass): no torque.
void add_drag(Vec3Array& force, const ParticleState& s, std::size_t n, float rho, float C_D, float rest_radius);

// The mouse's grab: a damped spring from one particle to a point. With no stiffness given, one
// stiff enough to drag the body and soft enough to be stable on its own (h omega = 1).
void add_grab(Vec3Array& force, const ParticleState& s, const Grab& grab, float m, float h);

}  // namespace softbody

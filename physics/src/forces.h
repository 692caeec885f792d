// Internal to the physics library: the forces, each a small function.
//   On a soft body's particles, other than its springs and dampers (pair_forces.h) and the
//   ground's friction (ground_contact.h): each adds its force to `force`, one entry per particle.
//   On a rigid body: each adds to the net force and the torque about its centre of mass.
//   Between bodies: the springs and dampers of link.h.
#pragma once

#include "physics/arrays.h"
#include "physics/link.h"
#include "physics/rigid_body.h"
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
// proportion to mass (they share one mass `m`): no torque.
//
// Integrated implicitly (backward Euler) for the centre of mass rather than explicitly: with
// kappa = rho C_D S / (2 M) and v* the velocity the step would reach without drag (from the
// forces already in `force`, so call it after every force but friction), the new velocity v'
// solves v' = v* - h kappa |v'| v', which has the closed form |v'| = 2 |v*| / (1 + sqrt(1 +
// 4 h kappa |v*|)) along v*; the force applied is M (v' - v*) / h. For a small h kappa |v|
// (any dense or slow body) that is Eq. 23; for a large, light body, whose explicit drag would
// reverse and grow its velocity every step (a 550 m sheet of four particles blew up in four
// ticks), it slows it without ever reversing it: stable at any size. At terminal velocity
// v' = v and g = kappa |v|^2 exactly, as in the continuous law.
void add_drag(Vec3Array& force, const ParticleState& s, std::size_t n, float rho, float C_D, float rest_radius, float m,
              float h);

// The mouse's grab: a damped spring from one particle to a point. With no stiffness given, one
// stiff enough to drag the body and soft enough to be stable on its own (h omega = 1).
void add_grab(Vec3Array& force, const ParticleState& s, const Grab& grab, float m, float h);

// --- Rigid bodies ----------------------------------------------------------------------------
// The net force F and the net torque tau about the centre of mass (Eq. 26, 27, 33).
struct Wrench {
    Vec3d F, tau;
};

// A force F applied at world point p: F, and the torque (p - x) x F (Eq. 27).
void add_force_at(Wrench& w, const RigidMotion& m, const Vec3d& p, const Vec3d& F);

// Gravity acts at the centre of mass: m g, no torque.
void add_rigid_gravity(Wrench& w, const RigidBody& body, const Vec3& g);

// Eq. 23 at the centre of mass (no torque), S the cross-section of the bounding sphere;
// implicit over the step h as add_drag is (call it after the body's other forces).
void add_rigid_drag(Wrench& w, const RigidBody& body, const RigidMotion& m, float rho, float h);

// The mouse's grab on a rigid body: a damped spring from a point of the body (grab.point, body
// axes) to grab.target, acting at that point, so it turns the body.
void add_rigid_grab(Wrench& w, const RigidBody& body, const RigidMotion& m, const Grab& grab, float h);

// --- Between bodies --------------------------------------------------------------------------
// Eq. 21 and Eq. 22 between two points p_a, p_b moving at u_a, u_b: the force on a (on b, its
// opposite). Coincident points have no direction: no force.
Vec3d link_force(const Link& link, const Vec3d& p_a, const Vec3d& u_a, const Vec3d& p_b, const Vec3d& u_b);

}  // namespace softbody

// Internal to the physics library: the integrators, one step of h each. The World evaluates
// the forces (into body.accel[stage]) and calls these in order; see World::step.
//
// Particles (soft bodies), with a = F / m:
//   verlet            x_{n+1} = 2 x_n - x_{n-1} + a h^2,  v_{n+1} = v_n + a h     (Listing 8)
//   symplectic_euler  v_{n+1} = v_n + a h,  x_{n+1} = x_n + v_{n+1} h
//   explicit_euler    x_{n+1} = x_n + v_n h,  v_{n+1} = v_n + a_n h              (Listings 10, 11)
//   rk4               classic Runge-Kutta: four force evaluations (stages 0 to 3)
//
// Rigid bodies: Listing 10's flat array of thirteen numbers a body (P, x, L, q), advanced by
// one implementation of each method for every body, whatever the numbers mean (Listing 11's
// point). The derivative (Listing 9, Eq. 26, 35) is
//   dP/dt = F,  dx/dt = P / m,  dL/dt = tau,  dq/dt = 1/2 w q  with  w = J_world^-1 L (Eq. 36).
//   explicit_euler    y_{n+1} = y_n + h f(y_n)          (Listing 9 exactly; gains energy in free rotation)
//   symplectic_euler  momenta P, L first, then x from the new P, and q turned freely through h
//                     with that L (free_turn): the free rigid body split into its three
//                     principal rotors, each an exact turn, composed symmetrically (Dullweber,
//                     Leimkuhler and McLachlan, 1997). |q| stays as it is, L is kept exactly,
//                     and the energy wanders without drifting however fast and thin the body:
//                     a rod spun about its long axis turns by any angle a step without harm,
//                     where the implicit midpoint rule's fixed-point passes (used before)
//                     diverge once h |L| / I_min passes about 2, and blew a thin cylinder up
//   verlet            for a rigid body, the same as symplectic_euler: position Verlet with Euler
//                     velocities is symplectic Euler when nothing else moves the state, and a
//                     quaternion has no "previous position" to take a difference of
//   rk4               classic Runge-Kutta on the whole array
#pragma once

#include <cstdint>
#include <span>

#include "physics/rigid_body.h"
#include "physics/soft_body.h"
#include "physics/thread_pool.h"

namespace softbody {

// Verlet starts (or restarts, after dt or the integrator changed) from x_{-1} = x_0 - v_0 h:
// its step x_0 - x_{-1} is v_0 h. Call before the force evaluation.
void verlet_start(SoftBody& body, float h);
void verlet_update(SoftBody& body, float h);            // from accel[0]
void symplectic_euler_update(SoftBody& body, float h);  // from accel[0]
void explicit_euler_update(SoftBody& body, float h);    // from accel[0]

// RK4 on d/dt (x, v) = (v, a(x, v)), in stages:
//   rk4_begin before stage 0's forces; for s = 1, 2, 3: rk4_stage(s) makes the stage state
//   (x_tmp, v_stage), the forces at it go to accel[s], then rk4_accumulate(s); rk4_finish.
void rk4_begin(SoftBody& body);
void rk4_stage(SoftBody& body, int s, float h);
void rk4_accumulate(SoftBody& body, int s);
void rk4_finish(SoftBody& body, float h);

// Pinned particles do not move, whatever the integrator made of them.
void hold_pins(SoftBody& body);

// Listing 9's state derivative of one rigid body, given its net force and torque. A fixed
// body's is zero.
void rigid_derivative(const RigidBody& body, const double* y, const Vec3d& F, const Vec3d& tau, double* dy);
// Its momenta's rates alone, dP/dt = F and dL/dt = tau (Eq. 26), the rest zero: all that
// symplectic Euler and Verlet take from it (flat_euler_momenta).
void rigid_momentum_derivative(const RigidBody& body, const Vec3d& F, const Vec3d& tau, double* dy);

// y += h dy, over the whole array (Listing 10's ExplicitEuler call).
void flat_euler(std::span<double> y, std::span<const double> dy, double h);
// Symplectic Euler's two halves: the momentum slots (P, L) by h dy; then every body's x and q
// from `start` (the step's start) moved by the momenta now in `y`; bodies marked in `asleep`
// (empty: none) are left where they are (sleep.h).
void flat_euler_momenta(std::span<double> y, std::span<const double> dy, double h);
void symplectic_positions(std::span<const RigidBody> bodies, std::span<const double> start, std::span<double> y, double h,
                          std::span<const std::uint8_t> asleep = {}, ThreadPool* pool = nullptr);
// q turned through h as a free body with angular momentum L turns (the splitting above), its
// energy 1/2 L . J_world^-1 L kept at what it was at q, or at `energy_target` when one is given.
Quat free_turn(const RigidBody& body, const Quat& q, const Vec3d& L, double h, double energy_target = -1.0);
// q turned a little so that the body's energy 1/2 L . J_world^-1 L is `energy` (|L| kept).
Quat match_energy(const RigidBody& body, const Quat& q, const Vec3d& L, double energy);
// RK4: stage = y + w k; and at the end y += h/6 (k0 + 2 k1 + 2 k2 + k3).
void flat_rk4_stage(std::span<const double> y, std::span<const double> k, double w, std::span<double> stage);
void flat_rk4_finish(std::span<double> y, std::span<const double> k0, std::span<const double> k1,
                     std::span<const double> k2, std::span<const double> k3, double h);
// RK4's stage offsets from the start (h/2, h/2, h for stages 1, 2, 3).
double rk4_stage_offset(int s, double h);

}  // namespace softbody

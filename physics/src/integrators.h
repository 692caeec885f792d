// Internal to the physics library: the integrators, one step of h each. The World evaluates
// the forces (into body.accel[stage]) and calls these in order; see World::step.
//
// Particles (soft bodies), with a = F / m:
//   verlet            x_{n+1} = 2 x_n - x_{n-1} + a h^2,  v_{n+1} = v_n + a h     (Listing 8)
//   symplectic_euler  v_{n+1} = v_n + a h,  x_{n+1} = x_n + v_{n+1} h
//   explicit_euler    x_{n+1} = x_n + v_n h,  v_{n+1} = v_n + a_n h              (Listings 10, 11)
//   rk4               classic Runge-Kutta: four force evaluations (stages 0 to 3)
#pragma once

#include "physics/soft_body.h"

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

}  // namespace softbody

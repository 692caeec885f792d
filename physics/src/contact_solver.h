// Internal to the physics library: the impulses of Eq. 37 and 38 over all of a step's contacts
// at once, with restitution and Coulomb friction, then a position pass that takes out what
// penetration is left. A contact's side a is a rigid body or a soft body's particle (a body of
// mass m with no rotation: Eq. 38 without its rotational term), side b a rigid body or the
// ground (static: 1/m = 0, J^-1 = 0).
//
// Sequential impulses with accumulated clamping (Catto, GDC 2005-2009; the solver of Box2D):
// each contact's impulse along the normal is Eq. 38's lambda for a target normal velocity,
// found again and again a contact at a time, while the total applied at each contact is kept
// non-negative (a contact pushes, never pulls) and friction's total within mu times it
// (Coulomb, in impulse form). The target is to stop the approach (or, for a contact still
// apart at the step's start, to close no more than the gap this step: a speculative contact);
// then a restitution pass gives each contact hit this step the velocity -e v_n, with v_n its
// approach before any impulse. With one contact, no friction and no gap, the two passes
// together are Eq. 38 exactly: lambda = -(1 + e) v_n / (1/m_1 + 1/m_2 + rotational terms).
// Contacts that persist from the last step start from last step's impulses (warm starting), so
// a box resting on another is held at once and does not jitter. The points of one pair of
// bodies (a manifold) are solved as a block: several passes over them before moving on.
//
// Friction at a particle is Eq. 24 and 25 in impulse form: a particle at rest on the surface
// as the step begins is held while the impulse that holds it is at most mu_s times the normal
// impulse, and otherwise takes mu_s times it against its slide (Eq. 24's min); one already
// sliding takes mu_d times it (Eq. 25), and stops when that is enough to stop it. Between
// rigid bodies one mu serves both.
//
// Chosen over Box2D v3's soft step because it works the same after every integrator the world
// offers (the soft step is tied to substepped symplectic Euler), and because its numbers are
// Eq. 38's, which the app shows a student.
#pragma once

#include <span>
#include <vector>

#include "physics/contact.h"
#include "physics/mat3.h"
#include "physics/rigid_body.h"

namespace softbody {

// A rigid body as the solver sees it: its thirteen numbers in the world's flat array, its
// inverse mass and inverse inertia tensor in body axes (zero for fixed ones).
struct SolverBody {
    double* state = nullptr;
    double inv_mass = 0.0;
    Mat3 J_body_inv;
};

// A soft body's particles as the solver sees them: positions, velocities, inverse masses.
struct SolverParticles {
    float *x = nullptr, *y = nullptr, *z = nullptr;
    float *vx = nullptr, *vy = nullptr, *vz = nullptr;
    const float* inv_mass = nullptr;
};

struct SolverSettings {
    double h = 0.02;                // the step, s
    bool speculative = false;       // the positions will follow the new velocities (symplectic
                                    // Euler): a contact apart at the start may close its gap
    double bounce_speed = 0.0;      // slower impacts are resting contact: they bounce with e = 0, m/s
    int velocity_iterations = 20;
    int manifold_passes = 8;        // passes over one manifold within each iteration
    int restitution_iterations = 10;
    int position_iterations = 5;
    double slop = 2e-4;             // m of penetration left alone: contact persists, nothing jitters
    double position_rate = 0.8;     // fraction of the penetration beyond the slop removed per pass
    double max_correction = 0.2;    // m per pass at most
};

// Impulses on the bodies' P and L (Eq. 9, 10, 37) and the particles' velocities. `previous`:
// last step's contacts, whose impulses start the ones that persist.
void solve_contact_velocities(std::vector<RigidContact>& contacts, const std::vector<RigidContact>& previous,
                              std::span<const SolverBody> bodies, std::span<const SolverParticles> particles,
                              const SolverSettings& settings);

// A speculative contact that bounces met its surface part-way through the step, at t = s0 / |v_n|
// with s0 its gap at the start; it should end e (|v_n| h - s0) from the surface, not
// s0 + e |v_n| h as moving the whole step at the bounced velocity leaves it: the bodies go back
// by (1 + e) s0 along the normal, shared by inverse mass, each by its contacts' largest.
void apply_bounce_shifts(const std::vector<RigidContact>& contacts, std::span<const SolverBody> bodies,
                         std::span<const SolverParticles> particles);

// The position pass on x and q (and particles' x): what penetration is left beyond the slop,
// taken out.
void solve_contact_positions(std::vector<RigidContact>& contacts, std::span<const SolverBody> bodies,
                             std::span<const SolverParticles> particles, const SolverSettings& settings);

// Eq. 38's denominator for a unit direction n at offsets r_a, r_b from the centres of mass:
// 1/m_a + 1/m_b + n . ((J_a^-1 (r_a x n)) x r_a) + n . ((J_b^-1 (r_b x n)) x r_b).
double effective_inverse_mass(double inv_m_a, const Mat3& J_inv_a, const Vec3d& r_a, double inv_m_b,
                              const Mat3& J_inv_b, const Vec3d& r_b, const Vec3d& n);

}  // namespace softbody

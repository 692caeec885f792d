// Internal to the physics library: the impulses of Eq. 37 and 38 at every contact of a tick,
// with restitution and Coulomb friction, for whichever integrator moved the bodies.
//
// A contact's side a is a rigid body or a soft body's particle (a body of mass m with no
// rotation: Eq. 38 without its rotational term), side b a rigid body or the ground (static:
// 1/m = 0, J^-1 = 0).
//
// The order of a tick (after Box2D v3's soft step; SOLVER_NOTES in the README's "Choices"):
//   prepare     once a tick, where the tick begins: each contact's anchors r_a, r_b (Eq. 38's r),
//               its effective masses (Eq. 38's denominator, for n and two tangents), the
//               impulses it ended the last tick with (warm starting), and each body's inverse
//               inertia in world axes (Eq. 32), frozen for the tick as the anchors are.
//   substep     after the integrator has moved every body freely through the substep h (its
//               forces, its own scheme: Verlet, symplectic or explicit Euler, RK4):
//                 warm start   the last substep's impulses again (gravity came back with h)
//                 solve        one pass: each point's impulse toward its target normal velocity
//                              (0 at a touching point, minus the gap over h at a point still
//                              apart, a bounded push apart where they overlap: a soft
//                              constraint), then friction within mu times it
//                 restitution  points that were hit: -e times the speed they came in with
//                 positions    the free step's positions moved on by h times the velocity the
//                              contacts changed (and turned by h times the turn they changed)
//                 relax        one pass again without the push apart, so that pushing overlaps
//                              apart leaves no velocity behind (no energy from it)
//   finish      the bounces still due (a point that met its surface in the last substep), and
//               the impulses kept for the next tick.
// The integrators never see a contact: whatever moved the bodies, the impulses act on the
// velocities of the step's end, and the positions follow them. That is what makes the contacts
// work the same under every integrator.
//
// Bounces at the surface: a point still apart when the substep began (a speculative contact)
// may close its gap in the substep and no more; the bounce that throws it back is applied in
// the next substep, once it is there, from the speed it would have met the surface with under
// the substep's acceleration (sqrt(v_n^2 + 2 a s)). A point touching when the substep begins
// bounces in the same substep, before the positions move: one impulse at one instant, so a
// single point without friction takes Eq. 38's lambda = -(1 + e) v_n / denominator exactly.
//
// No energy from contacts: what a contact phase does to the kinetic energy is measured (the
// work of its impulses at the substep's middle velocity, m dv . (v_avg - h g / 2), which for a
// body resting on another is zero, where the plain change of 1/2 m v^2 would count the
// gravity a substep brings and the contact takes away). Restitution may give back at most what
// the contacts of its island took this tick: past that (several points hit at once can ask for
// more under Newton's rule) its impulses are scaled down until it does not.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "physics/arrays.h"
#include "physics/contact.h"
#include "physics/mat3.h"
#include "physics/quat.h"
#include "physics/rigid_body.h"
#include "physics/world.h"

namespace softbody {

struct ContactSettings {
    double dt = 0.02;             // the tick, s
    int substeps = 4;             // of dt
    Vec3d gravity;                // m/s^2: its work is not the contacts' (see above)
    double bounce_speed = 0.4;    // slower impacts are resting contact: e = 0, m/s
    double contact_hertz = 30.0;  // stiffness of the push apart between two moving bodies
    double damping_ratio = 10.0;  // of that push (overdamped: it never overshoots)
    double push_speed = 1.0;      // the fastest an overlap is pushed apart, m/s
    double touching = 5e-4;       // m: a point this close at a substep's start touches (it may bounce there)
    int restitution_passes = 4;   // over the points that bounce in a substep
};

// A soft body's particles as the solver sees them.
struct SolverParticles {
    float *x = nullptr, *y = nullptr, *z = nullptr;
    float *vx = nullptr, *vy = nullptr, *vz = nullptr;
    const float* inv_mass = nullptr;
    float* verlet_x = nullptr;  // Verlet's step x_n - x_{n-1}, kept equal to v h where contacts
    float* verlet_y = nullptr;  // act (null when the integrator is not Verlet)
    float* verlet_z = nullptr;
};

// What the solver needs of the world: the rigid bodies and their flat state now and when the
// tick began and when the substep began, and the particles.
struct ContactWorld {
    std::span<const RigidBody> bodies;
    std::span<double> state;              // Listing 10's flat array, now
    std::span<const double> tick_start;   // as the tick began
    std::span<const double> step_start;   // as the substep began (for each point's approach)
    std::span<SolverParticles> particles;
    std::span<const Vec3Array* const> particle_step_start_v;  // each soft body's v as the substep began
};

// A body in the solver: a rigid body in contact, a particle in contact, or (index 0) the static
// world. Its velocities are the ones the solver changes; the free ones are what the integrator
// left, so that the contacts' share (v - v_free) can move the positions and the momenta.
struct SolverBody {
    enum class Kind : std::uint8_t { Static, Rigid, Particle };
    Kind kind = Kind::Static;
    std::uint32_t index = 0;   // the rigid body, or the particle
    std::int32_t soft = -1;    // the particle's soft body
    double inv_mass = 0.0;
    Mat3 inv_I;                // J_world^-1 (Eq. 32) as the tick began; zero for a particle
    Mat3 I;                    // J_world, its inverse
    Vec3d x0;                  // centre (or particle) as the tick began
    Quat q0;
    Vec3d v, w;                // now
    Vec3d v_free, w_free;      // as the integrator left them this substep
    Vec3d v_start, w_start;    // as the substep began
    Vec3d dp;                  // the centre's move since the tick began
    Mat3 turn;                 // the turn since the tick began
};

struct SolverPoint {
    Vec3d r_a, r_b;            // anchors from the centres as the tick began (Eq. 38's r)
    double s0 = 0.0;           // separation as the tick began (< 0 overlapping), m
    double s = 0.0;            // separation now, m
    double s_start = 0.0;      // as the substep began, m
    double normal_mass = 0.0;  // 1 / Eq. 38's denominator along n
    double tangent_mass[2] = {0.0, 0.0};
    double normal_impulse = 0.0;  // this substep's accumulated impulse (warm-started), N s
    double tangent_impulse[2] = {0.0, 0.0};
    double bounce_impulse = 0.0;  // restitution's, this substep
    double bounce = 0.0;          // > 0: bounces this substep from this speed, m/s
    double bounce_target = 0.0;   // the normal velocity the bounce leaves with
    double pending = 0.0;         // > 0: met its surface in the last substep at this speed
    double total_normal = 0.0, total_tangent[2] = {0.0, 0.0}, total_bounce = 0.0;  // over the tick
    double v_n0 = 0.0;            // v_rel . n as the tick began
    std::uint32_t contact = 0;    // in the tick's list
};

inline constexpr std::uint32_t kMaxManifoldPoints = 4;

struct SolverManifold {
    std::uint32_t a = 0, b = 0;  // solver bodies
    double K[4][4] = {};         // the points' coupling (see solve_block in contact_solver.cpp)
    Vec3d n, t1, t2;
    double mu = 0.0, e = 0.0;
    std::uint32_t first = 0, count = 0;
    std::uint32_t island = 0;
    bool stiff = false;          // against the static world: twice as stiff (Box2D's choice)
    bool bouncing = false;       // some point bounces this substep
};

class ContactSolver {
public:
    // The tick's contacts (their order: a manifold's points next to each other, see
    // RigidContact) and the last tick's (for warm starting by key).
    void prepare(std::vector<RigidContact>& contacts, const std::vector<RigidContact>& previous, const ContactWorld& world,
                 const ContactSettings& settings);
    // One substep: the integrator has moved every body through it already.
    void substep(std::vector<RigidContact>& contacts, const ContactWorld& world);
    // The bounces still due, and the record of what each contact did (RigidContact's fields).
    void finish(std::vector<RigidContact>& contacts, const ContactWorld& world);

    const ContactEnergy& energy() const { return energy_; }

private:
    using Body = SolverBody;
    using Point = SolverPoint;
    using Manifold = SolverManifold;
    void load(const ContactWorld& world);
    void store(const ContactWorld& world, bool move_positions);
    void separations(const ContactWorld& world);
    double work(const Body& body) const;
    void restitute(bool end_of_tick);

    ContactSettings settings_;
    double h_ = 0.0;
    std::vector<Body> bodies_;              // [0]: the static world
    std::vector<Manifold> manifolds_;
    std::vector<Point> points_;
    std::vector<std::int32_t> rigid_index_;  // rigid body -> solver body (0: static or not in contact)
    std::vector<std::uint32_t> island_of_;   // solver body -> island
    std::vector<double> absorbed_;           // per island: energy its contacts took this tick, J
    ContactEnergy energy_;
};

// Eq. 38's denominator for a unit direction n at offsets r_a, r_b from the centres of mass:
// 1/m_a + 1/m_b + n . ((J_a^-1 (r_a x n)) x r_a) + n . ((J_b^-1 (r_b x n)) x r_b).
double effective_inverse_mass(double inv_m_a, const Mat3& J_inv_a, const Vec3d& r_a, double inv_m_b,
                              const Mat3& J_inv_b, const Vec3d& r_b, const Vec3d& n);

// Two unit tangents completing n, chosen from n alone (so that a persisting contact keeps them).
void contact_tangents(const Vec3d& n, Vec3d& t1, Vec3d& t2);

}  // namespace softbody

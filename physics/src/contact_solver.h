// Internal to the physics library: the impulses of Eq. 37 and 38 at every contact of a tick,
// with restitution and Coulomb friction, for whichever integrator moved the bodies.
//
// A contact's side a is a rigid body or a soft body's particle (a body of mass m with no
// rotation: Eq. 38 without its rotational term), side b a rigid body or the ground (static:
// 1/m = 0, J^-1 = 0). The points one pair of bodies touch at (up to four) form a manifold.
//
// The order of a tick (physics/README.md, "Choices the physics makes"):
//   prepare     once, where the contacts were found (the tick's start, or each part of the tick
//               for a body turning fast: World::contact_intervals): each point's anchors r_a, r_b
//               (Eq. 38's r), each manifold's coupling K (Eq. 38's denominators and what one
//               point's impulse does to another's normal velocity) and its inverse, the impulses
//               each point ended the last tick with (warm starting), each body's inverse inertia
//               in world axes (Eq. 32).
//   substep     after the integrator has moved every body freely through the substep h (its
//               forces, its own scheme: Verlet, symplectic or explicit Euler, RK4); the impulses
//               act as the substep began:
//                 warm start   the last substep's impulses again (gravity came back with h)
//                 solve        each manifold's normal impulses together (solve_block: its small
//                              complementarity problem, exactly), toward each point's target
//                              normal velocity: minus the gap over h where it is still apart (a
//                              speculative contact: close it in this substep, no more), a bounded
//                              push apart where it touches or overlaps (a soft spring); then
//                              friction within mu, at the manifold's centre
//                 restitution  points touching as the substep began and coming in fast: -e times
//                              the speed they came in with, at that instant
//                 positions    the free step's positions moved on by h times the velocity the
//                              contacts changed, the turn redone with the new L
//                 relax        the same without the push apart (a few passes), so that pushing
//                              overlaps apart leaves no velocity behind, and no energy
//   finish      the bounces of points that met their surface during the tick, from there, and the
//               impulses kept for the next tick.
// The integrators never see a contact: whatever moved the bodies, the impulses act on the
// velocities of the step's end, and the positions follow them. That is what makes the contacts
// work the same under every integrator.
//
// Bounces at the surface: a point still apart when the substep began may close its gap in the
// substep and no more; it stays there for the rest of the tick, and as the tick ends it leaves
// at -e times the speed it met the surface with under the substep's acceleration
// (sqrt(v_n^2 + 2 a s)): a tick ends with the bodies touching, and a ball watched tick by tick
// turns at the surface, not above it. A point touching as a substep begins bounces in that
// substep, before the positions move: one impulse at one instant, so a single point without
// friction takes Eq. 38's lambda = -(1 + e) v_n / denominator exactly.
//
// No energy from contacts: what a contact phase does is measured as the work of its impulses at
// the substep's middle velocity, m dv . (v_avg - h g / 2) (for a body resting on another that
// is zero, where the plain change of 1/2 m v^2 would count the gravity a substep brings and the
// contact takes away). Restitution may give back at most what the contacts of its island took
// this tick: past that (several points hit at once can ask for more under Newton's rule) its
// impulses are scaled down until it does not. A manifold that bounced starts again from no
// impulse (warm starting from the impulse that stopped it would throw it again).
#pragma once

#include <cmath>
#include <cstdint>
#include <span>
#include <tuple>
#include <utility>
#include <vector>

#include "block_solver.h"
#include "physics/arrays.h"
#include "physics/contact.h"
#include "physics/mat3.h"
#include "physics/quat.h"
#include "physics/rigid_body.h"
#include "physics/thread_pool.h"
#include "physics/world.h"

namespace softbody {

struct ContactSettings {
    double dt = 0.02;             // the tick, s
    int substeps = 4;             // of dt
    Vec3d gravity;                // m/s^2: its work is not the contacts' (see above)
    double bounce_speed = 0.4;    // slower impacts are resting contact: e = 0, m/s
    double contact_hertz = 30.0;  // stiffness of the push apart between two moving bodies, unloaded
    double damping_ratio = 10.0;  // of that push (overdamped: it never overshoots)
    double stack_depth = 5e-4;    // m: a loaded contact is made stiffer so that it stands at most this compressed
    double push_speed = 1.0;      // the fastest an overlap is pushed apart, m/s
    double touching = 5e-4;       // m: a point this close at a substep's start touches (it may bounce there)
    int relax_passes = 3;         // over every manifold after the positions moved, in an interval's last substep
    int early_relax_passes = 2;   // the same in the substeps before it (the next substep's solve takes up the rest)
    bool exact_turn = false;      // symplectic Euler, Verlet: positions' turn by free_turn (see substep)
    bool particle_chord = false;  // RK4, explicit Euler: a particle's step is not h times its end velocity (see substep)
    int restitution_passes = 4;   // over the manifolds that bounce in a substep
};

// A soft body's particles as the solver sees them.
struct SolverParticles {
    float *x = nullptr, *y = nullptr, *z = nullptr;
    float *vx = nullptr, *vy = nullptr, *vz = nullptr;
    const float* inv_mass = nullptr;
    float* verlet_x = nullptr;  // Verlet's step x_n - x_{n-1}, kept equal to v h where contacts
    float* verlet_y = nullptr;  // act (null when the integrator is not Verlet)
    float* verlet_z = nullptr;
    const float* x0 = nullptr;  // where the substep began (the integrator's positions moved on
    const float* y0 = nullptr;  // from there, not always by h times the velocity it left:
    const float* z0 = nullptr;  // RK4 by h/6 of its four stages' velocities, explicit Euler by h v_0)
};

// What the solver needs of the world: the rigid bodies and their flat state now, as the tick
// began and as the substep began, and the particles.
struct ContactWorld {
    std::span<const RigidBody> bodies;
    std::span<double> state;              // Listing 10's flat array, now
    std::span<const double> tick_start;   // as the tick began
    std::span<const double> step_start;   // as the substep began (for each point's approach)
    std::span<SolverParticles> particles;
    std::span<const Vec3Array* const> particle_step_start_v;  // each soft body's v as the substep began
    ThreadPool* pool = nullptr;           // the world's threads (none: this one)
    std::span<const std::uint8_t> asleep; // per rigid body: 1 while it sleeps (static to the particles resting on it: sleep.h)
};

// A soft constraint: a spring of `hertz` with damping ratio `zeta`,
// written for one implicit step of h. bias_rate turns a depth into a velocity; mass_scale and
// impulse_scale soften the impulse so that the push apart is that spring's, whatever the masses.
struct Softness {
    double bias_rate = 0.0, mass_scale = 1.0, impulse_scale = 0.0;
};
inline Softness make_soft(double hertz, double zeta, double h) {
    if (hertz <= 0.0) return {};
    const double omega = 2.0 * 3.14159265358979323846 * hertz;
    const double a1 = 2.0 * zeta + h * omega, a2 = h * omega * a1, a3 = 1.0 / (1.0 + a2);
    return {omega / a1, a2 * a3, a3};
}

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
    Vec3d x0;                  // centre (or particle) as the contacts were found
    Quat q0;
    Mat3 R0_t;                 // the rotation of q0, transposed (anchor_turn's)
    Vec3d x;                   // centre now: as the substep began, then after its positions (the arms are from it)
    Quat q_now;                // orientation at the same moment (and `turn` is its anchor_turn)
    Quat q_ref;                // where inv_I and I were found (and the anchors placed)
    Vec3d L_free, L_start;     // angular momentum after the free step, and as the substep began
    bool refreshed = false;    // they were found again this substep
    Vec3d v, w;                // now
    Vec3d v_free, w_free;      // as the integrator left them this substep
    Vec3d v_start, w_start;    // as the substep began
    bool round = false;        // a sphere: the same surface however it turns (its anchors do not turn with it)
    Vec3d dp;                  // the centre's move from where the contacts were found to the substep's start
    Mat3 turn;                 // the turn of its anchors over the same (none for a round body)
    bool same_start = true;    // the substep began where the last one's positions left it (separate)
    Vec3d dp_free;             // the same to the free step's end
    Vec3d chord;               // a particle's step over h (its chord velocity) less its end velocity
    Mat3 turn_free;
};

// A point as the passes (warm start, solve, relax) see it: all they read and write of it, kept
// apart from the rest (SolverPoint, at the same index), so that each pass streams through as
// little memory as it can. In stack:20 (2,870 cubes) the passes read 78,341 points 20 times a
// tick: 112 bytes of each instead of 312, and a tick on one thread 8% shorter.
struct PassPoint {
    Vec3d c_a, c_b;               // r x n: a turn's share of the normal velocity, w . (r x n)
    double s = 0.0;               // separation now, m
    double offset = 0.0;          // closing speed of the free step's displacement less its end velocity's, m/s
    double normal_mass = 0.0;     // 1 / Eq. 38's denominator along n
    double normal_impulse = 0.0;  // this substep's accumulated impulse (warm-started), N s
    Softness softness;            // of the push apart where it overlaps
    double total_normal = 0.0;    // over the tick (beside the impulse: the sum of each substep's)
};

// A point's gap as the separations see it (twice a substep, every point): the anchors it was
// found with and its separation then, and what they made of it. Apart from SolverPoint for the
// same reason as PassPoint: 72 bytes of each point read, not 200.
struct GapPoint {
    Vec3d r_a0, r_b0;          // anchors from the centres as the contacts were found
    double s0 = 0.0;           // separation as the tick began (< 0 overlapping), m
    double s_start = 0.0;      // as the substep began, m
    double s_moved = 0.0;      // once the substep's positions moved, m
};

struct SolverPoint {
    Vec3d at;                  // where the impulses act (world): the point, or between the two anchors now
    Vec3d r_a, r_b;            // from the centres to it (Eq. 38's r)
    double bounce_impulse = 0.0;  // restitution's, this substep
    double bounce = 0.0;          // > 0: bounces this substep from this speed, m/s
    double bounce_target = 0.0;   // the normal velocity the bounce leaves with
    double pending = 0.0;         // > 0: met its surface this tick at this speed; bounces as it ends
    double total_bounce = 0.0;    // over the tick
    double v_n0 = 0.0;            // v_rel . n as the tick began
    std::uint32_t contact = 0;    // in the tick's list
};

inline constexpr std::uint32_t kMaxManifoldPoints = 4;

// A contact's key, to find it again a tick later: side a's soft body (-1: rigid), a, b, the
// feature that made it.
using ContactKey = std::tuple<std::int32_t, std::uint32_t, std::int32_t, std::uint32_t>;
// A run of one pair's points next to each other in a list of contacts.
struct ContactRun {
    std::tuple<std::int32_t, std::uint32_t, std::int32_t> pair;
    std::uint32_t first = 0, count = 0;
};

struct SolverManifold {
    std::uint32_t a = 0, b = 0;  // solver bodies
    Vec3d n, t[2];
    double mu = 0.0, e = 0.0;
    std::uint32_t first = 0, count = 0;
    std::uint32_t island = 0;
    bool bouncing = false;       // some point bounces in this substep (or as the tick ends)
    // Friction, at the points' centre: its anchors' r x t, effective masses, and impulses
    // (this substep's, warm-started; over the tick); the turn about n and its reach.
    Vec3d ft_a[2], ft_b[2];
    Vec3d fw_a[2], fw_b[2];      // J^-1 (r x t): the turn a unit friction impulse gives each side
    Vec3d nw_a, nw_b;            // J^-1 n: the turn a unit twist gives each side
    double tangent_mass[2] = {0.0, 0.0};
    double friction[2] = {0.0, 0.0}, total_friction[2] = {0.0, 0.0};  // (the total: totals())
    double twist_mass = 0.0, twist_radius = 0.0, twist = 0.0;
    // Rolling resistance: C_rr r (the largest torque per unit normal force), what stops the
    // two sides' relative turn (the inverse of J_a^-1 + J_b^-1), and its angular impulse.
    double roll_arm = 0.0;
    Mat3 roll_mass;
    Vec3d roll;
    // The points' coupling K (K_ij: point i's change of normal velocity per unit impulse at
    // point j), and what solves it for all points pushing (block_solver.h).
    double K[4][4] = {};
    BlockSolve block;
};

class ContactSolver {
public:
    // The tick's contacts (a manifold's points next to each other: RigidContact's order) and
    // the last tick's (for warm starting by key).
    void prepare(std::vector<RigidContact>& contacts, const std::vector<RigidContact>& previous, const ContactWorld& world,
                 const ContactSettings& settings);
    // One substep: the integrator has moved every body through it already.
    void substep(const ContactWorld& world);
    // The bounces due (points that met their surface in the tick), the record of what each
    // contact did (RigidContact's fields), and what the next tick starts from.
    void finish(std::vector<RigidContact>& contacts, const ContactWorld& world);

    const ContactEnergy& energy() const { return energy_; }

private:
    using Body = SolverBody;
    using Point = SolverPoint;
    using Manifold = SolverManifold;
    void setup(Manifold& m);
    void load(const ContactWorld& world);
    // A rigid body's inertia and anchors found again where it has turned far enough (true: they
    // were), then its manifolds' points and couplings, once every body has been looked at.
    bool refresh(const ContactWorld& world, Body& s);
    void refresh_manifolds();
    void store(const ContactWorld& world);
    // Asks for the lines of a manifold's two bodies that a visit reads and writes (v, w, 1/m,
    // J^-1), a few manifolds ahead of its visit: a pile's bodies do not all fit in the cache.
    void fetch_bodies(const SolverManifold& m) const;
    void separate(const SolverManifold& m, bool moved);
    void separations(bool moved);
    void restitute(bool after_positions);
    void forget_bounced();
    void forget_if_bounced(SolverManifold& m);
    void totals();
    void add_to_totals(SolverManifold& m);
    double work(const Body& body, bool shown) const;
    // A manifold as found: its first contact in the tick's list, how many, its two bodies.
    struct FoundManifold {
        std::uint32_t contact = 0, count = 0, a = 0, b = 0;
    };
    void slabs(std::span<const FoundManifold> found);
    // What prepare(), slabs() and restitute() work with and drop, kept from tick to tick with its
    // memory (kept_memory.h): the last tick's contacts by key, which of them each contact takes
    // over, the manifolds as found, the slabs', the islands' and the bounces' working lists.
    // A manifold as the scan of the contacts finds it, before its bodies are numbered: its
    // first contact, how many, and whose they are (RigidContact's soft, a and b).
    struct FoundPoints {
        std::uint32_t contact = 0, count = 0;
        std::int32_t soft = -1, b = -1;
        std::uint32_t a = 0;
    };
    struct Buffers {
        std::vector<ContactRun> runs;
        std::vector<std::vector<ContactRun>> run_parts;         // per chunk of the scan
        std::vector<std::vector<FoundPoints>> found_parts;      // per chunk of the scan
        std::vector<std::uint32_t> run_at;
        std::vector<std::pair<ContactKey, std::uint32_t>> last;
        std::vector<char> taken;
        std::vector<std::uint32_t> first_finder;
        std::vector<std::int64_t> match;
        std::vector<std::vector<std::int32_t>> particle_index;
        std::vector<std::uint32_t> body_of;  // each solver body's rigid body or particle (by kind, below)
        std::vector<std::int32_t> soft_of;   // its particle's soft body, -1 for a rigid body
        std::vector<FoundManifold> found;
        std::vector<std::uint32_t> first_point;
        std::vector<std::uint32_t> parent;
        std::vector<std::int64_t> number;
        std::vector<std::pair<double, std::uint32_t>> by_place;
        std::vector<std::uint32_t> slab, group, count, at;
        std::vector<std::uint32_t> bouncing;  // restitute()'s manifolds
    };
    void solve_manifold(Manifold& m, bool bias);
    void warm_start(Manifold& m);
    // f(i) for every i below count, on the pool's threads when there are enough: only for items
    // that write nothing another item reads (each body's own state, each manifold's own points).
    template <class F>
    void parallel(std::size_t count, std::size_t grain, const F& f);
    // f(b) for every moving body b, the same way, slab by slab (body_order_): each phase's
    // chunks of them go to the same threads, so a body's lines stay in one core's cache.
    template <class F>
    void each_body(const F& f);
    // f(manifold, pass) for every manifold, `passes` times: in each pass the slabs' at once, each
    // slab's in order, then those across. A group of the next pass may start as soon as every
    // group of this one that shares a slab with it is done (no wait for the whole pass).
    template <class F>
    void each_in_slabs(int passes, const F& f);
    template <class F>
    void chain_in_slabs(int first, int passes, const F& f);

    ContactSettings settings_;
    double h_ = 0.0;
    int substeps_done_ = 0;  // of the interval prepared (the last relaxes more: ContactSettings)
    std::vector<Body> bodies_;              // [0]: the static world
    std::vector<Manifold> manifolds_;
    std::vector<Point> points_;
    std::vector<PassPoint> pass_;            // points_[k]'s part the passes read
    std::vector<GapPoint> gap_;              // and the part the separations read
    std::vector<std::int32_t> rigid_index_;  // rigid body -> solver body (0: static or not in contact)
    std::vector<std::uint32_t> island_of_;   // solver body -> island
    std::vector<double> absorbed_;           // per island: energy its contacts took this tick, J
    std::vector<std::pair<double, double>> body_work_;  // per body: work() exact and as shown, this substep
    ContactEnergy energy_;
    // The manifolds by group (slabs()), laid out in that order (prepare): group c is
    // manifolds_[slab_start_[c]] up to manifolds_[slab_start_[c + 1]]. First each slab's (no two
    // sharing a moving body), then each boundary's between two neighbouring slabs, then those
    // across slabs further apart (each_in_slabs). slab_order_[i] is which manifold as found is
    // manifolds_[i]; found_order_ the other way round (the order of the loops whose bits depend
    // on it: restitution's rounds, the particles' chords).
    std::vector<std::uint32_t> slab_order_;
    std::vector<std::uint32_t> slab_start_;
    std::vector<std::uint32_t> found_order_;
    std::vector<std::uint32_t> body_order_;  // the moving bodies, slab after slab (each_body)
    ThreadPool* pool_ = nullptr;
    Buffers buffers_;
};

// Eq. 38's denominator for a unit direction n at offsets r_a, r_b from the centres of mass:
// 1/m_a + 1/m_b + n . ((J_a^-1 (r_a x n)) x r_a) + n . ((J_b^-1 (r_b x n)) x r_b).
double effective_inverse_mass(double inv_m_a, const Mat3& J_inv_a, const Vec3d& r_a, double inv_m_b,
                              const Mat3& J_inv_b, const Vec3d& r_b, const Vec3d& n);

// Two unit tangents completing n, chosen from n alone (so that a persisting contact keeps them).
void contact_tangents(const Vec3d& n, Vec3d& t1, Vec3d& t2);

}  // namespace softbody

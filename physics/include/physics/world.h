// The world: its settings (dt, gravity, integrator, substeps, ground, air, friction,
// restitution), its soft bodies (Listing 8), its rigid bodies (Listings 9-11), the springs
// between bodies, and one fixed tick that advances them all.
//
// tick() is the step in order and nothing else (world.cpp): forces, integration, contacts,
// checks. Each of those lives in a file of its own, named for its concept.
//
// Soft bodies collide with one another: each particle with the other bodies' surfaces, and
// with its own body's where that body asks for it (self_collision; soft_contacts.h). Each
// feels its own springs and dampers, gravity, drag, the ground, the rigid bodies its particles
// touch, the other soft bodies and the springs attached to it.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "physics/arrays.h"
#include "physics/broad_phase.h"
#include "physics/collide.h"
#include "physics/contact.h"
#include "physics/link.h"
#include "physics/mesh.h"
#include "physics/defs.h"
#include "physics/ids.h"
#include "physics/keys.h"
#include "physics/rigid_body.h"
#include "physics/soft_body.h"
#include "physics/thread_pool.h"

namespace softbody {

struct RigidContactScratch;  // rigid_contacts.h
class ContactSolver;         // contact_solver.h
class SoftContacts;          // soft_contacts.h
struct ContactWorld;
struct SolverParticles;

enum class Status { Ok, Diverged };

// The least substeps a tick with contacts runs (their soft step, contact_solver.h).
inline constexpr int kContactSubsteps = 4;
// With automatic substeps, no rigid body turns more than kMaxTurn in one substep (rad; under RK4
// and explicit Euler kMaxTurnRK4), nor, under those two, more than kMaxStiffTurn at the rate
// |L| / I_min a thin body's long axis can reach (World::rotation_substeps), up to
// kMaxRotationSubsteps a tick.
inline constexpr double kMaxTurn = 0.5;
inline constexpr double kMaxTurnRK4 = 0.1;
inline constexpr double kMaxStiffTurn = 2.0;
inline constexpr int kMaxRotationSubsteps = 1000;

// The energy contacts took (< 0) or gave over a tick, J, and how much of it was restitution's.
struct ContactEnergy {
    double total = 0.0;
    double restitution = 0.0;
};

struct Energy {
    double kinetic = 0.0;      // sum 1/2 m |v|^2, plus each rigid body's 1/2 |P|^2 / m + 1/2 L . w
    double rotational = 0.0;   // the rigid bodies' part of that: sum 1/2 L . w
    double gravity = 0.0;      // sum -m (g . x)
    double elastic = 0.0;      // sum over springs 1/2 k (l - l0)^2, every pair's and every link's
    double total() const { return kinetic + gravity + elastic; }
};

// How close the explicit step is to blowing up, for the fastest mode of the network.
struct Stability {
    double omega_max = 0.0;     // highest natural frequency sqrt(k lambda / m), rad/s
    double gamma_max = 0.0;     // damping rate of that mode, c lambda / m, 1/s
    double h = 0.0;             // step: dt / substeps in use
    double h_omega = 0.0;       // sqrt(h^2 omega^2 + 2 h gamma): h*omega without dampers
    double limit = 2.0;         // h_omega must stay below this (Verlet / symplectic Euler)
    double growth = 1.0;        // largest per-step amplification over the modes (> 1: grows)
    bool stable = true;
    int substeps = 1;           // in use
    int substeps_needed = 1;    // fewest that keep every mode stable (0: none up to 1000)
};

// A damped spring from a particle, or a point of a rigid body, to a point in space: the mouse
// grab of the interactive demo.
struct Grab {
    std::uint32_t particle = 0;
    Vec3 target;
    float stiffness = 0.0f;     // N/m; 0 picks one that moves the body briskly
    std::uint32_t body = 0;     // which soft body, or which rigid body when `rigid`
    bool rigid = false;
    Vec3d point;                // on a rigid body: the grabbed point, body axes from the centre of mass
    bool operator==(const Grab&) const = default;
};

// Which rigid bodies sleep, and how long each has been at rest (sleep.h says what these mean).
// Part of the state a tick carries into the next: a snapshot holds it, so time travel replays
// a body's falling asleep and waking exactly.
inline constexpr std::uint32_t kAwake = 0xFFFFFFFFu;
inline constexpr std::size_t kRestPoseSize = 7;
struct SleepState {
    std::vector<double> rest_time;        // per rigid body: s it has been at rest (sleep.h)
    std::vector<double> rest_pose;        // per rigid body: its centre (3) and orientation (4) as its rest began
    std::vector<std::uint32_t> island;    // per rigid body: kAwake, or the island it sleeps in (its first body's index)
    std::vector<double> deepest;          // per rigid body: its deepest contact with another as the last tick ended, m
    // Each sleeping island's contacts as it fell asleep, in their order then (by island: its
    // first body's index): its warm start on waking.
    std::vector<std::vector<RigidContact>> contacts;
    std::size_t sleeping = 0;             // bodies asleep
};

// Everything a tick carries into the next, copied out (World::snapshot): restored, the world
// goes on exactly as it did from that moment (the same bits). It holds what the world held
// then: each body and spring with its id and its definition (as built, and its keys as they
// were), so a body destroyed since is made again and one made since is unmade. The grab and
// the live keys of each tick are the history's to replay (history.h), not the snapshot's.
struct WorldSnapshot {
    struct Soft {
        SoftBodyDef built, def;  // what its particles were made from, and its keys then
        Vec3Array x, v, verlet_step, x_tick_prev;
        FloatArray inv_mass;  // pins
        float verlet_h = 0.0f;
    };
    std::vector<Soft> soft;
    IdTable<SoftBodyTag> soft_ids;
    IdTable<RigidBodyTag> rigid_ids;
    IdTable<SpringTag> spring_ids;
    std::vector<RigidBodyDef> rigid_built, rigid_defs;
    std::vector<SpringDef> springs;
    std::vector<Link> links;  // the springs resolved, rest lengths as measured
    std::vector<double> rigid, rigid_tick_prev;  // Listing 10's flat state, now and a tick before
    std::vector<RigidContact> contacts;          // the last step's: the next one starts from them
    PairCache pair_cache;                        // the narrow phase's last answers
    std::uint64_t ticks = 0;
    Status status = Status::Ok;
    std::string divergence;
    double energy_baseline = 0.0, energy_scale = 0.0;
    bool energy_baseline_stale = true;
    SleepState sleep;

    std::size_t bytes() const;  // the memory it holds
};

struct WorldOptions {
    int threads = 1;
    bool reference_kernel = false;  // use the readable one-pair-at-a-time loop
};

// The world: a WorldDef's settings and things, made once, then added to and taken from while it
// runs, each thing by its typed id (ids.h) or by its name; and the tick that advances them all.
class World {
public:
    // Makes every body and spring of `def` in order. Throws InputError (naming the body or
    // spring and the key) for an invalid key, a mesh that cannot be loaded, pins that name no
    // vertex, twice the same name, or a spring whose end names no body, a vertex that does not
    // exist, or a point where a vertex is needed.
    explicit World(const WorldDef& def, WorldOptions options = {});
    ~World();
    World(const World&) = delete;
    World& operator=(const World&) = delete;

    // One fixed tick of settings().dt, in substeps. Does nothing once diverged.
    void tick();
    void run(std::uint64_t ticks);

    // Back to the start: every body built again from its definition as it is now (keys that
    // apply on reset take effect) and placed as it was; the bodies added since are kept.
    void reset();
    // A key that applies on reset differs from what its body was built with.
    bool reset_pending() const;

    // --- What is in it: made and unmade while it runs -------------------------------------------
    // Each throws InputError (the world unchanged) as the constructor says. A new body starts
    // as its definition says, the others go on from where they are. Destroying a body destroys
    // the springs attached to it, and wakes every rigid body.
    SoftBodyId create_soft_body(SoftBodyDef def);
    RigidBodyId create_rigid_body(const RigidBodyDef& def);
    SpringId create_spring(const SpringDef& def);
    void destroy(SoftBodyId id);
    void destroy(RigidBodyId id);
    void destroy(SpringId id);

    // Ids by position (0 to count - 1: the order they are stepped in) and by name, and back.
    // index() throws InputError for an id that names nothing (destroyed, or never made).
    SoftBodyId soft_body_id(std::size_t index) const { return soft_ids_.at(index); }
    RigidBodyId rigid_body_id(std::size_t index) const { return rigid_ids_.at(index); }
    SpringId spring_id(std::size_t index) const { return spring_ids_.at(index); }
    std::size_t index(SoftBodyId id) const;
    std::size_t index(RigidBodyId id) const;
    std::size_t index(SpringId id) const;
    bool contains(SoftBodyId id) const { return soft_ids_.contains(id); }
    bool contains(RigidBodyId id) const { return rigid_ids_.contains(id); }
    bool contains(SpringId id) const { return spring_ids_.contains(id); }
    std::optional<SoftBodyId> find_soft_body(std::string_view name) const;
    std::optional<RigidBodyId> find_rigid_body(std::string_view name) const;
    std::optional<SpringId> find_spring(std::string_view name) const;

    // --- Keys --------------------------------------------------------------------------------
    // Keys that apply at once do so from the next tick; the others (keys.h: on_reset) at the
    // next reset(). Each setter validates and throws InputError, leaving everything unchanged.
    const WorldSettings& settings() const { return settings_; }
    void set_settings(const WorldSettings& settings);
    const SoftBodyDef& def(SoftBodyId id) const { return soft_[index(id)].def; }
    const RigidBodyDef& def(RigidBodyId id) const { return rigid_defs_[index(id)]; }
    const SpringDef& def(SpringId id) const { return spring_defs_[index(id)]; }
    void set_def(SoftBodyId id, const SoftBodyDef& def);
    void set_def(RigidBodyId id, const RigidBodyDef& def);
    void set_def(SpringId id, const SpringDef& def);
    // One key by the name a scene and `--set` use: "dt" (the world's), "stiffness" (every soft
    // body's), "bob.mass", "spring.stiffness" (the thing named so). Throws InputError naming it.
    void set_key(std::string_view name, const KeyValue& value);
    void set_key_text(std::string_view name, std::string_view text);
    KeyValue key(std::string_view name) const;
    // The world as it stands now: its settings and every thing's definition (what a saved
    // preset holds).
    WorldDef def() const;

    // Time travel: the state as it is now, and back to a state taken earlier from this world,
    // its bodies and springs too (those made since are unmade, those destroyed since made again).
    WorldSnapshot snapshot() const;
    void restore(const WorldSnapshot& snapshot);

    void set_threads(int threads);
    int threads() const { return pool_->threads(); }

    // Interaction (the app's mouse): pin or free a particle of a soft body (kept in its
    // definition's `pinned`, as a vertex, so it survives a reset), or pull one toward a point.
    void set_pinned(std::size_t body, std::uint32_t particle, bool pinned);
    // A grabbed rigid body wakes (with its island), and does not sleep while held.
    void set_grab(std::optional<Grab> grab);
    const std::optional<Grab>& grab() const { return grab_; }

    Status status() const { return status_; }
    const std::string& divergence() const { return divergence_; }  // why it stopped, and what to change

    std::uint64_t ticks() const { return ticks_; }
    double time() const { return static_cast<double>(ticks_) * static_cast<double>(settings_.dt); }

    // --- Rigid bodies: Listing 10's thirteen numbers each (rigid::P, X, L, Q) -------------------
    std::size_t rigid_body_count() const { return rigid_.size(); }
    const RigidBody& rigid_body(std::size_t i) const { return rigid_[i]; }
    const double* rigid_state(std::size_t i) const { return &y_[i * rigid::kStateSize]; }
    // The state at the start of the last tick: the renderer draws between it and the current one.
    const double* rigid_previous_state(std::size_t i) const { return &y_tick_prev_[i * rigid::kStateSize]; }
    RigidMotion rigid_motion(std::size_t i) const { return softbody::rigid_motion(rigid_[i], rigid_state(i)); }
    // Sleeping (the `sleeping` key, sleep.h): an island of rigid bodies all at rest for a while
    // sleeps, costs nothing but its broad-phase box, and wakes when touched by an awake body or
    // a particle, grabbed, or when a key changes.
    bool rigid_asleep(std::size_t i) const { return sleep_.island[i] != kAwake; }
    // How long the body has been at rest (sleep.h), s; 0 while it moves.
    double rigid_rest_time(std::size_t i) const { return sleep_.rest_time[i]; }
    std::size_t sleeping_count() const { return sleep_.sleeping; }
    // Wakes body i's island (nothing when it is awake).
    void wake_rigid(std::size_t i);
    void wake_all();
    // Contacts of the last step: rigid bodies with the ground and with one another, and soft
    // bodies' particles with rigid bodies (RigidContact::soft). A sleeping island's are not
    // among them (they are not solved).
    const std::vector<RigidContact>& contacts() const { return contacts_; }
    // Soft bodies' particles against other soft bodies' surfaces (and their own, with
    // self_collision) that pushed in the last substep.
    const std::vector<SoftContact>& soft_contacts() const;
    // Eq. 38 term by term for one of them, with the bodies' inertia where they are now.
    ImpulseTerms impulse_terms(const RigidContact& contact) const;
    // The springs between bodies, resolved (each with its definition at the same index).
    std::size_t spring_count() const { return links_.size(); }
    const std::vector<Link>& links() const { return links_; }
    // Where each end of a link is now (world, m).
    Vec3d link_end_position(const LinkEnd& end) const;
    // What was decided for the user while building (a normalised quaternion, a hull's mass).
    const std::vector<std::string>& notes() const { return notes_; }

    // Totals over every body, particles included: linear momentum, and angular momentum about
    // the origin (each rigid body's x x P + L, each particle's x x m v).
    Vec3d momentum() const;
    Vec3d angular_momentum() const;

    // --- Soft bodies ----------------------------------------------------------------------------
    std::size_t soft_body_count() const { return soft_.size(); }
    const SoftBody& soft_body(std::size_t i) const { return soft_[i]; }

    // --- Diagnostics (energy.cpp, stability.cpp) ----------------------------------------------
    Energy energy();
    Vec3 center_of_mass(std::size_t soft_body) const;  // of one soft body's particles
    Vec3 center_of_mass() const;                       // of everything that moves, by mass
    float min_z() const;          // the lowest point of any body: particle, sphere or hull vertex
    Stability stability() const;  // the least stable soft body's
    // Substeps of the last tick: the springs' need (stability), the rigid bodies' turns, or at
    // least kContactSubsteps in a tick with contacts.
    int substeps_in_use() const { return tick_substeps_; }
    // How many times the last tick found the rigid bodies' contacts: once, or while a body with a
    // contact turns faster than its shape allows (CollisionShape::contact_turn), once for each
    // part of the tick that takes (contact_intervals).
    int contact_finds() const { return tick_finds_; }
    // What the contacts did to the kinetic energy in the last tick (< 0: took it), J, and
    // restitution's share of it (contact_solver.h says how it is measured).
    const ContactEnergy& contact_energy() const { return contact_energy_; }
    std::uint64_t state_hash() const;  // FNV-1a over the bits of every x and v, and every rigid state
    // How many times something from outside changed the world's energy (a key, a grab, a pin,
    // a body made, unmade or restored, a reset): between two ticks with the same count, only the
    // world's own forces and contacts changed it (energy_ledger.h).
    std::uint64_t outside_changes() const { return outside_changes_; }

private:
    void build();
    // The bodies and springs changed (made, unmade, restored): every per-body array follows.
    void structure_changed();
    void check_new_name(const std::string& name) const;
    SoftBody make_soft_body(const SoftBodyDef& def, const SoftBodyDef* built = nullptr);
    Link resolve_link(const SpringDef& def, const std::string& what) const;
    ThingNames thing_names() const;
    void update_substeps();
    void step(float h);
    void note_motions();
    int rotation_substeps(double time) const;
    void find_contacts(double reach);
    void generate_contacts(double reach);
    void add_woken_contacts(double reach, const std::vector<std::uint8_t>& was_asleep);
    void reset_sleep();
    bool wake_touched_islands();
    void islands_touched(const RigidContact& c, std::vector<std::uint32_t>& out) const;
    void wake_islands(std::vector<std::uint32_t> islands, std::vector<RigidContact>& warm);
    void update_sleep();
    int begin_contacts(double interval, int steps);
    int contact_intervals(double time);
    int soft_contact_substeps(double part);
    void update_contact_substeps();
    ContactWorld contact_world();
    void evaluate_forces(int stage, bool record_contacts);
    void rigid_forces(int stage, std::size_t b, const std::vector<double>& y, bool momenta_only);
    void evaluate_links(int stage);
    double link_inverse_mass(const Link& link) const;
    void check_divergence();
    void take_energy_baseline();
    double kinetic_plus_gravity() const;

    WorldSettings settings_;
    std::vector<SoftBody> soft_;
    std::vector<RigidBody> rigid_;
    std::vector<RigidBodyDef> rigid_built_, rigid_defs_;  // each rigid body's definition: as built, and now
    std::vector<CollisionShape> shapes_;  // each rigid body's, beside it
    std::vector<Link> links_;
    std::vector<SpringDef> spring_defs_;  // each link's
    IdTable<SoftBodyTag> soft_ids_;
    IdTable<RigidBodyTag> rigid_ids_;
    IdTable<SpringTag> spring_ids_;
    std::vector<std::string> notes_;

    // The rigid bodies' flat state (Listing 10), the same at the start of the tick, the last
    // good one, and the integrators' stages and derivatives.
    std::vector<double> y_, y_tick_prev_, y_good_, y_stage_, y_step_start_, k_[4];
    std::vector<double> y_contacts_start_;  // where the last contacts were found (their anchors' frame)
    std::vector<Vec3d> link_force_on_rigid_, link_torque_on_rigid_;
    std::vector<std::vector<std::pair<std::uint32_t, Vec3>>> link_force_on_particles_;  // per soft body
    std::vector<RigidContact> contacts_, previous_contacts_;
    std::vector<std::uint8_t> contact_touching_;   // which rigid bodies have a contact (contact_intervals)
    // Each awake rigid body's rigid_motion where it is (note_motions): as each part of the tick
    // begins, for its substep count, its boxes, its ground contacts and the contact intervals, and
    // as the tick ends, for the divergence check and the sleep, worked out once for each. A
    // sleeping or fixed body's entry is not kept up to date (none of them reads it); a body that
    // wakes has its own worked out as it wakes.
    std::vector<RigidMotion> motion_;
    std::unique_ptr<RigidContactScratch> rigid_contact_scratch_;  // the broad phase's buffers
    std::unique_ptr<ContactSolver> solver_;
    std::unique_ptr<SoftContacts> soft_contacts_;  // soft against soft (soft_contacts.h)
    bool soft_touching_ = false;                   // the tick has soft-soft pairs within reach
    std::vector<SolverParticles> solver_particles_;
    std::vector<const Vec3Array*> solver_particle_v_;
    ContactEnergy contact_energy_;
    std::unique_ptr<ThreadPool> pool_;
    bool reference_kernel_;

    std::uint64_t ticks_ = 0;
    int substeps_ = 1;       // what the springs need (update_substeps)
    std::vector<int> contact_substeps_;  // per soft body: what its contacts need (update_substeps)
    std::vector<std::uint8_t> soft_in_contact_;  // per soft body: within reach of a contact this tick
    int tick_substeps_ = 1;  // what the last tick ran
    int tick_finds_ = 0;     // and how many times it found the rigid contacts
    Status status_ = Status::Ok;
    std::string divergence_;
    std::optional<Grab> grab_;
    SleepState sleep_;
    std::vector<std::uint8_t> asleep_;  // per rigid body: 1 while it sleeps (sleep_.island != kAwake), for the loops

    // Energy at the last outside change (reset, params, pins, grab), for divergence detection.
    double energy_baseline_ = 0.0;  // total energy then, J
    double energy_scale_ = 0.0;     // energy in play then: kinetic + elastic + weight x height, J
    bool energy_baseline_stale_ = true;
    std::uint64_t outside_changes_ = 0;
    void changed_from_outside() {
        energy_baseline_stale_ = true;
        ++outside_changes_;
    }
};

}  // namespace softbody

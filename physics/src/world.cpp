// The world's tick, in order: forces, integration, contacts, checks. What each of those does
// lives in its own file: forces.cpp, pair_forces.cpp, ground_contact.cpp, contact_solver.cpp,
// integrators.cpp, divergence.cpp (and stability.cpp, energy.cpp for what the world reports).
#include "physics/world.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>

#include "contact_solver.h"
#include "forces.h"
#include "ground_contact.h"
#include "integrators.h"
#include "kept_memory.h"
#include "message_text.h"
#include "particle_contacts.h"
#include "rigid_contacts.h"
#include "sleep.h"
#include "soft_contacts.h"
#include "stability.h"
#include "physics/error.h"

namespace softbody {

namespace {

// The slowest impact that bounces when there is no gravity to set the scale (m/s).
constexpr double kRestingSpeed = 0.01;

// The most h omega_max a substep may have while a soft body's particles are in contact
// (World::update_substeps): a contact stops a particle as its substep begins and moves it on by
// h times the velocity it changed, so the particle stands h dv off the path its springs
// followed in the step, and they store 1/2 K (h dv)^2 of the 1/2 m dv^2 the contact took. For a
// particle on a body's surface pushed along the normal K is about half of k N (half the
// pairs' directions lie along it), so the springs get (h omega_max)^2 / 2 of it, omega_max^2 = k
// N / m. At 1 that is at most half: a contact only ever takes energy. Near a step's stability
// limit (2 under Verlet and symplectic Euler, 2.8 under RK4) it is 2 to 4 times what was
// taken: two soft balls meeting at 20 m/s under RK4 at h omega 2.3 gained half their energy in
// the tick they met and passed through each other.
// And at least the substeps symplectic Euler needs for the body: the contacts' step is its step
// (an impulse as the substep begins, the positions moved on by h times it), and where its
// velocities follow their positions no looser. RK4 is stable at h gamma up to 2.8 against
// symplectic Euler's 2; there a stiff body's fast overdamped mode (the dampers, c N / m) hardly
// decays from one step to the next, its velocity stops saying where its particles go, and a
// contact that sees a particle leaving at 2 m/s watches it sink on: in a pile of seven under
// RK4 at h gamma 2.9 a cube's particle went 14 cm into a ball.
constexpr double kContactStepOmega = 1.0;

}  // namespace

const std::vector<SoftContact>& World::soft_contacts() const { return soft_contacts_->contacts(); }

// What each soft body's contacts need (contact_substeps_): h omega_max <= kContactStepOmega with
// its springs up to 25% stiffer (as the stability estimate allows for), and symplectic Euler's
// stable step, whatever the integrator: the contacts act the same in every one
// (contact_solver.h).
void World::update_contact_substeps() {
    contact_substeps_.assign(soft_.size(), 1);
    WorldSettings symplectic = settings_;
    symplectic.integrator = Integrator::SymplecticEuler;
    for (std::size_t b = 0; b < soft_.size(); ++b) {
        const SoftBody& body = soft_[b];
        const double n = double(body.particle_count());
        if (n < 2.0 || !(body.mass > 0.0f)) continue;
        const double omega = std::sqrt(1.25 * double(body.stiffness) * n / double(body.mass));
        const int stable = soft_body_stability(body, symplectic, 1).substeps_needed;
        contact_substeps_[b] = int(std::min(1000.0, std::ceil(double(settings_.dt) * omega / kContactStepOmega - 1e-9)));
        contact_substeps_[b] = stable > 0 ? std::max(contact_substeps_[b], stable) : 1000;
    }
}

// The substeps the soft bodies in contact need over `part` of the tick: the most any of them
// needs (contact_substeps_), 1 when none is in contact. In contact: a particle within reach of
// a rigid body (contacts_), or a soft pair or a rigid point within reach of its surface.
int World::soft_contact_substeps(double part) {
    soft_in_contact_.assign(soft_.size(), 0);
    if (soft_touching_) soft_contacts_->mark_touching(soft_in_contact_);
    for (const RigidContact& c : contacts_) {
        if (c.soft >= 0) soft_in_contact_[std::size_t(c.soft)] = 1;
    }
    int most = 1;
    for (std::size_t b = 0; b < soft_.size(); ++b) {
        if (soft_in_contact_[b]) most = std::max(most, contact_substeps_[b]);
    }
    return std::max(1, int(std::ceil(double(most) * part - 1e-9)));
}

// ---------------------------------------------------------------------------------------------
// Forces at one stage of the step: stage 0 is the current state, stages 1 to 3 are RK4's.
// ---------------------------------------------------------------------------------------------

// Eq. 21, 22 and 33: every link's force on its two ends, from the bodies' state at this stage.
void World::evaluate_links(int stage) {
    std::fill(link_force_on_rigid_.begin(), link_force_on_rigid_.end(), Vec3d{});
    std::fill(link_torque_on_rigid_.begin(), link_torque_on_rigid_.end(), Vec3d{});
    for (auto& list : link_force_on_particles_) list.clear();
    const std::vector<double>& y = stage == 0 ? y_ : y_stage_;
    const auto end_state = [&](const LinkEnd& end, Vec3d& p, Vec3d& u, RigidMotion& m) {
        switch (end.kind) {
            case LinkEnd::Kind::World:
                p = end.point;
                u = {};
                break;
            case LinkEnd::Kind::Rigid: {
                m = softbody::rigid_motion(rigid_[end.body], &y[end.body * rigid::kStateSize]);
                const Vec3d r = m.R * end.point;
                p = m.x + r;
                u = m.v + cross(m.omega, r);  // the velocity of a point of a turning body
                break;
            }
            case LinkEnd::Kind::Soft: {
                const SoftBody& body = soft_[end.body];
                const std::uint32_t i = end.particle;
                const bool staged = stage != 0;
                const Vec3 x = staged ? body.x_tmp[i] : body.x[i], v = staged ? body.v_stage[i] : body.v[i];
                p = Vec3d(x);
                u = Vec3d(v);
                break;
            }
        }
    };
    const auto apply = [&](const LinkEnd& end, const Vec3d& p, const RigidMotion& m, const Vec3d& F) {
        if (end.kind == LinkEnd::Kind::Rigid) {
            link_force_on_rigid_[end.body] += F;
            link_torque_on_rigid_[end.body] += cross(p - m.x, F);  // Eq. 33: r x F
        } else if (end.kind == LinkEnd::Kind::Soft) {
            link_force_on_particles_[end.body].emplace_back(end.particle, to_float(F));
        }
    };
    for (const Link& link : links_) {
        Vec3d p_a, u_a, p_b, u_b;
        RigidMotion m_a, m_b;
        end_state(link.a, p_a, u_a, m_a);
        end_state(link.b, p_b, u_b, m_b);
        const Vec3d F = link_force(link, p_a, u_a, p_b, u_b);
        apply(link.a, p_a, m_a, F);
        apply(link.b, p_b, m_b, -F);
    }
}

void World::evaluate_forces(int stage, bool record_contacts) {
    const float h = settings_.dt / static_cast<float>(substeps_);
    if (!links_.empty()) evaluate_links(stage);
    for (std::size_t b = 0; b < soft_.size(); ++b) {
        SoftBody& body = soft_[b];
        const std::size_t n = body.particle_count();
        const ParticleState s = stage == 0 ? current_state(body)
                                           : ParticleState{body.x_tmp.x.data(),   body.x_tmp.y.data(),
                                                           body.x_tmp.z.data(),   body.v_stage.x.data(),
                                                           body.v_stage.y.data(), body.v_stage.z.data()};
        // Eq. 21 and Eq. 22 over every pair.
        const PairInput in{s.x,  s.y,  s.z,  s.vx, s.vy, s.vz, body.rest.x.data(), body.rest.y.data(), body.rest.z.data(),
                           n, body.stiffness, body.damping};
        if (reference_kernel_) pair_forces_reference(in, body.force);
        else body.kernel->compute(in, body.force);

        add_gravity(body.force, body.mass, settings_.gravity);
        if (grab_ && !grab_->rigid && grab_->body == b && grab_->particle < n) add_grab(body.force, s, *grab_, body.mass, h);
        if (!links_.empty()) {
            for (const auto& [particle, F] : link_force_on_particles_[b]) body.force.add(particle, F);
        }
        // Drag after every other force but friction: its implicit step needs them (forces.h).
        if (body.def.drag_coefficient > 0.0f && settings_.air_density > 0.0f) {
            add_drag(body.force, s, n, settings_.air_density, body.def.drag_coefficient, body.rest_radius, body.mass, h);
        }
        // Friction last: Eq. 24 and 25 need everything else that pushes the particle.
        apply_ground_friction(body, s, settings_, record_contacts);

        Vec3Array& a = body.accel[stage];
        for (std::size_t i = 0; i < n; ++i) {
            a.x[i] = body.force.x[i] * body.inv_mass[i];
            a.y[i] = body.force.y[i] * body.inv_mass[i];
            a.z[i] = body.force.z[i] * body.inv_mass[i];
        }
    }
    // Rigid bodies: the net force and torque (Eq. 26, 27, 33), then Listing 9's derivative.
    const std::vector<double>& y = stage == 0 ? y_ : y_stage_;
    const bool momenta_only = settings_.integrator == Integrator::Verlet || settings_.integrator == Integrator::SymplecticEuler;
    // Each body on its own: on every thread (the same bits at any count).
    for_chunks(pool_.get(), rigid_.size(), 256, [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t b = begin; b < end; ++b) rigid_forces(stage, b, y, momenta_only);
    });
}

// Body b's net force and torque (Eq. 26, 27, 33) from state y, then Listing 9's derivative into
// k_[stage] (the momenta's rates alone when the integrator moves x and q itself).
void World::rigid_forces(int stage, std::size_t b, const std::vector<double>& y, bool momenta_only) {
    const float h = settings_.dt / static_cast<float>(substeps_);
    const RigidBody& body = rigid_[b];
    const double* state = &y[b * rigid::kStateSize];
    if (asleep_[b]) {
        // Not integrated: P and L are 0 and stay so, so x and q do not move (sleep.h).
        std::fill_n(&k_[stage][b * rigid::kStateSize], rigid::kStateSize, 0.0);
        return;
    }
    Wrench w;
    if (!body.fixed) {
        // The motion (velocities, world inertia) only for the forces that depend on it.
        const bool grabbed = grab_ && grab_->rigid && grab_->body == b;
        const bool dragged = body.drag_coefficient > 0.0f && settings_.air_density > 0.0f;
        const RigidMotion m = grabbed || dragged ? softbody::rigid_motion(body, state) : RigidMotion{};
        add_rigid_gravity(w, body, settings_.gravity);
        if (grabbed) add_rigid_grab(w, body, m, *grab_, h);
        if (!links_.empty()) {
            w.F += link_force_on_rigid_[b];
            w.tau += link_torque_on_rigid_[b];
        }
        if (dragged) add_rigid_drag(w, body, m, settings_.air_density, h);
    }
    // Symplectic Euler and Verlet take only the momenta's rates (they move x and q
    // themselves: symplectic_positions); the others the whole of Listing 9's derivative.
    if (momenta_only) rigid_momentum_derivative(body, w.F, w.tau, &k_[stage][b * rigid::kStateSize]);
    else rigid_derivative(body, state, w.F, w.tau, &k_[stage][b * rigid::kStateSize]);
}

// ---------------------------------------------------------------------------------------------
// One step of h: forces, the integrator (the bodies' free motion), then the contacts' substep.
// ---------------------------------------------------------------------------------------------
void World::step(float h) {
    const double hd = h;
    const bool contacts = !contacts_.empty();
    // Where the substep begins: symplectic Euler's positions move on from here, and each
    // contact's approach is measured from here. (Under Verlet and symplectic Euler each chunk
    // of bodies keeps its own just before the momenta change, on every thread.)
    const bool exact_turn = settings_.integrator == Integrator::Verlet || settings_.integrator == Integrator::SymplecticEuler;
    if (!rigid_.empty() && !exact_turn) y_step_start_ = y_;
    // And where each particle began it, for its contacts and its impacts with the ground.
    if (contacts || settings_.ground) {
        for (SoftBody& body : soft_) {
            body.v_step_start = body.v;
            body.x_step_start = body.x;
        }
    }
    if (soft_touching_) soft_contacts_->begin_substep(soft_, rigid_, y_, *pool_);
    switch (settings_.integrator) {
        case Integrator::Verlet:
        case Integrator::SymplecticEuler:
            if (settings_.integrator == Integrator::Verlet) {
                for (SoftBody& body : soft_) verlet_start(body, h);
            }
            evaluate_forces(0, true);
            for (SoftBody& body : soft_) {
                if (settings_.integrator == Integrator::Verlet) verlet_update(body, h);
                else symplectic_euler_update(body, h);
            }
            // Rigid bodies: the momenta, then x and q from them. Verlet is this for a rigid body.
            if (!rigid_.empty()) {
                y_step_start_.resize(y_.size());
                for_chunks(pool_.get(), rigid_.size(), 256, [&](std::size_t, std::size_t begin, std::size_t end) {
                    const std::size_t from = begin * rigid::kStateSize, count = (end - begin) * rigid::kStateSize;
                    std::copy_n(y_.begin() + std::ptrdiff_t(from), count, y_step_start_.begin() + std::ptrdiff_t(from));
                    flat_euler_momenta(std::span<double>(y_).subspan(from, count), std::span<const double>(k_[0]).subspan(from, count), hd);
                });
                symplectic_positions(rigid_, y_step_start_, y_, hd, asleep_, pool_.get());
            }
            break;
        case Integrator::ExplicitEuler:
            evaluate_forces(0, true);
            for (SoftBody& body : soft_) explicit_euler_update(body, h);
            flat_euler(y_, k_[0], hd);  // Listing 9 / 10: S += dt dS/dt, every number from the old state
            break;
        case Integrator::RK4:
            for (SoftBody& body : soft_) rk4_begin(body);
            evaluate_forces(0, true);
            for (int s = 1; s <= 3; ++s) {
                for (SoftBody& body : soft_) {
                    rk4_stage(body, s, h);
                    hold_stage_on_ground(body, settings_);
                }
                flat_rk4_stage(y_, k_[s - 1], rk4_stage_offset(s, hd), y_stage_);
                if (contacts) hold_stage_off_rigid(soft_, contacts_, rigid_, y_contacts_start_, y_stage_);
                evaluate_forces(s, false);
                for (SoftBody& body : soft_) rk4_accumulate(body, s);
            }
            for (SoftBody& body : soft_) rk4_finish(body, h);
            flat_rk4_finish(y_, k_[0], k_[1], k_[2], k_[3], hd);
            break;
    }
    for (SoftBody& body : soft_) hold_pins(body);
    // The contacts act on the velocities the integrator left, and move the positions on with
    // them (contact_solver.h). Before the ground's for particles: the ground moves for no one,
    // so it has the last word on a particle caught between it and a rigid body.
    if (contacts) solver_->substep(contact_world());
    if (soft_touching_) soft_contacts_->solve(soft_, rigid_, y_, settings_, h);
    for (SoftBody& body : soft_) resolve_ground_contacts(body, settings_, h);
}

void World::note_motions() {
    motion_.resize(rigid_.size());
    for_chunks(pool_.get(), rigid_.size(), 256, [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t b = begin; b < end; ++b) {
            if (!rigid_[b].fixed && !asleep_[b]) motion_[b] = rigid_motion(b);
        }
    });
}

// The substeps `time` (a tick, or what is left of it) needs for its rigid bodies' turns. Symplectic Euler and Verlet turn each
// body exactly about its principal axes and keep its energy (free_turn), stable at any rate: for
// accuracy, no body turns more than kMaxTurn in a substep. RK4 and explicit Euler step
// dq/dt = 1/2 w q as it is: RK4's energy error in a step is about (h w)^5 / 120 of it, so its
// bodies turn at most kMaxTurnRK4 (1e-7 a step); and for a thin body w depends steeply on q:
// tilting a rod by delta puts |L| delta of its angular momentum on its long axis, which spins it
// at |L| delta / I_min. Their steps must follow that rate, |L| / I_min, to within
// kMaxStiffTurn (RK4 is stable for h w < 2.8): a 5 m rod 5 cm thick tumbling at 20 rad/s needs
// about 300 substeps a tick, a box none. At most kMaxRotationSubsteps.
int World::rotation_substeps(double time) const {
    const bool stiff = settings_.integrator == Integrator::RK4 || settings_.integrator == Integrator::ExplicitEuler;
    const double turn = stiff ? kMaxTurnRK4 : kMaxTurn;
    // The largest over the bodies, on every thread (a maximum is the same in any order).
    std::vector<double> most_needed(std::size_t(4 * pool_->threads()), 1.0);
    for_chunks(pool_.get(), rigid_.size(), 256, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
        double needed = 1.0;  // (the chunk's own, written once: its neighbours' share a cache line)
        for (std::size_t b = begin; b < end; ++b) {
            const RigidBody& body = rigid_[b];
            if (body.fixed || asleep_[b]) continue;
            const RigidMotion& m = motion_[b];
            needed = std::max(needed, time * length(m.omega) / turn);
            if (stiff && body.principal_moments.x > 0.0) {
                needed = std::max(needed, time * length(m.L) / body.principal_moments.x / kMaxStiffTurn);
            }
        }
        most_needed[chunk] = needed;
    });
    const double needed = *std::max_element(most_needed.begin(), most_needed.end());
    const double most = std::max(1.0, std::ceil(double(kMaxRotationSubsteps) * time / double(settings_.dt)));
    return needed >= most ? int(most) : int(std::ceil(needed));
}

// What the contact solver sees of the world (contact_solver.h).
ContactWorld World::contact_world() {
    solver_particles_.resize(soft_.size());
    solver_particle_v_.resize(soft_.size());
    const bool verlet = settings_.integrator == Integrator::Verlet;
    for (std::size_t b = 0; b < soft_.size(); ++b) {
        SoftBody& body = soft_[b];
        SolverParticles& p = solver_particles_[b];
        p = {body.x.x.data(), body.x.y.data(), body.x.z.data(), body.v.x.data(), body.v.y.data(), body.v.z.data(),
             body.inv_mass.data()};
        if (verlet) {
            p.verlet_x = body.verlet_step.x.data();
            p.verlet_y = body.verlet_step.y.data();
            p.verlet_z = body.verlet_step.z.data();
        }
        p.x0 = body.x_step_start.x.data();
        p.y0 = body.x_step_start.y.data();
        p.z0 = body.x_step_start.z.data();
        solver_particle_v_[b] = &body.v_step_start;
    }
    return {rigid_, y_, y_contacts_start_, y_step_start_, solver_particles_, solver_particle_v_, pool_.get(), asleep_};
}

// Every contact within reach of `reach` seconds (the tick, or the rest of it), found where the
// bodies are now, each point within how far its bodies can move in that time (a speculative
// contact, found before it touches): rigid bodies with the ground and with one another, soft bodies'
// particles with rigid bodies. The last ones are kept for their impulses.
// A sleeping body has none with the ground, fixed bodies or other sleeping ones; one found with
// an awake body or a particle wakes its island, and the woken bodies' contacts are added (sleep.h).
void World::find_contacts(double reach) {
    std::swap(previous_contacts_, contacts_);
    generate_contacts(reach);
    std::vector<std::uint8_t> was_asleep = asleep_;
    while (wake_touched_islands()) {
        add_woken_contacts(reach, was_asleep);
        was_asleep = asleep_;
    }
}

void World::generate_contacts(double reach) {
    // The rigid bodies' contacts are written over the list of two finds ago (find_contacts swaps
    // the lists), which is then cut to them.
    y_contacts_start_ = y_;
    // Each body's with the ground, on every thread in chunks joined in the bodies' order.
    std::vector<std::vector<RigidContact>>& ground = rigid_contact_scratch_->ground;
    ground.resize(std::size_t(4 * pool_->threads()));
    const std::size_t chunks = for_chunks(pool_.get(), rigid_.size(), 128, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
        ChunkList taken(ground[chunk]);
        for (std::size_t b = begin; b < end; ++b) {
            fetch_hull_ahead(shapes_, b, end);
            if (asleep_[b]) continue;
            rigid_ground_contacts(rigid_[b], std::uint32_t(b), motion_[b], settings_, reach, *taken);
        }
    });
    const std::size_t ground_end = place_chunks(contacts_, 0, ground, chunks, pool_.get());
    contacts_.resize(rigid_body_contacts(rigid_, shapes_, y_, settings_, reach, *rigid_contact_scratch_, contacts_, ground_end, asleep_,
                                         pool_.get(), motion_));
    for (std::size_t b = 0; b < soft_.size(); ++b) {
        particle_rigid_contacts(soft_[b], std::int32_t(b), rigid_, shapes_, y_, settings_, reach, contacts_);
    }
}

// After a wake: the contacts the last find left out because their bodies slept, those of the
// woken bodies with the ground and of the rigid pairs that were both asleep or fixed, merged
// into the list in the places a whole find gives them (the ground's by body, the pairs' by pair,
// then the particles', which sleep does not change). What was found stays: the bodies have not
// moved since, and a sleeping body's contacts with awake ones and particles were found.
void World::add_woken_contacts(double reach, const std::vector<std::uint8_t>& was_asleep) {
    std::vector<RigidContact> ground, pairs;
    for (std::size_t b = 0; b < rigid_.size(); ++b) {
        if (was_asleep[b] && !asleep_[b]) rigid_ground_contacts(rigid_[b], std::uint32_t(b), &y_[b * rigid::kStateSize], settings_, reach, ground);
    }
    woken_rigid_body_contacts(rigid_, shapes_, y_, settings_, reach, *rigid_contact_scratch_, pairs, asleep_, was_asleep, pool_.get());
    if (ground.empty() && pairs.empty()) return;
    const auto is_ground = [](const RigidContact& c) { return c.soft < 0 && c.b < 0; };
    const auto is_pair = [](const RigidContact& c) { return c.soft < 0 && c.b >= 0; };
    const auto by_body = [](const RigidContact& x, const RigidContact& y) { return x.a < y.a; };
    const auto by_pair = [](const RigidContact& x, const RigidContact& y) {
        const std::uint32_t xb = std::uint32_t(x.b), yb = std::uint32_t(y.b);
        return std::pair(std::min(x.a, xb), std::max(x.a, xb)) < std::pair(std::min(y.a, yb), std::max(y.a, yb));
    };
    const auto ground_end = std::find_if_not(contacts_.begin(), contacts_.end(), is_ground);
    const auto pairs_end = std::find_if_not(ground_end, contacts_.end(), is_pair);
    // Into a list kept from wake to wake, which then swaps with the find's (a pile's contacts
    // are megabytes: a new list each wake was as many new pages).
    std::vector<RigidContact>& merged = rigid_contact_scratch_->merged;
    merged.clear();
    merged.reserve(contacts_.size() + ground.size() + pairs.size());
    std::merge(contacts_.begin(), ground_end, ground.begin(), ground.end(), std::back_inserter(merged), by_body);
    std::merge(ground_end, pairs_end, pairs.begin(), pairs.end(), std::back_inserter(merged), by_pair);
    merged.insert(merged.end(), pairs_end, contacts_.end());
    contacts_.swap(merged);
}

// The solver prepares the contacts found for an interval starting now (the tick, the rest of it,
// or one substep of it): anchors, masses, the last interval's impulses. Returns the substeps to
// run: `steps`, or with contacts at least kContactSubsteps a tick.
int World::begin_contacts(double interval, int steps) {
    for (SoftBody& body : soft_) body.v_step_start = body.v;
    if (contacts_.empty()) return steps;
    steps = std::max(steps, int(std::ceil(double(kContactSubsteps) * interval / double(settings_.dt) - 1e-9)));
    ContactSettings settings;
    settings.dt = interval;
    settings.substeps = steps;
    settings.gravity = Vec3d(settings_.gravity);
    settings.exact_turn = settings_.integrator == Integrator::Verlet || settings_.integrator == Integrator::SymplecticEuler;
    settings.particle_chord = !settings.exact_turn;
    // As for particles at the ground: impacts slower than two ticks' worth of gravity are
    // resting contact; without gravity, slower than 1 cm/s (else rounding in a push apart would
    // count as an impact, and a bouncing contact is not relaxed: the push would stay in it).
    settings.bounce_speed = std::max(2.0 * length(Vec3d(settings_.gravity)) * double(settings_.dt), kRestingSpeed);
    solver_->prepare(contacts_, previous_contacts_, contact_world(), settings);
    return steps;
}

// How many times contacts must be found over `time`: once, or for a body turning fast enough to
// turn more than its shape allows in that time (CollisionShape::contact_turn: half the angle
// between two neighbouring faces, 0.1 to 0.2 rad), once for every part of it in which none does. The
// solver takes each body's anchors, normal and inertia where its contacts were found; a thin
// plank tumbling at 20 rad/s turns 0.4 rad in a tick, by which its inertia in world axes and
// its corners have moved on, and impulses found for where it was would no longer stop it (and
// could throw it). Balls are left out: turning changes neither their shape nor their inertia.
// So are bodies without a contact: each body's margin covers its turn over `time` (|w| r), so
// one that met nothing within it meets nothing in that time, however fast it spins (a pile's
// boxes tumbling through the air as they fall). Found again, contacts would be the same none.
int World::contact_intervals(double time) {
    std::vector<std::uint8_t>& touching = contact_touching_;
    touching.assign(rigid_.size(), 0);
    // On every thread (a pile's contacts are tens of megabytes): each flag is only ever set to 1,
    // so the order in which the threads set them does not matter. (The compilers' atomic
    // built-ins: the browser build's C++ library has no std::atomic_ref.)
    const auto touch = [&](std::size_t b) { __atomic_store_n(&touching[b], std::uint8_t{1}, __ATOMIC_RELAXED); };
    for_chunks(pool_.get(), contacts_.size(), 1024, [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            const RigidContact& c = contacts_[k];
            if (c.soft < 0) touch(c.a);
            if (c.b >= 0) touch(std::size_t(c.b));
        }
    });
    std::vector<double> fastest_in(std::size_t(4 * pool_->threads()), 0.0);
    for_chunks(pool_.get(), rigid_.size(), 256, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
        double fastest = 0.0;  // (the chunk's own, written once)
        for (std::size_t b = begin; b < end; ++b) {
            if (touching[b] && !rigid_[b].fixed && !asleep_[b] && rigid_[b].shape != ShapeKind::Sphere) {
                fastest = std::max(fastest, length(motion_[b].omega) / shapes_[b].contact_turn);
            }
        }
        fastest_in[chunk] = fastest;
    });
    const double fastest = *std::max_element(fastest_in.begin(), fastest_in.end());
    const double needed = std::ceil(time * fastest);
    const double most = std::max(1.0, std::ceil(double(kMaxRotationSubsteps) * time / double(settings_.dt)));
    return needed >= most ? int(most) : std::max(1, int(needed));
}

// ---------------------------------------------------------------------------------------------
// The tick: contacts found, substeps, renormalisation, then the checks; a tick that diverged is
// taken back.
// ---------------------------------------------------------------------------------------------
void World::tick() {
    if (status_ != Status::Ok) return;
    if (energy_baseline_stale_ && !grab_) take_energy_baseline();
    y_tick_prev_ = y_;
    y_good_ = y_;
    // The substeps: what the springs need; with automatic substeps, enough that no rigid body
    // turns more than kMaxTurn in one (rotation_substeps); and at least kContactSubsteps in a
    // tick with contacts (their soft step, contact_solver.h). Contacts are found once a tick,
    // or once in each of several intervals when a body turns fast (contact_intervals). The
    // first are found before the particles' last tick is forgotten: how far they went then
    // says how far they may go now.
    // The tick runs in parts, each planned from the state it starts in: usually one part of the
    // whole tick; while a body turns fast, parts of one substep, so that a body set spinning by
    // an impact in the middle of a tick has its substeps and contacts follow it at once.
    contact_energy_ = {};
    tick_substeps_ = 0;
    tick_finds_ = 0;
    // Soft bodies within reach of one another (or of themselves): found before the last
    // tick's positions are forgotten, as the rigid contacts are; at least kContactSubsteps then.
    soft_touching_ = soft_contacts_->find(soft_, rigid_, y_, settings_, settings_.dt, *pool_);
    // A soft body within reach of a sleeping one wakes it, before anything is found or solved
    // (its contacts of last tick, the next find's warm start, come back to that list).
    if (soft_touching_ && sleep_.sleeping > 0) {
        std::vector<std::uint32_t> islands;
        soft_contacts_->for_each_rigid_in_reach([&](std::uint32_t r) {
            if (asleep_[r]) islands.push_back(sleep_.island[r]);
        });
        wake_islands(std::move(islands), contacts_);
    }
    const double dt = settings_.dt;
    double left = dt;
    for (bool first = true; left > 1e-9 * dt; first = false) {
        const double part = left / dt;
        int steps = std::max(1, int(std::ceil(double(substeps_) * part - 1e-9)));
        if (!rigid_.empty()) note_motions();
        if (settings_.auto_substeps) steps = std::max(steps, rotation_substeps(left));
        if (soft_touching_) steps = std::max(steps, int(std::ceil(double(kContactSubsteps) * part - 1e-9)));
        if (soft_touching_ && rigid_.empty()) steps = std::max(steps, soft_contact_substeps(part));
        double span = left;
        if (!rigid_.empty()) {
            // Contacts within reach of the rest of the tick; while a body turns fast, solved
            // over one substep only (and found again, from where it leaves the bodies, for the
            // next).
            find_contacts(left);
            ++tick_finds_;
            if (!soft_.empty()) steps = std::max(steps, soft_contact_substeps(part));
            const int turns = contacts_.empty() ? 1 : contact_intervals(left);
            if (turns > 1) {
                span = left / double(std::max(turns, steps));
                steps = 1;
            }
            steps = begin_contacts(span, steps);
        }
        if (first) {
            for (SoftBody& body : soft_) {
                body.x_tick_prev = body.x;
                body.x_good = body.x;
                body.v_good = body.v;
                body.verlet_step_good = body.verlet_step;
                body.verlet_h_good = body.verlet_h;
            }
        }
        const float h = float(span / double(steps));
        for (int s = 0; s < steps; ++s) step(h);
        tick_substeps_ += steps;
        if (!contacts_.empty()) {
            solver_->finish(contacts_, contact_world());
            contact_energy_.total += solver_->energy().total;
            contact_energy_.restitution += solver_->energy().restitution;
        }
        left -= span;
    }
    ++ticks_;
    // Listing 9: every few ticks, bring each quaternion back to unit length.
    if (settings_.renormalize_every > 0 && ticks_ % std::uint64_t(settings_.renormalize_every) == 0) {
        for (std::size_t b = 0; b < rigid_.size(); ++b) {
            if (asleep_[b]) continue;  // not integrated, nothing to bring back
            double* q = &y_[b * rigid::kStateSize + rigid::Q];
            const Quat unit = Quat{q[0], q[1], q[2], q[3]}.normalized();
            q[0] = unit.w;
            q[1] = unit.x;
            q[2] = unit.y;
            q[3] = unit.z;
        }
    }
    if (!rigid_.empty()) note_motions();
    check_divergence();
    if (status_ == Status::Ok) update_sleep();
    if (status_ != Status::Ok) {
        // Keep the last finite state on show; nothing downstream ever sees a NaN.
        for (SoftBody& body : soft_) {
            body.x = body.x_good;
            body.v = body.v_good;
            body.verlet_step = body.verlet_step_good;
            body.x_tick_prev = body.x;
            body.verlet_h = body.verlet_h_good;
        }
        y_ = y_good_;
        y_tick_prev_ = y_;
        --ticks_;
    }
}

void World::run(std::uint64_t ticks) {
    for (std::uint64_t t = 0; t < ticks && status_ == Status::Ok; ++t) tick();
}

}  // namespace softbody

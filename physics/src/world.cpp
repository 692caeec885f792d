// The world's tick, in order: forces, integration, contacts, checks. What each of those does
// lives in its own file: forces.cpp, pair_forces.cpp, ground_contact.cpp, contact_solver.cpp,
// integrators.cpp, divergence.cpp (and stability.cpp, energy.cpp for what the world reports).
#include "physics/world.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "contact_solver.h"
#include "forces.h"
#include "ground_contact.h"
#include "integrators.h"
#include "message_text.h"
#include "particle_contacts.h"
#include "rigid_contacts.h"
#include "sleep.h"
#include "soft_contacts.h"
#include "physics/error.h"

namespace softbody {

namespace {

// The slowest impact that bounces when there is no gravity to set the scale (m/s).
constexpr double kRestingSpeed = 0.01;

void copy(const Vec3Array& from, Vec3Array& to) {
    to.x = from.x;
    to.y = from.y;
    to.z = from.z;
}

void check_pins(const Params& params, const Mesh& mesh) {
    for (std::uint32_t vertex : params.pinned) {
        if (vertex >= mesh.vertex_to_particle.size()) {
            throw InputError("parameter 'pinned': vertex " + std::to_string(vertex) + " does not exist (the mesh has " +
                             std::to_string(mesh.vertex_to_particle.size()) + " vertices, numbered from 0)");
        }
    }
}

WorldDef one_body(const Params& params, Mesh mesh) {
    WorldDef def;
    def.params = params;
    def.soft_bodies.push_back(SoftBodyDef{"body", params, std::move(mesh)});
    return def;
}

}  // namespace

World::World(WorldDef def, WorldOptions options)
    : params_(def.params),
      rigid_contact_scratch_(std::make_unique<RigidContactScratch>()),
      solver_(std::make_unique<ContactSolver>()),
      soft_contacts_(std::make_unique<SoftContacts>()),
      reference_kernel_(options.reference_kernel) {
    validate(params_);
    pool_ = std::make_unique<ThreadPool>(std::max(1, options.threads));
    for (SoftBodyDef& d : def.soft_bodies) {
        validate(d.params);
        if (d.mesh.positions.empty()) throw InputError(d.mesh.source + ": the mesh has no vertices");
        check_pins(d.params, d.mesh);
        SoftBody body;
        body.name = std::move(d.name);
        body.params = std::move(d.params);
        body.mesh = std::move(d.mesh);
        body.kernel = std::make_unique<PairForceKernel>(*pool_);
        soft_.push_back(std::move(body));
    }
    rigid_ = std::move(def.rigid_bodies);
    for (const RigidBody& body : rigid_) {
        notes_.insert(notes_.end(), body.notes.begin(), body.notes.end());
        shapes_.push_back(collision_shape(body));
    }
    const std::size_t n = rigid_.size() * rigid::kStateSize;
    for (auto* y : {&y_, &y_tick_prev_, &y_good_, &y_stage_, &k_[0], &k_[1], &k_[2], &k_[3]}) y->assign(n, 0.0);
    link_force_on_rigid_.assign(rigid_.size(), {});
    link_torque_on_rigid_.assign(rigid_.size(), {});
    link_force_on_particles_.assign(soft_.size(), {});
    build();
    // What the loader set aside in each mesh file (a dangling normal index, ...): one line each.
    for (const SoftBody& body : soft_) notes_.insert(notes_.end(), body.mesh.warnings.begin(), body.mesh.warnings.end());
    // A body that asked for every vertex and got fewer: the cap said, not kept quiet.
    for (const SoftBody& body : soft_) {
        if (std::string note = particle_cap_note(body); !note.empty()) notes_.push_back(std::move(note));
    }
    resolve_links(def.springs);
    update_substeps();  // the links' springs count toward the step's stability
}

World::World(const Params& params, Mesh mesh, WorldOptions options) : World(one_body(params, std::move(mesh)), options) {}

World::~World() = default;

void World::build() {
    for (SoftBody& body : soft_) build_particles(body);
    soft_contacts_->build(soft_);
    soft_touching_ = false;
    for (std::size_t b = 0; b < rigid_.size(); ++b) {
        std::copy(rigid_[b].initial.begin(), rigid_[b].initial.end(), y_.begin() + std::ptrdiff_t(b * rigid::kStateSize));
    }
    y_tick_prev_ = y_;
    contacts_.clear();
    previous_contacts_.clear();
    reset_sleep();
    ticks_ = 0;
    status_ = Status::Ok;
    divergence_.clear();
    grab_.reset();
    energy_baseline_stale_ = true;
    update_substeps();
}

void World::reset() { build(); }

const std::vector<SoftContact>& World::soft_contacts() const { return soft_contacts_->contacts(); }

WorldSnapshot World::snapshot() const {
    WorldSnapshot out;
    for (const SoftBody& body : soft_) {
        out.soft.push_back({body.x, body.v, body.verlet_step, body.x_tick_prev, body.inv_mass, body.verlet_h});
    }
    out.rigid = y_;
    out.rigid_tick_prev = y_tick_prev_;
    out.contacts = contacts_;
    out.ticks = ticks_;
    out.status = status_;
    out.divergence = divergence_;
    out.energy_baseline = energy_baseline_;
    out.energy_scale = energy_scale_;
    out.energy_baseline_stale = energy_baseline_stale_;
    out.sleep = sleep_;
    return out;
}

void World::restore(const WorldSnapshot& s, bool more_bodies) {
    const bool fits = more_bodies ? s.soft.size() <= soft_.size() && s.rigid.size() <= y_.size()
                                  : s.soft.size() == soft_.size() && s.rigid.size() == y_.size();
    if (!fits || s.rigid.size() != s.rigid_tick_prev.size()) throw std::invalid_argument("World::restore: a snapshot of another world");
    for (std::size_t b = 0; b < s.soft.size(); ++b) {
        SoftBody& body = soft_[b];
        const WorldSnapshot::Soft& from = s.soft[b];
        if (from.x.size() != body.particle_count()) throw std::invalid_argument("World::restore: a snapshot of another body");
        body.x = from.x;
        body.v = from.v;
        body.verlet_step = from.verlet_step;
        body.x_tick_prev = from.x_tick_prev;
        body.inv_mass = from.inv_mass;
        body.verlet_h = from.verlet_h;
    }
    std::copy(s.rigid.begin(), s.rigid.end(), y_.begin());
    std::copy(s.rigid_tick_prev.begin(), s.rigid_tick_prev.end(), y_tick_prev_.begin());
    if (more_bodies) {
        contacts_.clear();  // the next tick finds them with the new bodies
    } else {
        contacts_ = s.contacts;
    }
    previous_contacts_.clear();
    ticks_ = s.ticks;
    status_ = s.status;
    divergence_ = s.divergence;
    energy_baseline_ = s.energy_baseline;
    energy_scale_ = s.energy_scale;
    energy_baseline_stale_ = s.energy_baseline_stale;
    // Asleep as they were; bodies added since start awake.
    if (s.sleep.island.size() != s.rigid.size() / rigid::kStateSize || s.sleep.rest_time.size() != s.sleep.island.size()) {
        throw std::invalid_argument("World::restore: a snapshot of another world");
    }
    sleep_ = s.sleep;
    sleep_.rest_time.resize(rigid_.size(), 0.0);
    sleep_.island.resize(rigid_.size(), kAwake);
    sleep_.deepest.resize(rigid_.size(), 0.0);
    for (std::size_t b = 0; b < rigid_.size(); ++b) asleep_[b] = sleep_.island[b] != kAwake ? 1 : 0;
}

std::size_t WorldSnapshot::bytes() const {
    std::size_t total = sizeof(*this);
    for (const Soft& body : soft) {
        total += sizeof(Soft) + body.inv_mass.size() * sizeof(float) +
                 (body.x.size() + body.v.size() + body.verlet_step.size() + body.x_tick_prev.size()) * 3 * sizeof(float);
    }
    return total + (rigid.size() + rigid_tick_prev.size() + sleep.rest_time.size()) * sizeof(double) +
           (contacts.size() + sleep.contacts.size()) * sizeof(RigidContact) + sleep.island.size() * sizeof(std::uint32_t) +
           divergence.size();
}

// Names to indices, each end checked, and the rest lengths measured where none is given.
void World::resolve_links(const std::vector<SpringDef>& springs) {
    for (std::size_t s = 0; s < springs.size(); ++s) {
        const SpringDef& def = springs[s];
        const std::string what = "spring " + std::to_string(s + 1);
        if (!def.stiffness) throw InputError(what + ": needs 'stiffness' (N/m)");
        if (!(*def.stiffness >= 0.0) || !(def.damping >= 0.0) || (def.rest_length && !(*def.rest_length >= 0.0))) {
            throw InputError(what + ": stiffness, damping and rest_length must not be negative");
        }
        Link link;
        link.k = *def.stiffness;
        link.c = def.damping;
        const auto resolve = [&](const SpringEndDef& end, const char* name) {
            const std::string where = what + ", end '" + name + "'";
            LinkEnd out;
            if (end.body.empty()) {
                if (end.vertex) throw InputError(where + ": a vertex needs a \"body\"");
                if (!end.point) throw InputError(where + ": needs a \"body\" or a \"point\" fixed in the world");
                out.kind = LinkEnd::Kind::World;
                out.point = *end.point;
                return out;
            }
            for (std::size_t b = 0; b < rigid_.size(); ++b) {
                if (rigid_[b].name != end.body) continue;
                if (end.vertex) throw InputError(where + ": rigid body '" + end.body + "' has no vertices; give a \"point\" in its axes");
                out.kind = LinkEnd::Kind::Rigid;
                out.body = std::uint32_t(b);
                out.point = end.point.value_or(Vec3d{});
                return out;
            }
            for (std::size_t b = 0; b < soft_.size(); ++b) {
                if (soft_[b].name != end.body) continue;
                if (end.point) throw InputError(where + ": soft body '" + end.body + "' is held at a \"vertex\", not a point");
                if (!end.vertex) throw InputError(where + ": needs the \"vertex\" of soft body '" + end.body + "'");
                const auto& map = soft_[b].mesh.vertex_to_particle;
                if (*end.vertex < 0 || std::size_t(*end.vertex) >= map.size()) {
                    throw InputError(where + ": vertex " + std::to_string(*end.vertex) + " does not exist (body '" +
                                     end.body + "' has " + std::to_string(map.size()) + " vertices, numbered from 0)");
                }
                out.kind = LinkEnd::Kind::Soft;
                out.body = std::uint32_t(b);
                out.particle = particle_of_vertex(soft_[b], std::uint32_t(*end.vertex));
                return out;
            }
            throw InputError(where + ": there is no body named '" + printable(end.body) + "'");
        };
        link.a = resolve(def.a, "a");
        link.b = resolve(def.b, "b");
        link.l0 = def.rest_length ? *def.rest_length : length(link_end_position(link.b) - link_end_position(link.a));
        links_.push_back(link);
    }
}

Vec3d World::link_end_position(const LinkEnd& end) const {
    switch (end.kind) {
        case LinkEnd::Kind::World: return end.point;
        case LinkEnd::Kind::Rigid: {
            const RigidMotion m = rigid_motion(end.body);
            return m.x + m.R * end.point;
        }
        case LinkEnd::Kind::Soft: return Vec3d(soft_[end.body].x[end.particle]);
    }
    return {};
}

void World::set_threads(int threads) {
    for (SoftBody& body : soft_) body.kernel.reset();
    pool_ = std::make_unique<ThreadPool>(std::max(1, threads));
    for (SoftBody& body : soft_) body.kernel = std::make_unique<PairForceKernel>(*pool_);
}

void World::set_body_params(std::size_t b, const Params& params) {
    if (b >= soft_.size()) throw InputError("there is no soft body number " + std::to_string(b));
    validate(params);
    check_pins(params, soft_[b].mesh);
    if (!(params == soft_[b].params)) {
        energy_baseline_stale_ = true;
        wake_all();  // a key changed: whatever it does, nothing stays asleep through it
    }
    soft_[b].params = params;
    apply_body_keys(soft_[b]);
    update_substeps();
}

void World::set_params(const Params& params) {
    validate(params);
    // The flat keys' soft body, when there is one, takes the body keys.
    if (!soft_.empty() && soft_.front().name == "body") set_body_params(0, params);
    // Switching to Verlet restarts it from the current x and v (x_{-1} = x_0 - v_0 h): its step
    // was last kept up to date when Verlet last ran, and is stale by now.
    if (params.integrator != params_.integrator) {
        for (SoftBody& body : soft_) body.verlet_h = 0.0f;
    }
    if (!(params == params_)) {
        energy_baseline_stale_ = true;
        wake_all();
    }
    params_ = params;
    update_substeps();
}

void World::set_grab(std::optional<Grab> grab) {
    grab_ = grab;
    energy_baseline_stale_ = true;  // the grab does work on the body
    if (grab_ && grab_->rigid) wake_rigid(grab_->body);
}

void World::set_rigid_material(std::size_t i, std::optional<float> restitution, std::optional<float> friction) {
    rigid_[i].restitution = restitution;
    rigid_[i].friction = friction;
    wake_rigid(i);
}

void World::set_pinned(std::uint32_t particle, bool pinned) {
    softbody::set_pinned(soft_.front(), particle, pinned);
    energy_baseline_stale_ = true;
}

void World::update_substeps() {
    substeps_ = params_.substeps;
    if (params_.auto_substeps) {
        const int needed = stability().substeps_needed;
        substeps_ = std::max(params_.substeps, needed > 0 ? needed : 1000);
    }
    tick_substeps_ = substeps_;
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
    const float h = params_.dt / static_cast<float>(substeps_);
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

        add_gravity(body.force, body.mass, params_.gravity);
        if (grab_ && !grab_->rigid && grab_->body == b && grab_->particle < n) add_grab(body.force, s, *grab_, body.mass, h);
        if (!links_.empty()) {
            for (const auto& [particle, F] : link_force_on_particles_[b]) body.force.add(particle, F);
        }
        // Drag after every other force but friction: its implicit step needs them (forces.h).
        if (body.params.drag_coefficient > 0.0f && params_.air_density > 0.0f) {
            add_drag(body.force, s, n, params_.air_density, body.params.drag_coefficient, body.rest_radius, body.mass, h);
        }
        // Friction last: Eq. 24 and 25 need everything else that pushes the particle.
        apply_ground_friction(body, s, params_, record_contacts);

        Vec3Array& a = body.accel[stage];
        for (std::size_t i = 0; i < n; ++i) {
            a.x[i] = body.force.x[i] * body.inv_mass[i];
            a.y[i] = body.force.y[i] * body.inv_mass[i];
            a.z[i] = body.force.z[i] * body.inv_mass[i];
        }
    }
    // Rigid bodies: the net force and torque (Eq. 26, 27, 33), then Listing 9's derivative.
    const std::vector<double>& y = stage == 0 ? y_ : y_stage_;
    for (std::size_t b = 0; b < rigid_.size(); ++b) {
        const RigidBody& body = rigid_[b];
        const double* state = &y[b * rigid::kStateSize];
        if (asleep_[b]) {
            // Not integrated: P and L are 0 and stay so, so x and q do not move (sleep.h).
            std::fill_n(&k_[stage][b * rigid::kStateSize], rigid::kStateSize, 0.0);
            continue;
        }
        Wrench w;
        if (!body.fixed) {
            const RigidMotion m = softbody::rigid_motion(body, state);
            add_rigid_gravity(w, body, params_.gravity);
            if (grab_ && grab_->rigid && grab_->body == b) add_rigid_grab(w, body, m, *grab_, h);
            if (!links_.empty()) {
                w.F += link_force_on_rigid_[b];
                w.tau += link_torque_on_rigid_[b];
            }
            if (body.drag_coefficient > 0.0f && params_.air_density > 0.0f) add_rigid_drag(w, body, m, params_.air_density, h);
        }
        rigid_derivative(body, state, w.F, w.tau, &k_[stage][b * rigid::kStateSize]);
    }
}

// ---------------------------------------------------------------------------------------------
// One step of h: forces, the integrator (the bodies' free motion), then the contacts' substep.
// ---------------------------------------------------------------------------------------------
void World::step(float h) {
    const double hd = h;
    const bool contacts = !contacts_.empty();
    // Where the substep begins: symplectic Euler's positions move on from here, and each
    // contact's approach is measured from here.
    if (!rigid_.empty()) y_step_start_ = y_;
    // And where each particle began it, for its contacts and its impacts with the ground.
    if (contacts || params_.ground) {
        for (SoftBody& body : soft_) {
            copy(body.v, body.v_step_start);
            copy(body.x, body.x_step_start);
        }
    }
    if (soft_touching_) soft_contacts_->begin_substep(soft_, rigid_, y_, *pool_);
    switch (params_.integrator) {
        case Integrator::Verlet:
        case Integrator::SymplecticEuler:
            if (params_.integrator == Integrator::Verlet) {
                for (SoftBody& body : soft_) verlet_start(body, h);
            }
            evaluate_forces(0, true);
            for (SoftBody& body : soft_) {
                if (params_.integrator == Integrator::Verlet) verlet_update(body, h);
                else symplectic_euler_update(body, h);
            }
            // Rigid bodies: the momenta, then x and q from them. Verlet is this for a rigid body.
            if (!rigid_.empty()) {
                flat_euler_momenta(y_, k_[0], hd);
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
                    hold_stage_on_ground(body, params_);
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
    if (soft_touching_) soft_contacts_->solve(soft_, rigid_, y_, params_, h);
    for (SoftBody& body : soft_) resolve_ground_contacts(body, params_, h);
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
    const bool stiff = params_.integrator == Integrator::RK4 || params_.integrator == Integrator::ExplicitEuler;
    const double turn = stiff ? kMaxTurnRK4 : kMaxTurn;
    // The largest over the bodies, on every thread (a maximum is the same in any order).
    std::vector<double> most_needed(std::size_t(4 * pool_->threads()), 1.0);
    for_chunks(pool_.get(), rigid_.size(), 256, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
        double& needed = most_needed[chunk];
        for (std::size_t b = begin; b < end; ++b) {
            const RigidBody& body = rigid_[b];
            if (body.fixed || asleep_[b]) continue;
            const RigidMotion m = rigid_motion(b);
            needed = std::max(needed, time * length(m.omega) / turn);
            if (stiff && body.principal_moments.x > 0.0) {
                needed = std::max(needed, time * length(m.L) / body.principal_moments.x / kMaxStiffTurn);
            }
        }
    });
    const double needed = *std::max_element(most_needed.begin(), most_needed.end());
    const double most = std::max(1.0, std::ceil(double(kMaxRotationSubsteps) * time / double(params_.dt)));
    return needed >= most ? int(most) : int(std::ceil(needed));
}

// What the contact solver sees of the world (contact_solver.h).
ContactWorld World::contact_world() {
    solver_particles_.resize(soft_.size());
    solver_particle_v_.resize(soft_.size());
    const bool verlet = params_.integrator == Integrator::Verlet;
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
// contact, as Box2D finds them): rigid bodies with the ground and with one another, soft bodies'
// particles with rigid bodies. The last ones are kept for their impulses.
// A sleeping body has none with the ground, fixed bodies or other sleeping ones; one found with
// an awake body or a particle wakes its island, and they are found again (sleep.h).
void World::find_contacts(double reach) {
    std::swap(previous_contacts_, contacts_);
    generate_contacts(reach);
    while (wake_touched_islands()) generate_contacts(reach);
}

void World::generate_contacts(double reach) {
    contacts_.clear();
    y_contacts_start_ = y_;
    // Each body's with the ground, on every thread in chunks joined in the bodies' order.
    std::vector<std::vector<RigidContact>>& ground = rigid_contact_scratch_->ground;
    ground.resize(std::size_t(4 * pool_->threads()));
    const std::size_t chunks = for_chunks(pool_.get(), rigid_.size(), 128, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
        ground[chunk].clear();
        for (std::size_t b = begin; b < end; ++b) {
            if (asleep_[b]) continue;
            rigid_ground_contacts(rigid_[b], std::uint32_t(b), &y_[b * rigid::kStateSize], params_, reach, ground[chunk]);
        }
    });
    for (std::size_t chunk = 0; chunk < chunks; ++chunk) contacts_.insert(contacts_.end(), ground[chunk].begin(), ground[chunk].end());
    rigid_body_contacts(rigid_, shapes_, y_, params_, reach, *rigid_contact_scratch_, contacts_, asleep_, pool_.get());
    for (std::size_t b = 0; b < soft_.size(); ++b) {
        particle_rigid_contacts(soft_[b], std::int32_t(b), rigid_, shapes_, y_, params_, reach, contacts_);
    }
}

// The solver prepares the contacts found for an interval starting now (the tick, the rest of it,
// or one substep of it): anchors, masses, the last interval's impulses. Returns the substeps to
// run: `steps`, or with contacts at least kContactSubsteps a tick.
int World::begin_contacts(double interval, int steps) {
    for (SoftBody& body : soft_) copy(body.v, body.v_step_start);
    if (contacts_.empty()) return steps;
    steps = std::max(steps, int(std::ceil(double(kContactSubsteps) * interval / double(params_.dt) - 1e-9)));
    ContactSettings settings;
    settings.dt = interval;
    settings.substeps = steps;
    settings.gravity = Vec3d(params_.gravity);
    settings.exact_turn = params_.integrator == Integrator::Verlet || params_.integrator == Integrator::SymplecticEuler;
    settings.particle_chord = !settings.exact_turn;
    // As for particles at the ground: impacts slower than two ticks' worth of gravity are
    // resting contact; without gravity, slower than 1 cm/s (else rounding in a push apart would
    // count as an impact, and a bouncing contact is not relaxed: the push would stay in it).
    settings.bounce_speed = std::max(2.0 * length(Vec3d(params_.gravity)) * double(params_.dt), kRestingSpeed);
    solver_->prepare(contacts_, previous_contacts_, contact_world(), settings);
    return steps;
}

// How many times contacts must be found over `time`: once, or for a body turning fast enough to
// turn more than kMaxContactTurn in that time, once for every part of it in which none does. The
// solver takes each body's anchors, normal and inertia where its contacts were found; a thin
// plank tumbling at 20 rad/s turns 0.4 rad in a tick, by which its inertia in world axes and
// its corners have moved on, and impulses found for where it was would no longer stop it (and
// could throw it). Balls are left out: turning changes neither their shape nor their inertia.
int World::contact_intervals(double time) const {
    std::vector<double> fastest_in(std::size_t(4 * pool_->threads()), 0.0);
    for_chunks(pool_.get(), rigid_.size(), 256, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
        for (std::size_t b = begin; b < end; ++b) {
            if (!rigid_[b].fixed && !asleep_[b] && rigid_[b].shape != ShapeKind::Sphere) {
                fastest_in[chunk] = std::max(fastest_in[chunk], length(rigid_motion(b).omega));
            }
        }
    });
    const double fastest = *std::max_element(fastest_in.begin(), fastest_in.end());
    const double needed = std::ceil(time * fastest / kMaxContactTurn);
    const double most = std::max(1.0, std::ceil(double(kMaxRotationSubsteps) * time / double(params_.dt)));
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
    // Soft bodies within reach of one another (or of themselves): found before the last
    // tick's positions are forgotten, as the rigid contacts are; at least kContactSubsteps then.
    soft_touching_ = soft_contacts_->find(soft_, rigid_, y_, params_, params_.dt, *pool_);
    // A soft body within reach of a sleeping one wakes it, before anything is found or solved
    // (its contacts of last tick, the next find's warm start, come back to that list).
    if (soft_touching_ && sleep_.sleeping > 0) {
        std::vector<std::uint32_t> islands;
        soft_contacts_->for_each_rigid_in_reach([&](std::uint32_t r) {
            if (asleep_[r]) islands.push_back(sleep_.island[r]);
        });
        wake_islands(std::move(islands), contacts_);
    }
    const double dt = params_.dt;
    double left = dt;
    for (bool first = true; left > 1e-9 * dt; first = false) {
        const double part = left / dt;
        int steps = std::max(1, int(std::ceil(double(substeps_) * part - 1e-9)));
        if (params_.auto_substeps) steps = std::max(steps, rotation_substeps(left));
        if (soft_touching_) steps = std::max(steps, int(std::ceil(double(kContactSubsteps) * part - 1e-9)));
        double span = left;
        if (!rigid_.empty()) {
            // Contacts within reach of the rest of the tick; while a body turns fast, solved
            // over one substep only (and found again, from where it leaves the bodies, for the
            // next).
            find_contacts(left);
            const int turns = contacts_.empty() ? 1 : contact_intervals(left);
            if (turns > 1) {
                span = left / double(std::max(turns, steps));
                steps = 1;
            }
            steps = begin_contacts(span, steps);
        }
        if (first) {
            for (SoftBody& body : soft_) {
                copy(body.x, body.x_tick_prev);
                copy(body.x, body.x_good);
                copy(body.v, body.v_good);
                copy(body.verlet_step, body.verlet_step_good);
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
    if (params_.renormalize_every > 0 && ticks_ % std::uint64_t(params_.renormalize_every) == 0) {
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
    check_divergence();
    if (status_ == Status::Ok) update_sleep();
    if (status_ != Status::Ok) {
        // Keep the last finite state on show; nothing downstream ever sees a NaN.
        for (SoftBody& body : soft_) {
            copy(body.x_good, body.x);
            copy(body.v_good, body.v);
            copy(body.verlet_step_good, body.verlet_step);
            copy(body.x, body.x_tick_prev);
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

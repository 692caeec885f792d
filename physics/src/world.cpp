// The world's tick, in order: forces, integration, contacts, checks. What each of those does
// lives in its own file: forces.cpp, pair_forces.cpp, ground_contact.cpp, integrators.cpp,
// divergence.cpp (and stability.cpp, energy.cpp for what the world reports).
#include "physics/world.h"

#include <algorithm>

#include "forces.h"
#include "ground_contact.h"
#include "integrators.h"
#include "physics/error.h"

namespace softbody {

namespace {

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

World::World(WorldDef def, WorldOptions options) : params_(def.params), reference_kernel_(options.reference_kernel) {
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
    build();
}

World::World(const Params& params, Mesh mesh, WorldOptions options) : World(one_body(params, std::move(mesh)), options) {}

World::~World() = default;

void World::build() {
    for (SoftBody& body : soft_) build_particles(body);
    ticks_ = 0;
    status_ = Status::Ok;
    divergence_.clear();
    grab_.reset();
    energy_baseline_stale_ = true;
    update_substeps();
}

void World::reset() { build(); }

void World::set_threads(int threads) {
    for (SoftBody& body : soft_) body.kernel.reset();
    pool_ = std::make_unique<ThreadPool>(std::max(1, threads));
    for (SoftBody& body : soft_) body.kernel = std::make_unique<PairForceKernel>(*pool_);
}

void World::set_params(const Params& params) {
    validate(params);
    if (!soft_.empty()) {
        check_pins(params, soft_.front().mesh);
        soft_.front().params = params;
        set_particle_mass(soft_.front(), params.particle_mass);
    }
    // Switching to Verlet restarts it from the current x and v (x_{-1} = x_0 - v_0 h): its step
    // was last kept up to date when Verlet last ran, and is stale by now.
    if (params.integrator != params_.integrator) {
        for (SoftBody& body : soft_) body.verlet_h = 0.0f;
    }
    if (!(params == params_)) energy_baseline_stale_ = true;
    params_ = params;
    update_substeps();
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
}

// ---------------------------------------------------------------------------------------------
// Forces at one stage of the step: stage 0 is the current state, stages 1 to 3 are RK4's.
// ---------------------------------------------------------------------------------------------
void World::evaluate_forces(int stage, bool record_contacts) {
    const float h = params_.dt / static_cast<float>(substeps_);
    for (std::size_t b = 0; b < soft_.size(); ++b) {
        SoftBody& body = soft_[b];
        const std::size_t n = body.particle_count();
        const ParticleState s = stage == 0 ? current_state(body)
                                           : ParticleState{body.x_tmp.x.data(),   body.x_tmp.y.data(),
                                                           body.x_tmp.z.data(),   body.v_stage.x.data(),
                                                           body.v_stage.y.data(), body.v_stage.z.data()};
        // Eq. 21 and Eq. 22 over every pair.
        const PairInput in{s.x,  s.y,  s.z,  s.vx, s.vy, s.vz, body.rest.x.data(), body.rest.y.data(), body.rest.z.data(),
                           n, body.params.stiffness, body.params.damping};
        if (reference_kernel_) pair_forces_reference(in, body.force);
        else body.kernel->compute(in, body.force);

        add_gravity(body.force, body.mass, params_.gravity);
        if (body.params.drag_coefficient > 0.0f && params_.air_density > 0.0f) {
            add_drag(body.force, s, n, params_.air_density, body.params.drag_coefficient, body.rest_radius);
        }
        if (grab_ && grab_->body == b && grab_->particle < n) add_grab(body.force, s, *grab_, body.mass, h);
        // Friction last: Eq. 24 and 25 need everything else that pushes the particle.
        apply_ground_friction(body, s, params_, record_contacts);

        Vec3Array& a = body.accel[stage];
        for (std::size_t i = 0; i < n; ++i) {
            a.x[i] = body.force.x[i] * body.inv_mass[i];
            a.y[i] = body.force.y[i] * body.inv_mass[i];
            a.z[i] = body.force.z[i] * body.inv_mass[i];
        }
    }
}

// ---------------------------------------------------------------------------------------------
// One step of h: forces, the integrator, contacts.
// ---------------------------------------------------------------------------------------------
void World::step(float h) {
    switch (params_.integrator) {
        case Integrator::Verlet:
            for (SoftBody& body : soft_) verlet_start(body, h);
            evaluate_forces(0, true);
            for (SoftBody& body : soft_) verlet_update(body, h);
            break;
        case Integrator::SymplecticEuler:
            evaluate_forces(0, true);
            for (SoftBody& body : soft_) symplectic_euler_update(body, h);
            break;
        case Integrator::ExplicitEuler:
            evaluate_forces(0, true);
            for (SoftBody& body : soft_) explicit_euler_update(body, h);
            break;
        case Integrator::RK4:
            for (SoftBody& body : soft_) rk4_begin(body);
            evaluate_forces(0, true);
            for (int s = 1; s <= 3; ++s) {
                for (SoftBody& body : soft_) rk4_stage(body, s, h);
                evaluate_forces(s, false);
                for (SoftBody& body : soft_) rk4_accumulate(body, s);
            }
            for (SoftBody& body : soft_) rk4_finish(body, h);
            break;
    }
    for (SoftBody& body : soft_) {
        hold_pins(body);
        resolve_ground_contacts(body, params_, h);
    }
}

// ---------------------------------------------------------------------------------------------
// The tick: substeps, then the checks; a tick that diverged is taken back.
// ---------------------------------------------------------------------------------------------
void World::tick() {
    if (status_ != Status::Ok) return;
    if (energy_baseline_stale_ && !grab_) take_energy_baseline();
    for (SoftBody& body : soft_) {
        copy(body.x, body.x_tick_prev);
        copy(body.x, body.x_good);
        copy(body.v, body.v_good);
        copy(body.verlet_step, body.verlet_step_good);
        body.verlet_h_good = body.verlet_h;
    }
    const float h = params_.dt / static_cast<float>(substeps_);
    for (int s = 0; s < substeps_; ++s) step(h);
    ++ticks_;
    check_divergence();
    if (status_ != Status::Ok) {
        // Keep the last finite state on show; nothing downstream ever sees a NaN.
        for (SoftBody& body : soft_) {
            copy(body.x_good, body.x);
            copy(body.v_good, body.v);
            copy(body.verlet_step_good, body.verlet_step);
            copy(body.x, body.x_tick_prev);
            body.verlet_h = body.verlet_h_good;
        }
        --ticks_;
    }
}

void World::run(std::uint64_t ticks) {
    for (std::uint64_t t = 0; t < ticks && status_ == Status::Ok; ++t) tick();
}

}  // namespace softbody

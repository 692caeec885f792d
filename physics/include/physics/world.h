// The soft body of Listing 8 and the world it lives in: particles, every-pair springs and
// dampers, gravity, drag, a ground plane with restitution and Coulomb friction, and a fixed
// tick advanced by one of four integrators.
//
// Layout follows "topology apart from state": the rest positions (from which every rest length
// comes) never change after construction; x, Verlet's step x_n - x_{n-1}, v and 1/m are the
// state, in flat arrays.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "physics/arrays.h"
#include "physics/mesh.h"
#include "physics/pair_forces.h"
#include "physics/params.h"
#include "physics/thread_pool.h"

namespace softbody {

enum class Status { Ok, Diverged };

struct Energy {
    double kinetic = 0.0;      // sum 1/2 m |v|^2
    double gravity = 0.0;      // sum -m (g . x)
    double elastic = 0.0;      // sum over springs 1/2 k (l - l0)^2
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

// A spring from one particle to a point in space: the mouse grab of the interactive demo.
struct Grab {
    std::uint32_t particle = 0;
    Vec3 target;
    float stiffness = 0.0f;  // N/m; 0 picks one that moves the body briskly
};

struct WorldOptions {
    int threads = 1;
    bool reference_kernel = false;  // use the readable one-pair-at-a-time loop
};

class World {
public:
    // Throws InputError for invalid params or pins that name no vertex.
    World(const Params& params, Mesh mesh, WorldOptions options = {});
    ~World();
    World(const World&) = delete;
    World& operator=(const World&) = delete;

    // One fixed tick of params().dt, in substeps. Does nothing once diverged.
    void tick();
    void run(std::uint64_t ticks);

    // Back to the start: the mesh placed by init_height and scale, with the current params.
    void reset();

    // Keys marked live in param_table() apply from the next tick; the rest (mesh, scale,
    // init_height, initial_velocity, pinned) apply at the next reset(). Throws InputError.
    void set_params(const Params& params);
    const Params& params() const { return params_; }

    void set_threads(int threads);
    int threads() const { return pool_->threads(); }

    // Interaction (the app's mouse): pin or free a particle, or pull one toward a point.
    void set_pinned(std::uint32_t particle, bool pinned);
    bool is_pinned(std::uint32_t particle) const { return inv_mass_[particle] == 0.0f; }
    void set_grab(std::optional<Grab> grab) {
        grab_ = grab;
        energy_baseline_stale_ = true;  // the grab does work on the body
    }
    const std::optional<Grab>& grab() const { return grab_; }

    Status status() const { return status_; }
    const std::string& divergence() const { return divergence_; }  // why it stopped, and what to change

    std::uint64_t ticks() const { return ticks_; }
    double time() const { return static_cast<double>(ticks_) * static_cast<double>(params_.dt); }

    const Mesh& mesh() const { return mesh_; }
    std::size_t particle_count() const { return x_.size(); }
    std::size_t spring_count() const { return particle_count() * (particle_count() - 1) / 2; }
    const Vec3Array& positions() const { return x_; }
    const Vec3Array& previous_tick_positions() const { return x_tick_prev_; }  // for interpolation
    const Vec3Array& velocities() const { return v_; }
    // Net force on each particle (N) at the last force evaluation, friction included: for display.
    const Vec3Array& forces() const { return force_; }
    const Vec3Array& rest_positions() const { return rest_; }
    const FloatArray& inverse_masses() const { return inv_mass_; }

    Energy energy();
    Vec3 center_of_mass() const;
    float min_z() const;
    Stability stability() const;
    int substeps_in_use() const { return substeps_; }
    std::uint64_t state_hash() const;  // FNV-1a over the bits of x and v

private:
    struct Contact;
    struct StateView;

    void build_particles();
    void apply_pins();
    void update_substeps();
    void step(float h);
    void accelerations(const StateView& s, Vec3Array& a, bool record_contacts);
    void resolve_contacts(float h);
    void check_divergence();
    void take_energy_baseline();
    double kinetic_plus_gravity() const;
    PairInput pair_input(const StateView& s) const;

    Params params_;
    Mesh mesh_;
    std::unique_ptr<ThreadPool> pool_;
    std::unique_ptr<PairForceKernel> kernel_;
    bool reference_kernel_;

    // Topology (fixed): rest positions.
    Vec3Array rest_;
    float rest_radius_ = 0.0f;  // bounding sphere about the rest centre of mass (Eq. 23's S)

    // State.
    Vec3Array x_, v_;
    Vec3Array verlet_step_;     // Verlet's x_n - x_{n-1}, carried as such (see step())
    FloatArray inv_mass_;       // 0 for pinned particles
    float mass_ = 1.0f;
    std::uint64_t ticks_ = 0;
    int substeps_ = 1;
    float verlet_h_ = 0.0f;     // step verlet_step_ was made for (0: make it from v)
    Status status_ = Status::Ok;
    std::string divergence_;
    std::optional<Grab> grab_;

    // Energy at the last outside change (reset, params, pins, grab), for divergence detection.
    double energy_baseline_ = 0.0;  // total energy then, J
    double energy_scale_ = 0.0;     // energy in play then: kinetic + elastic + weight x height, J
    bool energy_baseline_stale_ = true;

    // Scratch, kept to avoid allocating every step.
    Vec3Array force_, accel_[4], x_tmp_, v_stage_, v_sum_;
    Vec3Array x_tick_prev_, x_good_, v_good_, verlet_step_good_;
    std::vector<Contact> contacts_;
};

}  // namespace softbody

#include "physics/world.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "physics/error.h"

namespace softbody {

namespace {

constexpr float kContactTolerance = 1e-5f;  // m: a particle this close to the ground touches it
constexpr float kStaticSpeed = 1e-4f;       // m/s: below this tangential speed, friction is static
constexpr float kMaxSpeed = 1e5f;           // m/s: faster than this is an explosion, not physics
constexpr double kEnergyGrowth = 10.0;      // energy beyond the baseline, in units of the energy in play

void copy(const Vec3Array& from, Vec3Array& to) {
    to.x = from.x;
    to.y = from.y;
    to.z = from.z;
}

std::string fixed(double value, int digits) {
    std::ostringstream out;
    out.setf(std::ios::fixed);
    out.precision(digits);
    out << value;
    return out.str();
}

}  // namespace

// A particle touching the ground at the start of a step, and what friction did to it.
struct World::Contact {
    std::uint32_t particle;
    bool held;            // static friction (Eq. 24) cancelled the whole tangential force
    bool sliding;         // dynamic friction (Eq. 25) acted
    float x0, y0;         // tangential position at the start of the step
    float vx0, vy0;       // tangential velocity at the start of the step
};

struct World::StateView {
    const float *x, *y, *z, *vx, *vy, *vz;
};

World::World(const Params& params, Mesh mesh, WorldOptions options)
    : params_(params), mesh_(std::move(mesh)), reference_kernel_(options.reference_kernel) {
    validate(params_);
    if (mesh_.positions.empty()) throw InputError(mesh_.source + ": the mesh has no vertices");
    for (std::uint32_t vertex : params_.pinned) {
        if (vertex >= mesh_.vertex_to_particle.size()) {
            throw InputError("parameter 'pinned': vertex " + std::to_string(vertex) + " does not exist (the mesh has " +
                             std::to_string(mesh_.vertex_to_particle.size()) + " vertices, numbered from 0)");
        }
    }
    pool_ = std::make_unique<ThreadPool>(std::max(1, options.threads));
    kernel_ = std::make_unique<PairForceKernel>(*pool_);
    build_particles();
}

World::~World() = default;

void World::set_threads(int threads) {
    kernel_.reset();
    pool_ = std::make_unique<ThreadPool>(std::max(1, threads));
    kernel_ = std::make_unique<PairForceKernel>(*pool_);
}

void World::build_particles() {
    const std::size_t n = mesh_.positions.size();
    rest_.resize(n);
    // Turn the mesh about x, then y, then z (files written y-up need 90 degrees about x).
    const float to_rad = 3.14159265358979f / 180.0f;
    const float cx = std::cos(params_.rotation.x * to_rad), sx = std::sin(params_.rotation.x * to_rad);
    const float cy = std::cos(params_.rotation.y * to_rad), sy = std::sin(params_.rotation.y * to_rad);
    const float cz = std::cos(params_.rotation.z * to_rad), sz = std::sin(params_.rotation.z * to_rad);
    auto rotate = [&](Vec3 v) {
        v = {v.x, cx * v.y - sx * v.z, sx * v.y + cx * v.z};
        v = {cy * v.x + sy * v.z, v.y, -sy * v.x + cy * v.z};
        return Vec3{cz * v.x - sz * v.y, sz * v.x + cz * v.y, v.z};
    };
    Vec3 centre;
    for (std::size_t i = 0; i < n; ++i) {
        // Listing 8: the mesh's own coordinates, lifted by init_height.
        const Vec3 p = rotate(mesh_.positions[i]) * params_.scale + Vec3{0.0f, 0.0f, params_.init_height};
        rest_.set(i, p);
        centre += p;
    }
    centre = centre / static_cast<float>(n);
    rest_radius_ = 0.0f;
    for (std::size_t i = 0; i < n; ++i) rest_radius_ = std::max(rest_radius_, length(rest_[i] - centre));

    copy(rest_, x_);
    v_.resize(n);
    for (std::size_t i = 0; i < n; ++i) v_.set(i, params_.initial_velocity);
    mass_ = params_.particle_mass;
    inv_mass_.assign(n, 1.0f / mass_);
    apply_pins();

    verlet_step_.resize(n);
    verlet_h_ = 0.0f;  // Verlet's step is made from v at the first step
    copy(x_, x_tick_prev_);
    force_.resize(n);
    for (auto& a : accel_) a.resize(n);
    ticks_ = 0;
    status_ = Status::Ok;
    divergence_.clear();
    grab_.reset();
    energy_baseline_stale_ = true;
    update_substeps();
}

void World::apply_pins() {
    for (std::uint32_t vertex : params_.pinned) {
        const std::uint32_t p = mesh_.vertex_to_particle[vertex];
        inv_mass_[p] = 0.0f;
        v_.set(p, {});
    }
}

void World::reset() { build_particles(); }

void World::set_params(const Params& params) {
    validate(params);
    for (std::uint32_t vertex : params.pinned) {
        if (vertex >= mesh_.vertex_to_particle.size()) {
            throw InputError("parameter 'pinned': vertex " + std::to_string(vertex) + " does not exist (the mesh has " +
                             std::to_string(mesh_.vertex_to_particle.size()) + " vertices)");
        }
    }
    if (params.particle_mass != mass_) {
        mass_ = params.particle_mass;
        for (float& w : inv_mass_) {
            if (w != 0.0f) w = 1.0f / mass_;
        }
    }
    // Switching to Verlet restarts it from the current x and v (x_{-1} = x_0 - v_0 h): its step
    // was last kept up to date when Verlet last ran, and is stale by now.
    if (params.integrator != params_.integrator) verlet_h_ = 0.0f;
    if (!(params == params_)) energy_baseline_stale_ = true;
    params_ = params;
    update_substeps();
}

void World::set_pinned(std::uint32_t particle, bool pinned) {
    if (particle >= particle_count()) return;
    inv_mass_[particle] = pinned ? 0.0f : 1.0f / mass_;
    if (pinned) {
        v_.set(particle, {});
        verlet_step_.set(particle, {});
    }
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
// Forces
// ---------------------------------------------------------------------------------------------
PairInput World::pair_input(const StateView& s) const {
    return PairInput{s.x, s.y, s.z, s.vx, s.vy, s.vz, rest_.x.data(), rest_.y.data(), rest_.z.data(),
                     particle_count(), params_.stiffness, params_.damping};
}

void World::accelerations(const StateView& s, Vec3Array& a, bool record_contacts) {
    const std::size_t n = particle_count();
    const PairInput in = pair_input(s);
    if (reference_kernel_) pair_forces_reference(in, force_);
    else kernel_->compute(in, force_);

    // Gravity: the particle's weight, m g.
    const Vec3 weight = params_.gravity * mass_;
    for (std::size_t i = 0; i < n; ++i) force_.add(i, weight);

    // Eq. 23, aerodynamic drag, from the centre-of-mass velocity, shared by mass (no torque).
    if (params_.drag_coefficient > 0.0f && params_.air_density > 0.0f) {
        double vx = 0.0, vy = 0.0, vz = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            vx += s.vx[i];
            vy += s.vy[i];
            vz += s.vz[i];
        }
        const Vec3 v_com{float(vx / double(n)), float(vy / double(n)), float(vz / double(n))};
        const float S = 3.14159265f * rest_radius_ * rest_radius_;  // bounding sphere's cross-section
        const Vec3 F_drag = -0.5f * params_.air_density * params_.drag_coefficient * S * length(v_com) * v_com;
        const Vec3 share = F_drag / static_cast<float>(n);
        for (std::size_t i = 0; i < n; ++i) force_.add(i, share);
    }

    // The mouse: a damped spring from one particle to a point.
    if (grab_ && grab_->particle < n) {
        const std::uint32_t p = grab_->particle;
        const float h = params_.dt / static_cast<float>(substeps_);
        // Default: stiff enough to drag the body, soft enough to be stable on its own (h w = 1).
        const float k_grab = grab_->stiffness > 0.0f ? grab_->stiffness : mass_ / (h * h) * 0.5f;
        const float c_grab = 2.0f * std::sqrt(k_grab * mass_) * 0.5f;
        const Vec3 x_p{s.x[p], s.y[p], s.z[p]}, v_p{s.vx[p], s.vy[p], s.vz[p]};
        force_.add(p, k_grab * (grab_->target - x_p) - c_grab * v_p);
    }

    // Eq. 24 and Eq. 25: Coulomb friction for particles touching and pressed into the ground.
    // F_applied is everything above; n = (0, 0, 1).
    if (record_contacts) contacts_.clear();
    if (params_.ground) {
        const float mu_s = params_.static_friction, mu_d = params_.dynamic_friction;
        for (std::size_t i = 0; i < n; ++i) {
            if (s.z[i] > params_.ground_height + kContactTolerance || inv_mass_[i] == 0.0f) continue;
            const float F_n = force_.z[i];  // F_applied . n; < 0 presses into the ground
            if (!(F_n < 0.0f)) continue;
            const float F_tx = force_.x[i], F_ty = force_.y[i];
            const float F_t = std::sqrt(F_tx * F_tx + F_ty * F_ty);
            const float v_tx = s.vx[i], v_ty = s.vy[i];
            const float v_t = std::sqrt(v_tx * v_tx + v_ty * v_ty);
            Contact contact{static_cast<std::uint32_t>(i), false, false, s.x[i], s.y[i], v_tx, v_ty};
            if (v_t < kStaticSpeed) {
                // Eq. 24: F_friction = -(F_t/|F_t|) min(mu_s |F_n|, |F_t|).
                const float limit = mu_s * -F_n;
                if (F_t <= limit) {
                    force_.x[i] = 0.0f;  // cancels F_t exactly: the particle stays put
                    force_.y[i] = 0.0f;
                    contact.held = true;
                } else {
                    force_.x[i] -= F_tx / F_t * limit;
                    force_.y[i] -= F_ty / F_t * limit;
                }
            } else {
                // Eq. 25: F_friction = -(v_t/|v_t|) mu_d |F_n|.
                const float magnitude = mu_d * -F_n;
                force_.x[i] -= v_tx / v_t * magnitude;
                force_.y[i] -= v_ty / v_t * magnitude;
                contact.sliding = true;
            }
            if (record_contacts) contacts_.push_back(contact);
        }
    }

    for (std::size_t i = 0; i < n; ++i) {
        a.x[i] = force_.x[i] * inv_mass_[i];
        a.y[i] = force_.y[i] * inv_mass_[i];
        a.z[i] = force_.z[i] * inv_mass_[i];
    }
}

// ---------------------------------------------------------------------------------------------
// Integrators: one step of h
// ---------------------------------------------------------------------------------------------
void World::step(float h) {
    const std::size_t n = particle_count();
    const StateView now{x_.x.data(), x_.y.data(), x_.z.data(), v_.x.data(), v_.y.data(), v_.z.data()};
    Vec3Array& a = accel_[0];

    switch (params_.integrator) {
        case Integrator::Verlet: {
            // Start (or restart after dt or the integrator changed): x_{-1} = x_0 - v_0 h, so
            // the step x_0 - x_{-1} is v_0 h.
            if (verlet_h_ != h) {
                for (std::size_t i = 0; i < n; ++i) verlet_step_.set(i, v_[i] * h);
                verlet_h_ = h;
            }
            accelerations(now, a, true);
            const float h2 = h * h;
            for (std::size_t i = 0; i < n; ++i) {
                // x_{n+1} = 2 x_n - x_{n-1} + a h^2 (positions);  v_{n+1} = v_n + a h (velocities).
                // Summed as x_{n+1} = x_n + s_{n+1}, s_{n+1} = s_n + a h^2, carrying the step s
                // itself: the same recurrence, but taking s as the difference of two rounded
                // positions would feed their rounding back into it every step. Near rest a h^2
                // falls below half an ulp of a position a metre from the origin (6e-8 m), and
                // that feedback decouples x from v: a hanging mass then creeps down an ulp per
                // tick for ever while v points up, and the dampers, fed v, hold it at the wrong
                // stretch.
                const Vec3 s_next = verlet_step_[i] + a[i] * h2;
                verlet_step_.set(i, s_next);
                x_.add(i, s_next);
                v_.add(i, a[i] * h);
            }
            break;
        }
        case Integrator::SymplecticEuler:
            accelerations(now, a, true);
            for (std::size_t i = 0; i < n; ++i) {
                v_.add(i, a[i] * h);  // v_{n+1} = v_n + a h
                x_.add(i, v_[i] * h); // x_{n+1} = x_n + v_{n+1} h
            }
            break;
        case Integrator::ExplicitEuler:
            accelerations(now, a, true);
            for (std::size_t i = 0; i < n; ++i) {
                x_.add(i, v_[i] * h);  // x_{n+1} = x_n + v_n h
                v_.add(i, a[i] * h);   // v_{n+1} = v_n + a_n h
            }
            break;
        case Integrator::RK4: {
            // Classic Runge-Kutta on d/dt (x, v) = (v, a(x, v)):
            //   stage s: x_s = x + v_{s-1} w_s,  v_s = v + a_{s-1} w_s,  a_s = a(x_s, v_s)
            //   with w = h/2, h/2, h; then x += h/6 (v_1 + 2 v_2 + 2 v_3 + v_4), same for v with a.
            copy(v_, v_stage_);
            copy(v_, v_sum_);
            x_tmp_.resize(n);
            accelerations(now, accel_[0], true);
            for (int s = 1; s <= 3; ++s) {
                const float w = s < 3 ? 0.5f * h : h;
                const float weight = s < 3 ? 2.0f : 1.0f;
                for (std::size_t i = 0; i < n; ++i) {
                    x_tmp_.set(i, x_[i] + v_stage_[i] * w);       // uses v_{s-1}
                    v_stage_.set(i, v_[i] + accel_[s - 1][i] * w);  // becomes v_s
                }
                const StateView stage{x_tmp_.x.data(), x_tmp_.y.data(), x_tmp_.z.data(),
                                      v_stage_.x.data(), v_stage_.y.data(), v_stage_.z.data()};
                accelerations(stage, accel_[s], false);
                for (std::size_t i = 0; i < n; ++i) v_sum_.add(i, v_stage_[i] * weight);
            }
            for (std::size_t i = 0; i < n; ++i) {
                x_.add(i, v_sum_[i] * (h / 6.0f));
                v_.add(i, (accel_[0][i] + 2.0f * accel_[1][i] + 2.0f * accel_[2][i] + accel_[3][i]) * (h / 6.0f));
            }
            break;
        }
    }
    // Pinned particles stay where they are.
    for (std::size_t i = 0; i < n; ++i) {
        if (inv_mass_[i] == 0.0f) v_.set(i, {});
    }
    resolve_contacts(h);
}

// After a step: static friction holds, sliding stops without reversing, and the ground pushes
// back with restitution. x and v are set together, and Verlet's step with them, so position
// and velocity stay consistent (x_n - x_{n-1} = v h).
void World::resolve_contacts(float h) {
    const bool verlet = params_.integrator == Integrator::Verlet;
    for (const Contact& c : contacts_) {
        const std::uint32_t i = c.particle;
        const bool reversed = c.sliding && (v_.x[i] * c.vx0 + v_.y[i] * c.vy0) <= 0.0f;
        if (c.held || reversed) {
            // The slide ends within this step: v_t = 0, and x_t = x_t(start) + v_t h.
            v_.x[i] = 0.0f;
            v_.y[i] = 0.0f;
            x_.x[i] = c.x0;
            x_.y[i] = c.y0;
            if (verlet) {
                verlet_step_.x[i] = 0.0f;
                verlet_step_.y[i] = 0.0f;
            }
        }
    }
    if (!params_.ground) return;
    const float ground = params_.ground_height;
    // Impacts slower than two steps of gravity are resting contact, not a bounce.
    const float bounce_speed = 2.0f * std::abs(params_.gravity.z) * h;
    for (std::size_t i = 0; i < particle_count(); ++i) {
        if (!(x_.z[i] < ground) || inv_mass_[i] == 0.0f) continue;
        x_.z[i] = ground;
        const float v_n = v_.z[i];
        if (v_n < -bounce_speed) v_.z[i] = -params_.restitution * v_n;  // v_n' = -e v_n
        else if (v_n < 0.0f) v_.z[i] = 0.0f;
        if (verlet) verlet_step_.set(i, v_[i] * h);
    }
}

// ---------------------------------------------------------------------------------------------
// Ticks and divergence
// ---------------------------------------------------------------------------------------------
void World::tick() {
    if (status_ != Status::Ok) return;
    if (energy_baseline_stale_ && !grab_) take_energy_baseline();
    copy(x_, x_tick_prev_);
    copy(x_, x_good_);
    copy(v_, v_good_);
    copy(verlet_step_, verlet_step_good_);
    const float good_verlet_h = verlet_h_;
    const float h = params_.dt / static_cast<float>(substeps_);
    for (int s = 0; s < substeps_; ++s) step(h);
    ++ticks_;
    check_divergence();
    if (status_ != Status::Ok) {
        // Keep the last finite state on show; nothing downstream ever sees a NaN.
        copy(x_good_, x_);
        copy(v_good_, v_);
        copy(verlet_step_good_, verlet_step_);
        copy(x_, x_tick_prev_);
        verlet_h_ = good_verlet_h;
        --ticks_;
    }
}

void World::run(std::uint64_t ticks) {
    for (std::uint64_t t = 0; t < ticks && status_ == Status::Ok; ++t) tick();
}

void World::check_divergence() {
    const std::size_t n = particle_count();
    const Vec3 com = center_of_mass();
    const float limit = std::max(50.0f * rest_radius_, rest_radius_ + 50.0f);
    std::string what;
    for (std::size_t i = 0; i < n && what.empty(); ++i) {
        const Vec3 x = x_[i], v = v_[i];
        if (!is_finite(x) || !is_finite(v)) {
            what = "particle " + std::to_string(i) + "'s state is no longer a finite number";
        } else if (length(x - com) > limit) {
            what = "particle " + std::to_string(i) + " is " + fixed(length(x - com), 1) +
                   " m from the centre of mass (the body's radius is " + fixed(rest_radius_, 2) + " m)";
        } else if (length(v) > kMaxSpeed) {
            what = "particle " + std::to_string(i) + " moves at " + fixed(length(v), 0) + " m/s";
        }
    }
    // Past its stability limit a body need not fly apart: the fastest mode (the uniform
    // expansion) can grow until the springs turn the body inside out and cap it, leaving it
    // churning in place with a hundred times the energy it had, every particle close to the
    // centre of mass and at a finite speed. Nothing in the world supplies energy except the
    // grab (dampers, drag, friction and impacts remove it; gravity's work is the gravitational
    // term), so kinetic + gravitational energy, a lower bound of the total (elastic energy is
    // never negative), far above the total at the last outside change was made by the step.
    // Only flagged when the step is past its estimated limit: explicit Euler gains energy on
    // purpose even where no mode grows exponentially (a particle in free fall).
    if (what.empty() && !grab_ && !energy_baseline_stale_) {
        const double E = kinetic_plus_gravity();
        const double allowed = energy_baseline_ + kEnergyGrowth * energy_scale_ + 1e-9 * std::abs(energy_baseline_);
        if (E > allowed && !stability().stable) {
            what = "the body's kinetic and gravitational energy reached " + fixed(E, 1) + " J, from a total of " +
                   fixed(energy_baseline_, 1) + " J with nothing to supply more";
        }
    }
    if (what.empty()) return;

    const Stability s = stability();
    std::ostringstream out;
    out << "diverged in tick " << ticks_ << " (t = " << fixed(time(), 2) << " s): " << what << ". ";
    if (!s.stable) {
        out << "The step is past its stability limit for " << to_string(params_.integrator) << " (h*omega = "
            << fixed(s.h_omega, 2) << ", limit " << fixed(s.limit, 2) << ", growth " << fixed(s.growth, 3)
            << " per step): ";
        if (s.substeps_needed > 0) {
            out << "set substeps to at least " << s.substeps_needed << " (or auto_substeps=true)";
        } else {
            out << "use another integrator";
        }
        out << ", or lower stiffness or damping, raise particle_mass, or shorten dt";
    } else {
        out << "The step was within its estimated limit (h*omega = " << fixed(s.h_omega, 2) << " of "
            << fixed(s.limit, 2) << "); large deformations or hard impacts can still excite it: raise "
            << "substeps, or lower stiffness or damping, or raise particle_mass";
    }
    status_ = Status::Diverged;
    divergence_ = out.str();
}

// The energy budget for check_divergence, taken before the first tick after an outside change.
// The scale is the energy in play: motion, deformation and the fall to the ground (plus two
// body radii of it, so a body resting on the ground or in free space has some), generous for
// the bounded energy error of a stable step.
void World::take_energy_baseline() {
    const Energy e = energy();
    energy_baseline_ = e.total();
    double height = 0.0;
    if (params_.ground) height = std::max(0.0, double(center_of_mass().z) - double(params_.ground_height));
    const double weight = double(mass_) * double(particle_count()) * double(length(params_.gravity));
    energy_scale_ = e.kinetic + e.elastic + weight * (height + 2.0 * double(rest_radius_));
    energy_baseline_stale_ = false;
}

// The O(N) part of energy(): sum 1/2 m |v|^2 (free particles) + sum -m (g . x).
double World::kinetic_plus_gravity() const {
    double kinetic = 0.0, gravity = 0.0;
    for (std::size_t i = 0; i < particle_count(); ++i) {
        const Vec3 v = v_[i];
        if (inv_mass_[i] != 0.0f) kinetic += 0.5 * double(mass_) * double(dot(v, v));
        gravity -= double(mass_) * double(dot(params_.gravity, x_[i]));
    }
    return kinetic + gravity;
}

// ---------------------------------------------------------------------------------------------
// Diagnostics
// ---------------------------------------------------------------------------------------------
Energy World::energy() {
    Energy e;
    const std::size_t n = particle_count();
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3 v = v_[i], x = x_[i];
        const double m = inv_mass_[i] == 0.0f ? 0.0 : mass_;  // pinned particles do not move
        e.kinetic += 0.5 * m * double(dot(v, v));
        e.gravity -= double(mass_) * double(dot(params_.gravity, x));
    }
    const StateView now{x_.x.data(), x_.y.data(), x_.z.data(), v_.x.data(), v_.y.data(), v_.z.data()};
    e.elastic = reference_kernel_ ? elastic_energy_reference(pair_input(now)) : kernel_->elastic_energy(pair_input(now));
    return e;
}

Vec3 World::center_of_mass() const {
    double x = 0.0, y = 0.0, z = 0.0;
    const std::size_t n = particle_count();
    for (std::size_t i = 0; i < n; ++i) {
        x += x_.x[i];
        y += x_.y[i];
        z += x_.z[i];
    }
    return {float(x / double(n)), float(y / double(n)), float(z / double(n))};
}

float World::min_z() const { return *std::min_element(x_.z.begin(), x_.z.end()); }

std::uint64_t World::state_hash() const {
    std::uint64_t hash = 1469598103934665603ull;
    auto mix = [&](const FloatArray& values) {
        for (float value : values) {
            std::uint32_t bits;
            std::memcpy(&bits, &value, sizeof bits);
            for (int b = 0; b < 4; ++b) hash = (hash ^ ((bits >> (8 * b)) & 0xFFu)) * 1099511628211ull;
        }
    };
    for (const auto* a : {&x_, &v_}) {
        mix(a->x);
        mix(a->y);
        mix(a->z);
    }
    return hash;
}

}  // namespace softbody

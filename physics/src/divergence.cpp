// Divergence: after each tick the state is checked, and a state that has blown up stops the
// world with a message that says which limit was crossed and what to change. The last good
// state stays on show (World::tick restores it); nothing downstream ever sees a NaN.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "physics/world.h"

namespace softbody {

namespace {

constexpr float kMaxSpeed = 1e5f;       // m/s: faster than this is an explosion, not physics
constexpr double kMaxAngularSpeed = 1e5;  // rad/s: 16,000 turns a second is an explosion too
constexpr double kMaxDistance = 1e7;    // m from the origin: a rigid body flung this far has blown up
constexpr double kEnergyGrowth = 10.0;  // energy beyond the baseline, in units of the energy in play

std::string fixed(double value, int digits) {
    std::ostringstream out;
    out.setf(std::ios::fixed);
    out.precision(digits);
    out << value;
    return out.str();
}

Vec3 centre_of(const SoftBody& body) {
    double x = 0.0, y = 0.0, z = 0.0;
    const std::size_t n = body.particle_count();
    for (std::size_t i = 0; i < n; ++i) {
        x += body.x.x[i];
        y += body.x.y[i];
        z += body.x.z[i];
    }
    return {float(x / double(n)), float(y / double(n)), float(z / double(n))};
}

// What is wrong with a soft body's state, or "" when nothing is: a number that is not finite,
// a particle flung far from the body (max(50 r, r + 50 m) from the centre of mass, r the rest
// bounding radius), or one moving faster than kMaxSpeed.
std::string soft_body_fault(const SoftBody& body, const std::string& who) {
    const Vec3 com = centre_of(body);
    const float limit = std::max(50.0f * body.rest_radius, body.rest_radius + 50.0f);
    for (std::size_t i = 0; i < body.particle_count(); ++i) {
        const Vec3 x = body.x[i], v = body.v[i];
        if (!is_finite(x) || !is_finite(v)) {
            return who + std::to_string(i) + "'s state is no longer a finite number";
        } else if (length(x - com) > limit) {
            return who + std::to_string(i) + " is " + fixed(length(x - com), 1) +
                   " m from the centre of mass (the body's radius is " + fixed(body.rest_radius, 2) + " m)";
        } else if (length(v) > kMaxSpeed) {
            return who + std::to_string(i) + " moves at " + fixed(length(v), 0) + " m/s";
        }
    }
    return "";
}

// What is wrong with a rigid body's state, or "": a number that is not finite, an absurd speed
// or spin, or a body flung absurdly far.
// `m`: its motion, rigid_motion(body, state).
std::string rigid_body_fault(const RigidBody& body, const double* state, const RigidMotion& m) {
    const auto who = [&] { return "rigid body '" + body.name + "'"; };
    for (int k = 0; k < rigid::kStateSize; ++k) {
        if (!std::isfinite(state[k])) return who() + "'s state is no longer a finite number";
    }
    if (!is_finite(m.omega) || !is_finite(m.v)) return who() + "'s state is no longer a finite number";
    if (length(m.v) > kMaxSpeed) return who() + " moves at " + fixed(length(m.v), 0) + " m/s";
    if (length(m.omega) > kMaxAngularSpeed) return who() + " spins at " + fixed(length(m.omega), 0) + " rad/s";
    if (length(m.x) > kMaxDistance) return who() + " is " + fixed(length(m.x), 0) + " m from the origin";
    return "";
}

}  // namespace

void World::check_divergence() {
    std::string what;
    for (std::size_t b = 0; b < soft_.size() && what.empty(); ++b) {
        const std::string who = soft_.size() > 1 ? "body '" + soft_[b].name() + "' particle " : "particle ";
        what = soft_body_fault(soft_[b], who);
    }
    // A body asleep or fixed has not moved since it was last checked (nor can it have). The
    // first body at fault, looked for on every thread (each chunk's first, then the first chunk's).
    if (what.empty()) {
        const std::size_t none = rigid_.size();
        std::vector<std::size_t> first_fault(std::size_t(4 * pool_->threads()), none);
        for_chunks(pool_.get(), rigid_.size(), 256, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
            for (std::size_t b = begin; b < end && first_fault[chunk] == none; ++b) {
                if (!rigid_[b].fixed && !asleep_[b] && !rigid_body_fault(rigid_[b], rigid_state(b), motion_[b]).empty()) first_fault[chunk] = b;
            }
        });
        const std::size_t b = *std::min_element(first_fault.begin(), first_fault.end());
        if (b != none) what = rigid_body_fault(rigid_[b], rigid_state(b), motion_[b]);
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
    // (The step's limit first: it costs a few operations a soft body and spring, where the
    // energy is a sum over every body, every tick, on one thread.)
    if (what.empty() && !grab_ && !energy_baseline_stale_ && !stability().stable) {
        const double E = kinetic_plus_gravity();
        const double allowed = energy_baseline_ + kEnergyGrowth * energy_scale_ + 1e-9 * std::abs(energy_baseline_);
        if (E > allowed) {
            what = std::string(soft_.size() + rigid_.size() > 1 ? "the bodies'" : "the body's") +
                   " kinetic and gravitational energy reached " + fixed(E, 1) + " J, from a total of " +
                   fixed(energy_baseline_, 1) + " J with nothing to supply more";
        }
    }
    if (what.empty()) return;

    const Stability s = stability();
    std::ostringstream out;
    out << "diverged in tick " << ticks_ << " (t = " << fixed(time(), 2) << " s): " << what << ". ";
    if (!s.stable) {
        out << "The step is past its stability limit for " << to_string(settings_.integrator) << " (h*omega = "
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
    energy_scale_ = e.kinetic + e.elastic;
    for (const SoftBody& body : soft_) {
        double height = 0.0;
        if (settings_.ground) height = std::max(0.0, double(centre_of(body).z) - double(settings_.ground_height));
        const double weight = double(body.mass) * double(body.particle_count()) * double(length(settings_.gravity));
        energy_scale_ += weight * (height + 2.0 * double(body.rest_radius));
    }
    energy_baseline_stale_ = false;
}

// The O(N) part of energy(): sum 1/2 m |v|^2 (free particles) + sum -m (g . x), and the
// rigid bodies' kinetic and gravitational energy.
double World::kinetic_plus_gravity() const {
    double kinetic = 0.0, gravity = 0.0;
    for (const SoftBody& body : soft_) {
        for (std::size_t i = 0; i < body.particle_count(); ++i) {
            const Vec3 v = body.v[i];
            if (body.inv_mass[i] != 0.0f) kinetic += 0.5 * double(body.mass) * double(dot(v, v));
            gravity -= double(body.mass) * double(dot(settings_.gravity, body.x[i]));
        }
    }
    // A sleeping body's P and L are exactly 0: its kinetic energy adds nothing, not even a
    // rounding, and its motion (a rotation matrix and J^-1) is not worked out.
    for (std::size_t b = 0; b < rigid_.size(); ++b) {
        if (rigid_[b].fixed) continue;
        const double* s = rigid_state(b);
        if (!asleep_[b]) {
            const RigidMotion m = rigid_motion(b);
            kinetic += 0.5 * dot(m.P, m.v) + 0.5 * dot(m.L, m.omega);
        }
        gravity -= rigid_[b].mass * dot(Vec3d(settings_.gravity), Vec3d{s[rigid::X], s[rigid::X + 1], s[rigid::X + 2]});
    }
    return kinetic + gravity;
}

}  // namespace softbody

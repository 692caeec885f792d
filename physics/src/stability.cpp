// The stability estimate: how far the explicit step is from blowing up.
//
// Linearised about the rest shape, the springs' stiffness matrix is K = k G and the dampers'
// is C = c G, with G = sum over pairs of (e_i - e_j)(e_i - e_j)^T (x) d_hat d_hat^T. Because
// dampers and springs share G, every vibration mode of G (eigenvalue lambda of M^-1 G) is a
// damped oscillator x'' = -omega^2 x - gamma x' with omega^2 = k lambda, gamma = c lambda.
//
// For every pair joined and equal masses m, the uniform expansion u_i = x_i - x_com is an
// exact mode with lambda = N / m (each d_hat . (u_i - u_j) = -l0), and no mode is faster:
// d_hat d_hat^T <= I, so G <= L (x) I with L the complete graph's Laplacian, whose largest
// eigenvalue is N. Pinned particles only remove rows, which cannot raise the maximum.
// So lambda_max = N / m exactly without pins, and bounds it with them.
//
// Each integrator maps (x, v) of a mode to A (x, v) every step; the step is stable while the
// spectral radius of A stays at or below 1. That radius is computed here for the fastest mode
// and slower ones (explicit Euler can grow on slow modes first).
#include "stability.h"

#include <algorithm>
#include <cmath>

namespace softbody {

namespace {

struct Mat2 {
    double a, b, c, d;  // [[a, b], [c, d]]
    Mat2 operator*(const Mat2& o) const {
        return {a * o.a + b * o.c, a * o.b + b * o.d, c * o.a + d * o.c, c * o.b + d * o.d};
    }
    Mat2 operator+(const Mat2& o) const { return {a + o.a, b + o.b, c + o.c, d + o.d}; }
    Mat2 operator*(double s) const { return {a * s, b * s, c * s, d * s}; }
};

double spectral_radius(const Mat2& m) {
    const double trace = m.a + m.d, det = m.a * m.d - m.b * m.c;
    const double disc = trace * trace - 4.0 * det;
    if (disc < 0.0) return std::sqrt(std::max(det, 0.0));  // complex pair: |lambda|^2 = det
    const double root = std::sqrt(disc);
    return std::max(std::abs(trace + root), std::abs(trace - root)) / 2.0;
}

// One step's amplification of (x, v) for x'' = -w2 x - g x'.
Mat2 amplification(Integrator integrator, double h, double w2, double g) {
    switch (integrator) {
        case Integrator::Verlet:           // identical to symplectic Euler for a linear mode
        case Integrator::SymplecticEuler:  // v' = v + h(-w2 x - g v), x' = x + h v'
            return {1.0 - h * h * w2, h * (1.0 - h * g), -h * w2, 1.0 - h * g};
        case Integrator::ExplicitEuler:    // x' = x + h v, v' = v + h(-w2 x - g v)
            return {1.0, h, -h * w2, 1.0 - h * g};
        case Integrator::RK4: {            // I + hJ + (hJ)^2/2 + (hJ)^3/6 + (hJ)^4/24
            const Mat2 hJ{0.0, h, -h * w2, -h * g};
            const Mat2 hJ2 = hJ * hJ, hJ3 = hJ2 * hJ, hJ4 = hJ3 * hJ;
            return Mat2{1.0, 0.0, 0.0, 1.0} + hJ + hJ2 * 0.5 + hJ3 * (1.0 / 6.0) + hJ4 * (1.0 / 24.0);
        }
    }
    return {1.0, 0.0, 0.0, 1.0};
}

// Largest growth over modes lambda_max, lambda_max/2, ..., lambda_max/2^20.
double growth(Integrator integrator, double h, double lambda_max, double k, double c) {
    double worst = 0.0;
    double lambda = lambda_max;
    for (int m = 0; m <= 20; ++m, lambda *= 0.5) {
        worst = std::max(worst, spectral_radius(amplification(integrator, h, k * lambda, c * lambda)));
    }
    return worst;
}

}  // namespace

// One mode x'' = -k lambda x - c lambda x' under the world's integrator and step.
Stability mode_stability(double lambda, double k, double c, const WorldSettings& world, int substeps) {
    Stability s;
    const double dt = world.dt;
    s.omega_max = std::sqrt(k * lambda);
    s.gamma_max = c * lambda;
    s.substeps = substeps;
    s.h = dt / substeps;
    s.h_omega = std::sqrt(s.h * s.h * s.omega_max * s.omega_max + 2.0 * s.h * s.gamma_max);
    s.limit = world.integrator == Integrator::RK4 ? 2.0 * std::sqrt(2.0) : 2.0;
    constexpr double kTolerance = 1e-9;  // an undamped mode under Verlet sits at exactly 1
    s.growth = growth(world.integrator, s.h, lambda, k, c);
    s.stable = s.growth <= 1.0 + kTolerance;
    // Fewest substeps stable with the springs up to 25% stiffer (about 12% on omega): stretched
    // and bent springs stiffen a little, and a run right at the limit would sit on the edge of
    // growing. Stiffer, not more modes: the dampers do not stiffen with them, which is what
    // explicit Euler's limit (c >= h k, whatever the mode) needs a margin on (two soft balls
    // squashed head-on grew from a step at exactly that limit). Every stiffness from k to 1.25 k,
    // not only the last: with damping, RK4's stable region is not a disc, and a mode can be
    // stable at 1.25 k and grow at k (three soft cubes stacked under RK4 got 6 substeps, grew
    // 2.2% a step at them and diverged in tick 9).
    const auto stable_at = [&](int sub) {
        for (const double stiffer : {1.0, 1.0625, 1.125, 1.1875, 1.25}) {
            if (growth(world.integrator, dt / sub, lambda, stiffer * k, c) > 1.0 + kTolerance) return false;
        }
        return true;
    };
    s.substeps_needed = 0;
    for (int sub = 1; sub <= 1000; ++sub) {
        if (stable_at(sub)) {
            s.substeps_needed = sub;
            break;
        }
    }
    return s;
}

Stability soft_body_stability(const SoftBody& body, const WorldSettings& world, int substeps) {
    const double n = static_cast<double>(body.particle_count());
    const double lambda = n >= 2.0 ? n / double(body.mass) : 0.0;  // lambda_max of M^-1 G, see above
    return mode_stability(lambda, body.stiffness, body.damping, world, substeps);
}

// A spring between bodies is one mode: its two ends move apart along the spring against the
// inverse mass each end offers there, 1/m + (r x d)^T J^-1 (r x d) for a rigid body's point
// (Eq. 38's denominator: a point off the centre of mass also turns the body), 1/m for a
// particle, 0 for the world; lambda is their sum.
double World::link_inverse_mass(const Link& link) const {
    const Vec3d a = link_end_position(link.a), b = link_end_position(link.b);
    const Vec3d d = length(b - a) > 0.0 ? normalize(b - a) : Vec3d{0.0, 0.0, 1.0};
    const auto end = [&](const LinkEnd& e) {
        switch (e.kind) {
            case LinkEnd::Kind::World: return 0.0;
            case LinkEnd::Kind::Soft: return double(soft_[e.body].inv_mass[e.particle]);
            case LinkEnd::Kind::Rigid: {
                const RigidMotion m = rigid_motion(e.body);
                const Vec3d rxd = cross(m.R * e.point, d);
                return rigid_[e.body].inv_mass + dot(rxd, m.J_inv * rxd);
            }
        }
        return 0.0;
    };
    return end(link.a) + end(link.b);
}

// The world's step must suit its least stable part, a soft body or a spring between bodies:
// the largest growth, and the most substeps needed (where 0, none is enough, outranks every
// count).
Stability World::stability() const {
    Stability worst;
    worst.substeps = substeps_;
    worst.h = settings_.dt / substeps_;
    worst.limit = settings_.integrator == Integrator::RK4 ? 2.0 * std::sqrt(2.0) : 2.0;
    int needed = 1;
    bool first = true;
    const auto take = [&](const Stability& s) {
        needed = first ? s.substeps_needed
                       : (needed == 0 || s.substeps_needed == 0 ? 0 : std::max(needed, s.substeps_needed));
        if (first || s.growth > worst.growth) worst = s;
        first = false;
    };
    for (const SoftBody& body : soft_) take(soft_body_stability(body, settings_, substeps_));
    for (const Link& link : links_) take(mode_stability(link_inverse_mass(link), link.k, link.c, settings_, substeps_));
    worst.substeps_needed = needed;
    return worst;
}

}  // namespace softbody

#include "integrators.h"

#include <algorithm>
#include <cmath>

namespace softbody {

namespace {

// RK4's stage s: w = h/2, h/2, h from the start; its weight in the sum: 2, 2, 1.
float rk4_offset(int s, float h) { return s < 3 ? 0.5f * h : h; }
float rk4_weight(int s) { return s < 3 ? 2.0f : 1.0f; }

}  // namespace

// ---------------------------------------------------------------------------------------------
// Particles
// ---------------------------------------------------------------------------------------------
void verlet_start(SoftBody& body, float h) {
    if (body.verlet_h == h) return;
    for (std::size_t i = 0; i < body.particle_count(); ++i) body.verlet_step.set(i, body.v[i] * h);
    body.verlet_h = h;
}

void verlet_update(SoftBody& body, float h) {
    const Vec3Array& a = body.accel[0];
    const float h2 = h * h;
    for (std::size_t i = 0; i < body.particle_count(); ++i) {
        // x_{n+1} = 2 x_n - x_{n-1} + a h^2 (positions);  v_{n+1} = v_n + a h (velocities).
        // Summed as x_{n+1} = x_n + s_{n+1}, s_{n+1} = s_n + a h^2, carrying the step s
        // itself: the same recurrence, but taking s as the difference of two rounded
        // positions would feed their rounding back into it every step. Near rest a h^2
        // falls below half an ulp of a position a metre from the origin (6e-8 m), and
        // that feedback decouples x from v: a hanging mass then creeps down an ulp per
        // tick for ever while v points up, and the dampers, fed v, hold it at the wrong
        // stretch.
        const Vec3 s_next = body.verlet_step[i] + a[i] * h2;
        body.verlet_step.set(i, s_next);
        body.x.add(i, s_next);
        body.v.add(i, a[i] * h);
    }
}

void symplectic_euler_update(SoftBody& body, float h) {
    const Vec3Array& a = body.accel[0];
    for (std::size_t i = 0; i < body.particle_count(); ++i) {
        body.v.add(i, a[i] * h);       // v_{n+1} = v_n + a h
        body.x.add(i, body.v[i] * h);  // x_{n+1} = x_n + v_{n+1} h
    }
}

void explicit_euler_update(SoftBody& body, float h) {
    const Vec3Array& a = body.accel[0];
    for (std::size_t i = 0; i < body.particle_count(); ++i) {
        body.x.add(i, body.v[i] * h);  // x_{n+1} = x_n + v_n h
        body.v.add(i, a[i] * h);       // v_{n+1} = v_n + a_n h
    }
}

// Classic Runge-Kutta on d/dt (x, v) = (v, a(x, v)):
//   stage s: x_s = x + v_{s-1} w_s,  v_s = v + a_{s-1} w_s,  a_s = a(x_s, v_s)
//   with w = h/2, h/2, h; then x += h/6 (v_1 + 2 v_2 + 2 v_3 + v_4), same for v with a.
void rk4_begin(SoftBody& body) {
    body.v_stage = body.v;
    body.v_sum = body.v;
    body.x_tmp.resize(body.particle_count());
}

void rk4_stage(SoftBody& body, int s, float h) {
    const float w = rk4_offset(s, h);
    const Vec3Array& a = body.accel[s - 1];
    for (std::size_t i = 0; i < body.particle_count(); ++i) {
        body.x_tmp.set(i, body.x[i] + body.v_stage[i] * w);  // uses v_{s-1}
        body.v_stage.set(i, body.v[i] + a[i] * w);           // becomes v_s
    }
}

void rk4_accumulate(SoftBody& body, int s) {
    const float weight = rk4_weight(s);
    for (std::size_t i = 0; i < body.particle_count(); ++i) body.v_sum.add(i, body.v_stage[i] * weight);
}

void rk4_finish(SoftBody& body, float h) {
    const Vec3Array* a = body.accel;
    for (std::size_t i = 0; i < body.particle_count(); ++i) {
        body.x.add(i, body.v_sum[i] * (h / 6.0f));
        body.v.add(i, (a[0][i] + 2.0f * a[1][i] + 2.0f * a[2][i] + a[3][i]) * (h / 6.0f));
    }
}

void hold_pins(SoftBody& body) {
    for (std::size_t i = 0; i < body.particle_count(); ++i) {
        if (body.inv_mass[i] == 0.0f) body.v.set(i, {});
    }
}

// ---------------------------------------------------------------------------------------------
// Rigid bodies: Listing 10's flat array
// ---------------------------------------------------------------------------------------------
void rigid_derivative(const RigidBody& body, const double* y, const Vec3d& F, const Vec3d& tau, double* dy) {
    for (int k = 0; k < rigid::kStateSize; ++k) dy[k] = 0.0;
    if (body.fixed) return;
    const RigidMotion m = rigid_motion(body, y);
    const Quat dq = Quat::pure(m.omega) * m.q * 0.5;  // Eq. 35: dq/dt = 1/2 w q
    for (int k = 0; k < 3; ++k) {
        dy[rigid::P + k] = F[k];      // dP/dt = F_net
        dy[rigid::X + k] = m.v[k];    // dx/dt = P / m
        dy[rigid::L + k] = tau[k];    // dL/dt = tau_net (Eq. 26)
    }
    dy[rigid::Q] = dq.w;
    dy[rigid::Q + 1] = dq.x;
    dy[rigid::Q + 2] = dq.y;
    dy[rigid::Q + 3] = dq.z;
}

void rigid_momentum_derivative(const RigidBody& body, const Vec3d& F, const Vec3d& tau, double* dy) {
    for (int k = 0; k < rigid::kStateSize; ++k) dy[k] = 0.0;
    if (body.fixed) return;
    for (int k = 0; k < 3; ++k) {
        dy[rigid::P + k] = F[k];
        dy[rigid::L + k] = tau[k];
    }
}

namespace {
bool is_momentum_slot(std::size_t k) {
    const std::size_t slot = k % rigid::kStateSize;
    return slot < rigid::X || (slot >= rigid::L && slot < rigid::Q);
}
}  // namespace

void flat_euler(std::span<double> y, std::span<const double> dy, double h) {
    for (std::size_t k = 0; k < y.size(); ++k) y[k] += h * dy[k];
}

void flat_euler_momenta(std::span<double> y, std::span<const double> dy, double h) {
    for (std::size_t k = 0; k < y.size(); ++k) {
        if (is_momentum_slot(k)) y[k] += h * dy[k];
    }
}

void symplectic_positions(std::span<const RigidBody> bodies, std::span<const double> start, std::span<double> y, double h,
                          std::span<const std::uint8_t> asleep, ThreadPool* pool) {
    // Each body on its own: on every thread, in chunks of bodies (the same bits at any count).
    for_chunks(pool, bodies.size(), 64, [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t b = begin; b < end; ++b) {
            const RigidBody& body = bodies[b];
            if (body.fixed || (!asleep.empty() && asleep[b])) continue;
            const std::size_t at = b * rigid::kStateSize;
            const Vec3d P{y[at + rigid::P], y[at + rigid::P + 1], y[at + rigid::P + 2]};
            const Vec3d L{y[at + rigid::L], y[at + rigid::L + 1], y[at + rigid::L + 2]};
            for (int k = 0; k < 3; ++k) y[at + std::size_t(rigid::X + k)] = start[at + std::size_t(rigid::X + k)] + h * P[k] * body.inv_mass;
            const Quat q1 = free_turn(body, Quat{start[at + rigid::Q], start[at + rigid::Q + 1], start[at + rigid::Q + 2],
                                                 start[at + rigid::Q + 3]},
                                      L, h);
            y[at + rigid::Q] = q1.w;
            y[at + rigid::Q + 1] = q1.x;
            y[at + rigid::Q + 2] = q1.y;
            y[at + rigid::Q + 3] = q1.z;
        }
    });
}

namespace {

// The principal axes as columns, made right-handed (an eigen-solver may return a reflection):
// turning the body about its own axis e_k is then turning the momentum pi = E^T R^T L about the
// k-th coordinate axis the other way.
Mat3 right_handed_axes(const RigidBody& body) {
    Mat3 E = body.principal_axes;
    const Vec3d e0{E.m[0][0], E.m[1][0], E.m[2][0]}, e1{E.m[0][1], E.m[1][1], E.m[2][1]}, e2{E.m[0][2], E.m[1][2], E.m[2][2]};
    if (dot(cross(e0, e1), e2) < 0.0) {
        for (int r = 0; r < 3; ++r) E.m[r][2] = -E.m[r][2];
    }
    return E;
}

// The body's angular momentum in its principal axes, pi = E^T R^T L (R of q made unit).
Vec3d principal_momentum(const Mat3& E, const Quat& q, const Vec3d& L) {
    return E.transposed() * (q.normalized().to_matrix().transposed() * L);
}

// True when the three principal moments are one (a ball, a cube): every axis is principal, and
// the free body turns steadily about L.
bool isotropic(const Vec3d& I) {
    const double most = std::max({I.x, I.y, I.z}), least = std::min({I.x, I.y, I.z});
    return least > 0.0 && most - least <= 1e-12 * most;
}

// match_energy on a momentum already in principal axes (E right-handed).
Quat match_principal_energy(const RigidBody& body, const Mat3& E, const Quat& q0, const Vec3d& pi, double E0) {
    // In the body's principal axes its angular momentum pi = R^T L has |pi| = |L| and energy
    // sum pi_i^2 / 2 I_i. The pi' nearest pi with the same |pi| and energy E0, on the curve where
    // the sphere meets the ellipsoid (where the true motion runs), is pi_i / (1 + m1 + m2 / I_i)
    // for the two multipliers m1, m2 that meet both, found by Newton's method; the body is then
    // turned by the least rotation taking pi to pi' in its own axes.
    const Vec3d& I = body.principal_moments;
    if (!(I.x > 0.0 && I.y > 0.0 && I.z > 0.0) || !(E0 > 0.0)) return q0;
    const double pi2[3] = {pi.x * pi.x, pi.y * pi.y, pi.z * pi.z}, inv_I[3] = {1.0 / I.x, 1.0 / I.y, 1.0 / I.z};
    const double size2 = pi2[0] + pi2[1] + pi2[2];
    // No energy other than E0 within reach: L^2 / 2 I_max <= E0 <= L^2 / 2 I_min.
    if (!(E0 >= 0.5 * size2 * std::min({inv_I[0], inv_I[1], inv_I[2]}) && E0 <= 0.5 * size2 * std::max({inv_I[0], inv_I[1], inv_I[2]}))) {
        return q0;
    }
    double m1 = 0.0, m2 = 0.0;
    for (int iteration = 0; iteration < 30; ++iteration) {
        double f1 = -size2, f2 = -2.0 * E0, d11 = 0.0, d12 = 0.0, d22 = 0.0;
        bool valid = true;
        for (int i = 0; i < 3; ++i) {
            const double d = 1.0 + m1 + m2 * inv_I[i];
            valid = valid && d > 0.0;
            const double c = pi2[i] / (d * d), dc = -2.0 * c / d;  // d(c)/d(d)
            f1 += c;
            f2 += c * inv_I[i];
            d11 += dc;
            d12 += dc * inv_I[i];
            d22 += dc * inv_I[i] * inv_I[i];
        }
        if (!valid) return q0;
        if (std::abs(f1) <= 1e-15 * size2 && std::abs(f2) <= 1e-15 * E0) break;
        const double det = d11 * d22 - d12 * d12;
        if (!(std::abs(det) > 0.0)) return q0;
        m1 -= (f1 * d22 - f2 * d12) / det;
        m2 -= (d11 * f2 - d12 * f1) / det;
    }
    const Vec3d target{pi.x / (1.0 + m1 + m2 * inv_I[0]), pi.y / (1.0 + m1 + m2 * inv_I[1]), pi.z / (1.0 + m1 + m2 * inv_I[2])};
    // R'^T L = pi' for R' = R B with B pi' = pi: B turns pi' onto pi, about pi' x pi (principal
    // axes). The least turn that does it, as a quaternion without an angle (no sine or
    // arctangent: the same bits everywhere, portable_math.h): (|a||b| + a . b, a x b),
    // normalised, turns a onto b. A turn in the body's own axes multiplies q on the right.
    const Vec3d axis = cross(target, pi);
    if (!(length(axis) > 0.0)) return q0;
    const double w = length(target) * length(pi) + dot(target, pi);
    const Vec3d axis_body = E * axis;
    return q0 * Quat{w, axis_body.x, axis_body.y, axis_body.z}.normalized();
}

}  // namespace

Quat free_turn(const RigidBody& body, const Quat& q0, const Vec3d& L, double h, double energy_target) {
    const Vec3d& I = body.principal_moments;
    // A ball or a cube: w = L / I stays as it is, and the exact turn is one turn about L.
    if (isotropic(I)) {
        const double size = length(L);
        if (!(size > 0.0)) return q0;
        return Quat::from_axis_angle(L / size, h * size / I.x) * q0;
    }
    // About principal axis k for time t: the body turns by t pi_k / I_k about its own axis e_k,
    // which the turn leaves where it is (an exact rotation; Eq. 35 with w = J_world^-1 L
    // restricted to that axis's share of the energy). In the body's own axes the turn multiplies
    // q on the right, and turns the momentum the body sees, pi, the other way about that axis.
    const Mat3 E = right_handed_axes(body);
    Vec3d pi = principal_momentum(E, q0, L);
    const auto energy = [&](const Vec3d& p) { return 0.5 * (p.x * p.x / I.x + p.y * p.y / I.y + p.z * p.z / I.z); };
    const double E0 = energy_target >= 0.0 ? energy_target : energy(pi);
    Quat q = q0;
    const auto turn_about = [&](int k, double t) {
        if (!(I[k] > 0.0)) return;
        const double angle = t * pi[k] / I[k];
        if (angle == 0.0) return;
        double s = 0.0, c = 0.0;
        portable::sin_cos(0.5 * angle, s, c);
        const Vec3d e = Vec3d{E.m[0][k], E.m[1][k], E.m[2][k]} * s;
        q = q * Quat{c, e.x, e.y, e.z};
        // pi' = Rot_k(angle)^T pi, with sin and cos of the whole angle from the half angle's.
        const double sa = 2.0 * s * c, ca = c * c - s * s;
        const int i = (k + 1) % 3, j = (k + 2) % 3;
        const double pi_i = pi[i], pi_j = pi[j];
        pi[i] = ca * pi_i + sa * pi_j;
        pi[j] = ca * pi_j - sa * pi_i;
    };
    // Largest moment outside, smallest (the fastest turn) once in the middle.
    turn_about(2, 0.5 * h);
    turn_about(1, 0.5 * h);
    turn_about(0, h);
    turn_about(1, 0.5 * h);
    turn_about(2, 0.5 * h);
    // The splitting keeps |L| exactly and the energy to O(h^2), wandering about its value; a
    // free body keeps both: brought back (match_principal_energy), a tumbling body's energy never
    // rises, under any spin.
    return match_principal_energy(body, E, q, pi, E0);
}

Quat match_energy(const RigidBody& body, const Quat& q0, const Vec3d& L, double E0) {
    const Mat3 E = right_handed_axes(body);
    return match_principal_energy(body, E, q0, principal_momentum(E, q0, L), E0);
}

void flat_rk4_stage(std::span<const double> y, std::span<const double> k, double w, std::span<double> stage) {
    for (std::size_t i = 0; i < y.size(); ++i) stage[i] = y[i] + w * k[i];
}

void flat_rk4_finish(std::span<double> y, std::span<const double> k0, std::span<const double> k1,
                     std::span<const double> k2, std::span<const double> k3, double h) {
    for (std::size_t i = 0; i < y.size(); ++i) y[i] += h / 6.0 * (k0[i] + 2.0 * k1[i] + 2.0 * k2[i] + k3[i]);
}

double rk4_stage_offset(int s, double h) { return s < 3 ? 0.5 * h : h; }

}  // namespace softbody

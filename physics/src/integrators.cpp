#include "integrators.h"

#include <algorithm>
#include <cmath>

namespace softbody {

namespace {

void copy(const Vec3Array& from, Vec3Array& to) {
    to.x = from.x;
    to.y = from.y;
    to.z = from.z;
}

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
    copy(body.v, body.v_stage);
    copy(body.v, body.v_sum);
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

void symplectic_positions(std::span<const RigidBody> bodies, std::span<const double> start, std::span<double> y, double h) {
    for (std::size_t b = 0; b < bodies.size(); ++b) {
        const RigidBody& body = bodies[b];
        if (body.fixed) continue;
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
}

Quat free_turn(const RigidBody& body, const Quat& q0, const Vec3d& L, double h, double energy_target) {
    // About principal axis k for time t: the body turns by t (a . L) / I_k about a = R e_k,
    // its own axis, which the turn leaves where it is (an exact rotation; Eq. 35 with
    // w = J_world^-1 L restricted to that axis's share of the energy).
    Quat q = q0;
    const auto turn_about = [&](int k, double t) {
        const double I = body.principal_moments[k];
        if (!(I > 0.0)) return;
        const Mat3 R = q.normalized().to_matrix();
        const Vec3d e{body.principal_axes.m[0][k], body.principal_axes.m[1][k], body.principal_axes.m[2][k]};
        const Vec3d a = normalize(R * e);
        const double angle = t * dot(a, L) / I;
        if (angle != 0.0) q = Quat::from_axis_angle(a, angle) * q;
    };
    // The energy 1/2 L . J_world^-1 L of an orientation, from the body-axes angular momentum
    // pi = R^T L in principal axes.
    const auto body_momentum = [&](const Quat& orientation) {
        const Vec3d b = orientation.normalized().to_matrix().transposed() * L;
        return body.principal_axes.transposed() * b;
    };
    const Vec3d& I = body.principal_moments;
    const auto energy = [&](const Vec3d& pi) { return 0.5 * (pi.x * pi.x / I.x + pi.y * pi.y / I.y + pi.z * pi.z / I.z); };
    const double E0 = energy_target >= 0.0 ? energy_target : energy(body_momentum(q0));
    // Largest moment outside, smallest (the fastest turn) once in the middle.
    turn_about(2, 0.5 * h);
    turn_about(1, 0.5 * h);
    turn_about(0, h);
    turn_about(1, 0.5 * h);
    turn_about(2, 0.5 * h);
    // The splitting keeps |L| exactly and the energy to O(h^2), wandering about its value; a
    // free body keeps both: brought back (match_energy), a tumbling body's energy never rises,
    // under any spin.
    return match_energy(body, q, L, E0);
}

Quat match_energy(const RigidBody& body, const Quat& q0, const Vec3d& L, double E0) {
    // The energy is brought to E0 by turning the body a little further about the axis
    // pi x (J^-1 pi) (in its own axes: the direction in which the energy changes fastest with
    // |pi| fixed), found by Newton's method: the turn ends on the intersection of the momentum
    // sphere and the energy ellipsoid, where the true motion is.
    const Vec3d& I = body.principal_moments;
    if (!(I.x > 0.0 && I.y > 0.0 && I.z > 0.0) || !(E0 >= 0.0)) return q0;
    const auto body_momentum = [&](const Quat& orientation) {
        return body.principal_axes.transposed() * (orientation.normalized().to_matrix().transposed() * L);
    };
    const auto energy = [&](const Vec3d& pi) { return 0.5 * (pi.x * pi.x / I.x + pi.y * pi.y / I.y + pi.z * pi.z / I.z); };
    Quat q = q0;
    for (int iteration = 0; iteration < 3; ++iteration) {
        const Vec3d pi = body_momentum(q);
        const Vec3d grad{pi.x / I.x, pi.y / I.y, pi.z / I.z};
        const Vec3d axis_principal = cross(pi, grad);
        const double E = energy(pi), size = length(axis_principal);
        if (!(size > 0.0) || std::abs(E - E0) <= 1e-15 * E0) break;
        // Turning the body by theta about body axis a changes pi by -theta a x pi, and E by
        // -theta (a x pi) . grad = -theta a . (pi x grad): the rate along a = axis / size is -size.
        const double theta = (E - E0) / size;
        const Vec3d axis_body = body.principal_axes * (axis_principal / size);
        q = Quat::from_axis_angle(q.normalized().to_matrix() * axis_body, theta) * q;
    }
    return q;
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

#include "physics/pair_forces.h"

#include <cmath>

namespace softbody {

// ---------------------------------------------------------------------------------------------
// Reference: Listing 8's CalcForce, with each unordered pair visited once and its force applied
// to both ends (Newton's third law), as written in the book.
// ---------------------------------------------------------------------------------------------
void pair_forces_reference(const PairInput& in, Vec3Array& f) {
    f.resize(in.n);
    for (std::size_t i = 0; i < in.n; ++i) {
        const Vec3 x_i{in.x[i], in.y[i], in.z[i]};
        const Vec3 v_i{in.vx[i], in.vy[i], in.vz[i]};
        const Vec3 r_i{in.rx[i], in.ry[i], in.rz[i]};
        for (std::size_t j = i + 1; j < in.n; ++j) {
            const Vec3 d = Vec3{in.x[j], in.y[j], in.z[j]} - x_i;
            const float l = length(d);
            if (l == 0.0f) continue;  // coincident particles: no direction, no force
            const Vec3 d_hat = d / l;
            const float l0 = length(Vec3{in.rx[j], in.ry[j], in.rz[j]} - r_i);  // rest length

            // Eq. 21 (Hooke): stretched (l > l0) pulls i toward j, compressed pushes it away.
            const Vec3 F_spring = in.k * (l - l0) * d_hat;
            // Eq. 22 (dashpot): resists the relative velocity along the spring axis only.
            const Vec3 v_rel = Vec3{in.vx[j], in.vy[j], in.vz[j]} - v_i;
            const Vec3 F_damp = in.c * dot(v_rel, d_hat) * d_hat;

            f.add(i, F_spring + F_damp);   // on i
            f.add(j, -(F_spring + F_damp));  // equal and opposite on j
        }
    }
}

double elastic_energy_reference(const PairInput& in) {
    double energy = 0.0;
    for (std::size_t i = 0; i < in.n; ++i) {
        for (std::size_t j = i + 1; j < in.n; ++j) {
            const float l = length(Vec3{in.x[j] - in.x[i], in.y[j] - in.y[i], in.z[j] - in.z[i]});
            const float l0 = length(Vec3{in.rx[j] - in.rx[i], in.ry[j] - in.ry[i], in.rz[j] - in.rz[i]});
            energy += 0.5 * in.k * double(l - l0) * double(l - l0);
        }
    }
    return energy;
}

// ---------------------------------------------------------------------------------------------
// Fast kernel: the triangle of pairs (i < j) is cut into square tiles of kBlock x kBlock.
// Each tile writes its partial forces into a buffer of its own; each block's total is then the
// sum of its tiles' partials in a fixed order. Threads only choose which tile to do next, so
// the sums, and the bits of the result, are the same for any number of threads.
// ---------------------------------------------------------------------------------------------
namespace {

constexpr std::size_t B = PairForceKernel::kBlock;

// Pairs (i, j) with i in [i0, i1), j in [j0, j1), and j > i on a diagonal tile. Adds the force
// on i to out_i[axis * B + (i - i0)] and the force on j to out_j[axis * B + (j - j0)].
// The force on i is s d with d = x_j - x_i and, from Eq. 21 and Eq. 22 over d_hat = d / l,
//     s = k (l - l0) / l + c ((v_j - v_i) . d) / l^2.
void tile_scalar(const PairInput& in, std::size_t i0, std::size_t i1, std::size_t j0, std::size_t j1, bool diagonal,
                 float* out_i, float* out_j) {
    for (std::size_t i = i0; i < i1; ++i) {
        const float xi = in.x[i], yi = in.y[i], zi = in.z[i];
        const float vxi = in.vx[i], vyi = in.vy[i], vzi = in.vz[i];
        const float rxi = in.rx[i], ryi = in.ry[i], rzi = in.rz[i];
        float fx = 0.0f, fy = 0.0f, fz = 0.0f;
        for (std::size_t j = diagonal ? i + 1 : j0; j < j1; ++j) {
            const float dx = in.x[j] - xi, dy = in.y[j] - yi, dz = in.z[j] - zi;
            const float l2 = dx * dx + dy * dy + dz * dz;
            if (l2 == 0.0f) continue;
            const float inv_l = 1.0f / std::sqrt(l2);
            const float l = l2 * inv_l;
            const float ex = in.rx[j] - rxi, ey = in.ry[j] - ryi, ez = in.rz[j] - rzi;
            const float l0 = std::sqrt(ex * ex + ey * ey + ez * ez);
            const float dv_d = (in.vx[j] - vxi) * dx + (in.vy[j] - vyi) * dy + (in.vz[j] - vzi) * dz;
            const float s = (in.k * (l - l0) + in.c * dv_d * inv_l) * inv_l;
            fx += s * dx;
            fy += s * dy;
            fz += s * dz;
            out_j[j - j0] -= s * dx;
            out_j[B + j - j0] -= s * dy;
            out_j[2 * B + j - j0] -= s * dz;
        }
        out_i[i - i0] += fx;
        out_i[B + i - i0] += fy;
        out_i[2 * B + i - i0] += fz;
    }
}

double tile_energy(const PairInput& in, std::size_t i0, std::size_t i1, std::size_t j0, std::size_t j1, bool diagonal) {
    double energy = 0.0;
    for (std::size_t i = i0; i < i1; ++i) {
        for (std::size_t j = diagonal ? i + 1 : j0; j < j1; ++j) {
            const float dx = in.x[j] - in.x[i], dy = in.y[j] - in.y[i], dz = in.z[j] - in.z[i];
            const float ex = in.rx[j] - in.rx[i], ey = in.ry[j] - in.ry[i], ez = in.rz[j] - in.rz[i];
            const double stretch = double(std::sqrt(dx * dx + dy * dy + dz * dz)) - std::sqrt(ex * ex + ey * ey + ez * ez);
            energy += stretch * stretch;
        }
    }
    return 0.5 * in.k * energy;
}

}  // namespace

const char* PairForceKernel::variant() { return "scalar"; }

void PairForceKernel::prepare(std::size_t n) {
    if (n == n_ && !tile_i_.empty()) return;
    n_ = n;
    blocks_ = (n + B - 1) / B;
    tile_i_.clear();
    tile_j_.clear();
    for (std::size_t I = 0; I < blocks_; ++I) {
        for (std::size_t J = I; J < blocks_; ++J) {
            tile_i_.push_back(I);
            tile_j_.push_back(J);
        }
    }
    partial_.assign(tile_i_.size() * 6 * B, 0.0f);
    partial_energy_.assign(tile_i_.size(), 0.0);
}

void PairForceKernel::compute(const PairInput& in, Vec3Array& f) {
    f.resize(in.n);
    if (in.n < 2) return;
    prepare(in.n);
    pool_.run(tile_i_.size(), [&](std::size_t t) {
        float* out = partial_.data() + t * 6 * B;
        std::fill(out, out + 6 * B, 0.0f);
        const std::size_t I = tile_i_[t], J = tile_j_[t];
        const std::size_t i0 = I * B, i1 = std::min(i0 + B, in.n);
        const std::size_t j0 = J * B, j1 = std::min(j0 + B, in.n);
        tile_scalar(in, i0, i1, j0, j1, I == J, out, I == J ? out : out + 3 * B);
    });
    // Block b's total: its tiles (min(b,J), max(b,J)) for J = 0, 1, ... in that order.
    pool_.run(blocks_, [&](std::size_t b) {
        const std::size_t p0 = b * B, p1 = std::min(p0 + B, in.n);
        for (std::size_t J = 0; J < blocks_; ++J) {
            const std::size_t I = std::min(b, J), K = std::max(b, J);
            // index of tile (I, K) in the order prepare() lists them: row I holds blocks_ - I tiles
            const std::size_t tile = I * (2 * blocks_ - I + 1) / 2 + (K - I);
            const float* part = partial_.data() + tile * 6 * B + (b == I ? 0 : 3 * B);
            for (std::size_t p = p0; p < p1; ++p) {
                f.x[p] += part[p - p0];
                f.y[p] += part[B + p - p0];
                f.z[p] += part[2 * B + p - p0];
            }
        }
    });
}

double PairForceKernel::elastic_energy(const PairInput& in) {
    if (in.n < 2 || in.k == 0.0f) return 0.0;
    prepare(in.n);
    pool_.run(tile_i_.size(), [&](std::size_t t) {
        const std::size_t I = tile_i_[t], J = tile_j_[t];
        const std::size_t i0 = I * B, i1 = std::min(i0 + B, in.n);
        const std::size_t j0 = J * B, j1 = std::min(j0 + B, in.n);
        partial_energy_[t] = tile_energy(in, i0, i1, j0, j1, I == J);
    });
    double energy = 0.0;
    for (double e : partial_energy_) energy += e;
    return energy;
}

}  // namespace softbody

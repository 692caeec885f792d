#include "block_solver.h"

#include <algorithm>
#include <cmath>

namespace softbody {

namespace {

// A symmetric positive definite matrix of at most 4 x 4 as L D L^T: L unit lower triangular
// (its entries below the diagonal, row by row: L_rc at below(r, c)) and D's reciprocals.
// Solving with it takes two triangular solves.
struct BlockFactor {
    static constexpr int below(int r, int c) { return r * (r - 1) / 2 + c; }
    double L[6] = {};
    double inv_d[4] = {};
};

// Factors the symmetric positive definite M x M matrix A as L D L^T (L unit lower triangular,
// below its diagonal in `f`, and 1 / D): false when a pivot is not positive. M known when
// compiled, so that the loops unroll.
template <int M>
bool factor(const double (&A)[4][4], BlockFactor& f) {
    double d[4];
    for (int r = 0; r < M; ++r) {
        for (int c = 0; c <= r; ++c) {
            double sum = A[r][c];
            for (int k = 0; k < c; ++k) sum -= f.L[BlockFactor::below(r, k)] * f.L[BlockFactor::below(c, k)] * d[k];
            if (r == c) {
                if (!(sum > 0.0)) return false;
                d[r] = sum;
                f.inv_d[r] = 1.0 / sum;
            } else {
                f.L[BlockFactor::below(r, c)] = sum * f.inv_d[c];
            }
        }
    }
    return true;
}

// y = A^-1 c through A's factors: two triangular solves.
template <int M>
void solve_factored(const BlockFactor& f, const double (&c)[4], double (&y)[4]) {
    for (int r = 0; r < M; ++r) {
        double sum = c[r];
        for (int k = 0; k < r; ++k) sum -= f.L[BlockFactor::below(r, k)] * y[k];
        y[r] = sum;
    }
    for (int r = M - 1; r >= 0; --r) {
        double sum = y[r] * f.inv_d[r];
        for (int k = r + 1; k < M; ++k) sum -= f.L[BlockFactor::below(k, r)] * y[k];
        y[r] = sum;
    }
}

// Solves K_SS x_S = b_S for the M points in `index`, with 1e-9 of the diagonal added when there
// are two or more (three collinear corners leave it singular). False when singular all the same.
template <int M>
bool solve_points(const int (&index)[4], const double (&K)[4][4], const double (&b)[4], double (&x)[4]) {
    double A[4][4], c[4], y[4];
    for (int r = 0; r < M; ++r) {
        for (int k = 0; k <= r; ++k) A[r][k] = K[index[r]][index[k]];
        if (M > 1) A[r][r] *= 1.0 + 1e-9;
        c[r] = b[index[r]];
    }
    BlockFactor f;
    if (!factor<M>(A, f)) return false;
    solve_factored<M>(f, c, y);
    for (int r = 0; r < M; ++r) x[index[r]] = y[r];
    return true;
}

// Solves K_SS x_S = b_S for the points in `set` (at most four); x is 0 for the others.
bool solve_set(int n, unsigned set, const double (&K)[4][4], const double (&b)[4], double (&x)[4]) {
    int index[4], m = 0;
    for (int i = 0; i < n; ++i) {
        if (set & (1u << i)) index[m++] = i;
    }
    for (int i = 0; i < n; ++i) x[i] = 0.0;
    switch (m) {
        case 1: return solve_points<1>(index, K, b, x);
        case 2: return solve_points<2>(index, K, b, x);
        case 3: return solve_points<3>(index, K, b, x);
        case 4: return solve_points<4>(index, K, b, x);
        default: return m == 0;
    }
}

// For n points, the sets of them (bit i: point i) in the order they are tried: the most points
// first, and among sets of one size the larger bit pattern first. 0 ends a list.
constexpr unsigned kSetsBySize[5][16] = {
    {0},
    {1, 0},
    {3, 2, 1, 0},
    {7, 6, 5, 3, 4, 2, 1, 0},
    {15, 14, 13, 11, 7, 12, 10, 9, 6, 5, 3, 8, 4, 2, 1, 0},
};

// A's inverse into `block` (its lower triangle) when A factors; false when it does not.
template <int M>
bool factor_and_invert(const double (&A)[4][4], BlockSolve& block) {
    BlockFactor f;
    if (!factor<M>(A, f)) return false;
    for (int c = 0; c < M; ++c) {
        double e[4] = {0.0, 0.0, 0.0, 0.0}, column[4];
        e[c] = 1.0;
        solve_factored<M>(f, e, column);
        for (int r = c; r < M; ++r) block.inverse[BlockSolve::lower(r, c)] = column[r];
    }
    return true;
}

}  // namespace

void prepare_block(int n, const double (&K)[4][4], const double (&q)[4][2], BlockSolve& block) {
    // What solves K for all points at once. Four corners on a plane: their normal velocities
    // depend on the bodies' motion only through v_n + (w_a - w_b) . (p x n), an affine function
    // of the point in the plane, so K has rank 3 and z, the affine dependency of the four
    // (sum z_i = 0, sum z_i q_i = 0 for their coordinates q_i in the plane), spans its null space.
    double A4[4][4];
    for (int x = 0; x < n; ++x)
        for (int y = 0; y < n; ++y) A4[x][y] = K[x][y];
    block.singular = false;
    block.last_set = 0;
    if (n == 4) {
        const auto det3 = [&](int a, int b, int c) {
            return (q[b][0] - q[a][0]) * (q[c][1] - q[a][1]) - (q[c][0] - q[a][0]) * (q[b][1] - q[a][1]);
        };
        const double z[4] = {det3(1, 2, 3), -det3(0, 2, 3), det3(0, 1, 3), -det3(0, 1, 2)};
        const double size = std::sqrt(z[0] * z[0] + z[1] * z[1] + z[2] * z[2] + z[3] * z[3]);
        double extent = 0.0;
        for (int x = 0; x < 4; ++x) extent = std::max(extent, q[x][0] * q[x][0] + q[x][1] * q[x][1]);
        if (size > 1e-9 * extent) {
            block.singular = true;
            const double fill = (K[0][0] + K[1][1] + K[2][2] + K[3][3]) / 4.0;
            for (int x = 0; x < 4; ++x) block.z[x] = z[x] / size;
            for (int x = 0; x < 4; ++x)
                for (int y = 0; y < 4; ++y) A4[x][y] += fill * block.z[x] * block.z[y];
        }
    }
    if (!block.singular && n > 1) {
        for (int x = 0; x < n; ++x) A4[x][x] *= 1.0 + 1e-9;  // three corners on a line
    }
    switch (n) {
        case 1: block.factored = factor_and_invert<1>(A4, block); break;
        case 2: block.factored = factor_and_invert<2>(A4, block); break;
        case 3: block.factored = factor_and_invert<3>(A4, block); break;
        case 4: block.factored = factor_and_invert<4>(A4, block); break;
        default: block.factored = false; break;
    }
}

namespace {

// All N points pushing, through the inverse prepared for the tick: x and true when that fits
// (solve_block). N known when compiled, so that the loops unroll: the same operations in the
// same order as for any n.
template <int N>
bool solve_all(const BlockSolve& block, const double (&K)[4][4], const double (&b)[4], double (&x)[4]) {
    double c[4] = {b[0], b[1], b[2], b[3]};
    if (block.singular) {
        double along = 0.0;
        for (int i = 0; i < N; ++i) along += c[i] * block.z[i];
        for (int i = 0; i < N; ++i) c[i] -= along * block.z[i];
    }
    double y[4];
    for (int i = 0; i < N; ++i) {
        double sum = 0.0;
        for (int j = 0; j < N; ++j) sum += block.inverse[BlockSolve::lower(i, j)] * c[j];
        y[i] = sum;
    }
    // Rounding at the edge of the set: an impulse a hair below zero is zero. With four
    // corners the answer is the least-squares one: where the targets are not those of one
    // motion of the face (corners at different gaps closing as far as each may), some
    // corner would be left short of its target, and a set of three is the answer instead.
    double largest = 0.0, scale = 0.0;
    for (int i = 0; i < N; ++i) {
        largest = std::max(largest, y[i]);
        scale = std::max(scale, std::abs(b[i]));
    }
    bool fits_all = true;
    for (int i = 0; i < N; ++i) {
        double w = -b[i];
        for (int j = 0; j < N; ++j) w += K[i][j] * std::max(y[j], 0.0);
        fits_all = fits_all && y[i] >= -1e-12 * largest && std::abs(w) <= 1e-6 * scale + 1e-12;
    }
    if (!fits_all) return false;
    for (int i = 0; i < N; ++i) x[i] = std::max(y[i], 0.0);
    return true;
}

}  // namespace

// The normal impulses x >= 0 of a manifold's n <= 4 points acting together. K is their
// coupling; (K x)_i - b_i is point i's normal velocity above its target with impulses x, and it
// must be zero where the point pushes (x_i > 0) and may be more where it does not (x_i = 0): a
// linear complementarity problem, solved exactly by trying the sets of pushing points, all of
// them first (through K's inverse, prepared once a tick), then smaller sets, the first whose
// impulses all push and whose other points do not close. Four corners on a plane leave K
// singular (three would hold the face: statically indeterminate): of the answers, the one with
// the least impulses is taken (b's part along the null direction z removed, and z filled in
// before K was factored), which shares the load evenly and changes smoothly as the bodies move.
void solve_block(BlockSolve& block, int n, const double (&K)[4][4], const double (&b)[4], double (&x)[4],
                 bool all_points) {
    const auto fits = [&](unsigned set, const double (&y)[4]) {
        for (int i = 0; i < n; ++i) {
            if (set & (1u << i)) {
                if (y[i] < 0.0) return false;
            } else {
                double w = -b[i];
                for (int j = 0; j < n; ++j) w += K[i][j] * y[j];
                if (w < -1e-9 * (std::abs(b[i]) + 1e-9)) return false;
            }
        }
        return true;
    };
    const unsigned full = (1u << n) - 1u;
    if (all_points && block.factored) {
        bool fits_all = false;
        switch (n) {
            case 1: fits_all = solve_all<1>(block, K, b, x); break;
            case 2: fits_all = solve_all<2>(block, K, b, x); break;
            case 3: fits_all = solve_all<3>(block, K, b, x); break;
            case 4: fits_all = solve_all<4>(block, K, b, x); break;
            default: break;
        }
        if (fits_all) return;
    }
    // No point pushes (all come apart): the commonest other answer.
    bool apart = true;
    for (int i = 0; i < n; ++i) apart = apart && b[i] <= 0.0;
    if (apart) {
        for (int i = 0; i < n; ++i) x[i] = 0.0;
        return;
    }
    // The set that pushed last time, first: from one pass to the next a manifold's contacts
    // change little, and that set mostly fits again (the search below tries 3.4 sets on
    // average in a resting stack of cubes). Where K is regular only one set fits, so which is
    // tried first does not change the answer.
    const unsigned last = all_points ? block.last_set : 0u;
    if (last != 0) {
        double y[4];
        if (solve_set(n, last, K, b, y) && fits(last, y)) {
            for (int i = 0; i < n; ++i) x[i] = y[i];
            return;
        }
    }
    // Smaller sets, largest first (the full set again when it was not tried above); of one
    // size, the larger bit pattern first.
    for (const unsigned* set_at = kSetsBySize[n]; *set_at != 0; ++set_at) {
        const unsigned set = *set_at;
        if ((all_points && set == full) || set == last) continue;
        double y[4];
        if (solve_set(n, set, K, b, y) && fits(set, y)) {
            for (int i = 0; i < n; ++i) x[i] = y[i];
            if (all_points) block.last_set = set;
            return;
        }
    }
    for (int i = 0; i < n; ++i) x[i] = 0.0;  // none: every point lets go
}


}  // namespace softbody

// Internal to the physics library: the normal impulses of one manifold's points (at most four)
// acting together, the contact solver's block solve (contact_solver.h). Each point's impulse
// changes every point's normal velocity through the coupling K (K_ij: point i's change per unit
// impulse at point j); the impulses must be zero or push, and where they push the point must
// reach its target: a small linear complementarity problem, solved exactly here.
#pragma once

namespace softbody {

// A symmetric positive definite matrix of at most 4 x 4 as L D L^T: L unit lower triangular
// (its entries below the diagonal, row by row: L_rc at below(r, c)) and D's reciprocals.
// Solving with it takes two triangular solves.
struct BlockFactor {
    static constexpr int below(int r, int c) { return r * (r - 1) / 2 + c; }
    double L[6] = {};
    double inv_d[4] = {};
};

// What solves K for all points pushing at once, prepared once a tick (prepare_block): K's
// factors, or, for four corners on a plane (K singular: three would hold the face), those of K
// with the null direction z filled in, and z itself (`factored`: false when K could not be
// factored, and then the sets are searched); and the smaller set of points that pushed the
// last time all of them were solved for (0: none yet), tried first the next time.
struct BlockSolve {
    BlockFactor factor;
    double z[4] = {};
    bool singular = false;
    bool factored = false;
    unsigned last_set = 0;
};

// From K of n points and their coordinates q in the contact plane (from any one of them).
void prepare_block(int n, const double (&K)[4][4], const double (&q)[4][2], BlockSolve& block);

// The impulses x >= 0 of n points with coupling K whose normal velocities must rise by b
// where they push ((K x)_i - b_i is point i's normal velocity above its target: zero where
// x_i > 0, at least zero where x_i = 0). `all_points`: K is the one `block` was prepared from,
// so the set of all points is tried first through it, then the set that pushed last time; then
// smaller sets, largest first.
void solve_block(BlockSolve& block, int n, const double (&K)[4][4], const double (&b)[4], double (&x)[4],
                 bool all_points);

}  // namespace softbody

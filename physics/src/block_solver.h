// Internal to the physics library: the normal impulses of one manifold's points (at most four)
// acting together, the contact solver's block solve (contact_solver.h). Each point's impulse
// changes every point's normal velocity through the coupling K (K_ij: point i's change per unit
// impulse at point j); the impulses must be zero or push, and where they push the point must
// reach its target: a small linear complementarity problem, solved exactly here.
#pragma once

namespace softbody {

// What solves K for all points pushing at once, prepared once a tick (prepare_block): K's
// inverse, or, for four corners on a plane (K singular: three would hold the face), that of K
// with the null direction z filled in, and z itself (`factored`: false when K could not be
// factored, and then the sets are searched); and the smaller set of points that pushed the
// last time all of them were solved for (0: none yet), tried first the next time.
// The inverse is made from K's L D L^T factors, and kept (it is symmetric) as its lower
// triangle, row by row: (r, c) at lower(r, c). A visit multiplies by it: four sums side by side,
// where the factors' two triangular solves are a chain of steps each waiting for the last.
struct BlockSolve {
    static constexpr int lower(int r, int c) { return r >= c ? r * (r + 1) / 2 + c : c * (c + 1) / 2 + r; }
    double inverse[10] = {};
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

// Internal to the physics library: the normal impulses of one manifold's points (at most four)
// acting together, the contact solver's block solve (contact_solver.h). Each point's impulse
// changes every point's normal velocity through the coupling K (K_ij: point i's change per unit
// impulse at point j); the impulses must be zero or push, and where they push the point must
// reach its target: a small linear complementarity problem, solved exactly here.
#pragma once

namespace softbody {

// What solves K for all points pushing at once, prepared once a tick (prepare_block): K's
// inverse, or, for four corners on a plane (K singular: three would hold the face), the inverse
// with the null direction z filled in, and z itself; and the smaller set of points that pushed
// the last time all of them were solved for (0: none yet), tried first the next time.
struct BlockInverse {
    double K_solve[4][4] = {};
    double z[4] = {};
    bool singular = false;
    unsigned last_set = 0;
};

// The inverse of an n x n matrix (n <= 4) by Gauss-Jordan elimination with partial pivoting;
// false when a pivot vanishes.
bool invert(int n, const double (&A)[4][4], double (&inverse)[4][4]);

// From K of n points and their coordinates q in the contact plane (from any one of them).
void prepare_block(int n, const double (&K)[4][4], const double (&q)[4][2], BlockInverse& block);

// The impulses x >= 0 of n points with coupling K whose normal velocities must rise by b
// where they push ((K x)_i - b_i is point i's normal velocity above its target: zero where
// x_i > 0, at least zero where x_i = 0). `all_points`: K is the one `block` was prepared from,
// so the set of all points is tried first through it, then the set that pushed last time; then
// smaller sets, largest first.
void solve_block(BlockInverse& block, int n, const double (&K)[4][4], const double (&b)[4], double (&x)[4],
                 bool all_points);

}  // namespace softbody

// The pair tile with WebAssembly SIMD (128 bits): four particles i against one particle j at a
// time, for the browser build. This file alone is compiled with -msimd128 there; elsewhere it is
// empty. The formulas are those of pair_tiles.h, and unlike the AVX tiles this one gives the
// portable tile's results bit for bit, so a browser and a native build forced to the portable
// tile (SOFTBODY_KERNEL=portable) reach the same state hash:
//   - WebAssembly has no fused multiply-add and no approximate reciprocal square root, so each
//     pair takes the portable tile's operations in its order: products and sums apart, g = 2 / l
//     from an exact square root and a division, s = (k - (k l0 / 2) g) + ((w . e) g) g.
//   - The sums keep the portable tile's order. It adds the force on i over j = j0, j0 + 1, ...
//     one pair at a time, and the force on j over i = i0, i0 + 1, ... Here the lanes hold four
//     rows i (so each lane sums its row over j in order, as the portable tile does), and the
//     forces on four columns j are turned (a 4 x 4 transpose) so that each column's lane adds
//     its four rows in order, i first.
//   - A pair that is skipped (coincident, or outside the triangle or the tile) adds +0 to a row
//     sum and -0 to a column's: x - (+0) and x + (-0) are x for every x, signed zeros included,
//     as leaving the pair out is.
// Without a fused multiply-add the chains are longer than the AVX tiles', and every pair pays a
// square root and a division more than they do; four lanes still make it 2.4 times the portable
// tile's speed in the same browser, and twice the native portable tile's (tests/benchmarks/README.md, "In the
// browser", has the figures).
#if defined(__wasm_simd128__)

#include <wasm_simd128.h>

#include "pair_tiles.h"

namespace softbody::detail {

namespace {

constexpr std::size_t kLanes = 4;

// Rows i .. i+3, one per lane, and the forces on them summed over j.
struct Rows {
    v128_t x, y, z, vx, vy, vz, rx, ry, rz;
    v128_t fx, fy, fz;
};

Rows load_rows(const PackedParticles& p, std::size_t i) {
    const v128_t zero = wasm_f32x4_splat(0.0f);
    return {wasm_v128_load(p.x + i),  wasm_v128_load(p.y + i),  wasm_v128_load(p.z + i),
            wasm_v128_load(p.vx + i), wasm_v128_load(p.vy + i), wasm_v128_load(p.vz + i),
            wasm_v128_load(p.rx + i), wasm_v128_load(p.ry + i), wasm_v128_load(p.rz + i),
            zero,                     zero,                     zero};
}

// Lane r of a 4 x 4 block, transposed: out[c] lane r = in[r] lane c.
void transpose(v128_t& a, v128_t& b, v128_t& c, v128_t& d) {
    const v128_t ab_lo = wasm_i32x4_shuffle(a, b, 0, 4, 1, 5), ab_hi = wasm_i32x4_shuffle(a, b, 2, 6, 3, 7);
    const v128_t cd_lo = wasm_i32x4_shuffle(c, d, 0, 4, 1, 5), cd_hi = wasm_i32x4_shuffle(c, d, 2, 6, 3, 7);
    a = wasm_i32x4_shuffle(ab_lo, cd_lo, 0, 1, 4, 5);
    b = wasm_i32x4_shuffle(ab_lo, cd_lo, 2, 3, 6, 7);
    c = wasm_i32x4_shuffle(ab_hi, cd_hi, 0, 1, 4, 5);
    d = wasm_i32x4_shuffle(ab_hi, cd_hi, 2, 3, 6, 7);
}

// The pairs (i .. i+3, j): the force s e on each row's lane, as pair_tiles.h derives it, with
// the portable tile's operations in its order. `valid` marks the lanes whose pair counts.
struct PairForce {
    v128_t tx, ty, tz;
    v128_t valid;
};

__attribute__((always_inline)) inline PairForce pair_force(const PackedParticles& p, std::size_t j, const Rows& rows,
                                                           v128_t k, v128_t valid) {
    // e = x_i - x_j = -d: the sign cancels in l^2 and in (v_j - v_i) . d.
    const v128_t ex = wasm_f32x4_sub(rows.x, wasm_v128_load32_splat(p.x + j));
    const v128_t ey = wasm_f32x4_sub(rows.y, wasm_v128_load32_splat(p.y + j));
    const v128_t ez = wasm_f32x4_sub(rows.z, wasm_v128_load32_splat(p.z + j));
    const v128_t l2 = wasm_f32x4_add(wasm_f32x4_add(wasm_f32x4_mul(ex, ex), wasm_f32x4_mul(ey, ey)), wasm_f32x4_mul(ez, ez));
    // Coincident (l^2 below the smallest normal float): no direction, no force. Written as "not
    // below" so that a NaN counts, as it does in the portable tile.
    valid = wasm_v128_andnot(valid, wasm_f32x4_lt(l2, wasm_f32x4_splat(kMinLengthSq)));
    const v128_t g = wasm_f32x4_div(wasm_f32x4_splat(2.0f), wasm_f32x4_sqrt(l2));
    // (k/2) l0 from the pre-scaled rest positions.
    const v128_t qx = wasm_f32x4_sub(rows.rx, wasm_v128_load32_splat(p.rx + j));
    const v128_t qy = wasm_f32x4_sub(rows.ry, wasm_v128_load32_splat(p.ry + j));
    const v128_t qz = wasm_f32x4_sub(rows.rz, wasm_v128_load32_splat(p.rz + j));
    const v128_t half_k_l0 =
        wasm_f32x4_sqrt(wasm_f32x4_add(wasm_f32x4_add(wasm_f32x4_mul(qx, qx), wasm_f32x4_mul(qy, qy)), wasm_f32x4_mul(qz, qz)));
    // (c/4) (v_i - v_j) . e
    const v128_t wx = wasm_f32x4_sub(rows.vx, wasm_v128_load32_splat(p.vx + j));
    const v128_t wy = wasm_f32x4_sub(rows.vy, wasm_v128_load32_splat(p.vy + j));
    const v128_t wz = wasm_f32x4_sub(rows.vz, wasm_v128_load32_splat(p.vz + j));
    const v128_t dv_d = wasm_f32x4_add(wasm_f32x4_add(wasm_f32x4_mul(wx, ex), wasm_f32x4_mul(wy, ey)), wasm_f32x4_mul(wz, ez));
    // s = k - (k l0 / 2) g + (c/4)(dv . d) g^2
    const v128_t s = wasm_f32x4_add(wasm_f32x4_sub(k, wasm_f32x4_mul(half_k_l0, g)),
                                    wasm_f32x4_mul(wasm_f32x4_mul(dv_d, g), g));
    return {wasm_f32x4_mul(s, ex), wasm_f32x4_mul(s, ey), wasm_f32x4_mul(s, ez), valid};
}

// Lanes r (rows i + r) with i + r < end.
v128_t rows_below(std::size_t i, std::size_t end) {
    const v128_t index = wasm_i32x4_add(wasm_i32x4_splat(static_cast<int>(i)), wasm_i32x4_make(0, 1, 2, 3));
    return wasm_i32x4_lt(index, wasm_i32x4_splat(static_cast<int>(end)));
}

// The four columns j .. j+3 against rows i .. i+3 (valid_rows marks the rows that exist; on a
// diagonal tile only the pairs with column > row count). Row sums and the columns' forces in
// out_j (x; y and z at kTile and 2 kTile) grow as in the portable tile.
__attribute__((always_inline)) inline void block(const PackedParticles& p, std::size_t i, std::size_t j, std::size_t j1,
                                                 bool diagonal, Rows& rows, v128_t k, v128_t valid_rows, float* out_j) {
    const v128_t row_index = wasm_i32x4_add(wasm_i32x4_splat(static_cast<int>(i)), wasm_i32x4_make(0, 1, 2, 3));
    const v128_t minus_zero = wasm_f32x4_splat(-0.0f);
    v128_t cx[kLanes], cy[kLanes], cz[kLanes];  // per column: the forces on it, one lane per row
    for (std::size_t c = 0; c < kLanes; ++c) {
        const std::size_t col = j + c;
        v128_t valid = col < j1 ? valid_rows : wasm_i32x4_splat(0);
        if (diagonal) valid = wasm_v128_and(valid, wasm_i32x4_lt(row_index, wasm_i32x4_splat(static_cast<int>(col))));
        const PairForce f = pair_force(p, col, rows, k, valid);
        // On i: s d = -s e, each row in column order.
        rows.fx = wasm_f32x4_sub(rows.fx, wasm_v128_and(f.tx, f.valid));
        rows.fy = wasm_f32x4_sub(rows.fy, wasm_v128_and(f.ty, f.valid));
        rows.fz = wasm_f32x4_sub(rows.fz, wasm_v128_and(f.tz, f.valid));
        // On j: +s e, kept until the four columns are turned to one lane each.
        cx[c] = wasm_v128_bitselect(f.tx, minus_zero, f.valid);
        cy[c] = wasm_v128_bitselect(f.ty, minus_zero, f.valid);
        cz[c] = wasm_v128_bitselect(f.tz, minus_zero, f.valid);
    }
    transpose(cx[0], cx[1], cx[2], cx[3]);  // now cx[r] lane c: row i + r on column j + c
    transpose(cy[0], cy[1], cy[2], cy[3]);
    transpose(cz[0], cz[1], cz[2], cz[3]);
    v128_t ox = wasm_v128_load(out_j), oy = wasm_v128_load(out_j + kTile), oz = wasm_v128_load(out_j + 2 * kTile);
    for (std::size_t r = 0; r < kLanes; ++r) {
        ox = wasm_f32x4_add(ox, cx[r]);
        oy = wasm_f32x4_add(oy, cy[r]);
        oz = wasm_f32x4_add(oz, cz[r]);
    }
    wasm_v128_store(out_j, ox);
    wasm_v128_store(out_j + kTile, oy);
    wasm_v128_store(out_j + 2 * kTile, oz);
}

// a + b in the lanes of `mask`, a elsewhere.
v128_t add_where(v128_t a, v128_t b, v128_t mask) { return wasm_v128_bitselect(wasm_f32x4_add(a, b), a, mask); }

}  // namespace

void tile_wasm(const PackedParticles& p, std::size_t i0, std::size_t i1, std::size_t j0, std::size_t j1, bool diagonal,
               float* out_i, float* out_j) {
    const v128_t k = wasm_f32x4_splat(p.k);
    for (std::size_t i = i0; i < i1; i += kLanes) {  // i0 is a multiple of kPad, so of 4
        Rows rows = load_rows(p, i);
        const v128_t valid_rows = rows_below(i, i1);
        // On a diagonal tile the first columns are the rows' own block (pairs above the diagonal).
        for (std::size_t j = diagonal ? i : j0; j < j1; j += kLanes) {
            block(p, i, j, j1, diagonal, rows, k, valid_rows, out_j + (j - j0));
        }
        // Each row's sum, after every column (on a diagonal tile, after the rows above have
        // added to it as a column: the portable tile's order).
        float* o = out_i + (i - i0);
        wasm_v128_store(o, add_where(wasm_v128_load(o), rows.fx, valid_rows));
        wasm_v128_store(o + kTile, add_where(wasm_v128_load(o + kTile), rows.fy, valid_rows));
        wasm_v128_store(o + 2 * kTile, add_where(wasm_v128_load(o + 2 * kTile), rows.fz, valid_rows));
    }
}

double stretch_tile_wasm(const PackedParticles& p, std::size_t i0, std::size_t i1, std::size_t j0, std::size_t j1,
                         bool diagonal) {
    // The portable tile's one running sum over the pairs, row by row, j in order; four columns'
    // lengths at a time. Columns outside the tile add +0 (the sum is never -0).
    double sum = 0.0;
    for (std::size_t i = i0; i < i1; ++i) {
        const v128_t x = wasm_f32x4_splat(p.x[i]), y = wasm_f32x4_splat(p.y[i]), z = wasm_f32x4_splat(p.z[i]);
        const v128_t rx = wasm_f32x4_splat(p.rx[i]), ry = wasm_f32x4_splat(p.ry[i]), rz = wasm_f32x4_splat(p.rz[i]);
        const std::size_t first = diagonal ? i + 1 : j0;
        for (std::size_t j = first & ~(kLanes - 1); j < j1; j += kLanes) {
            const v128_t ex = wasm_f32x4_sub(x, wasm_v128_load(p.x + j));
            const v128_t ey = wasm_f32x4_sub(y, wasm_v128_load(p.y + j));
            const v128_t ez = wasm_f32x4_sub(z, wasm_v128_load(p.z + j));
            const v128_t qx = wasm_f32x4_sub(rx, wasm_v128_load(p.rx + j));
            const v128_t qy = wasm_f32x4_sub(ry, wasm_v128_load(p.ry + j));
            const v128_t qz = wasm_f32x4_sub(rz, wasm_v128_load(p.rz + j));
            const v128_t l =
                wasm_f32x4_sqrt(wasm_f32x4_add(wasm_f32x4_add(wasm_f32x4_mul(ex, ex), wasm_f32x4_mul(ey, ey)), wasm_f32x4_mul(ez, ez)));
            const v128_t l0 =
                wasm_f32x4_sqrt(wasm_f32x4_add(wasm_f32x4_add(wasm_f32x4_mul(qx, qx), wasm_f32x4_mul(qy, qy)), wasm_f32x4_mul(qz, qz)));
            // (l - l0) in double, squared, two lanes at a time; then added one by one in j order.
            const v128_t lo = wasm_f64x2_sub(wasm_f64x2_promote_low_f32x4(l), wasm_f64x2_promote_low_f32x4(l0));
            const v128_t hi = wasm_f64x2_sub(wasm_f64x2_promote_low_f32x4(wasm_i32x4_shuffle(l, l, 2, 3, 2, 3)),
                                             wasm_f64x2_promote_low_f32x4(wasm_i32x4_shuffle(l0, l0, 2, 3, 2, 3)));
            const v128_t lo2 = wasm_f64x2_mul(lo, lo), hi2 = wasm_f64x2_mul(hi, hi);
            const double squares[kLanes] = {wasm_f64x2_extract_lane(lo2, 0), wasm_f64x2_extract_lane(lo2, 1),
                                            wasm_f64x2_extract_lane(hi2, 0), wasm_f64x2_extract_lane(hi2, 1)};
            for (std::size_t c = 0; c < kLanes; ++c) {
                if (j + c >= first && j + c < j1) sum += squares[c];
            }
        }
    }
    return sum;
}

float probe_wasm(std::size_t rounds, float seed) {
    // A multiply and an add per step (no fused multiply-add in WebAssembly), as the tile spends
    // them; 12 chains of four lanes, half the SIMD probes' count, as the portable probe runs.
    constexpr std::size_t kChains = kProbeChains / 2;
    v128_t a[kChains];
    for (std::size_t c = 0; c < kChains; ++c) a[c] = wasm_f32x4_splat(seed + 0.001f * float(c));
    const v128_t b = wasm_f32x4_splat(0.999f), c = wasm_f32x4_splat(0.001f);
    for (std::size_t r = 0; r < rounds; ++r) {
#pragma clang loop unroll(full)
        for (std::size_t k = 0; k < kChains; ++k) a[k] = wasm_f32x4_add(wasm_f32x4_mul(a[k], b), c);
    }
    v128_t sum = a[0];
    for (std::size_t k = 1; k < kChains; ++k) sum = wasm_f32x4_add(sum, a[k]);
    return wasm_f32x4_extract_lane(sum, 0) + wasm_f32x4_extract_lane(sum, 1) + wasm_f32x4_extract_lane(sum, 2) +
           wasm_f32x4_extract_lane(sum, 3);
}

}  // namespace softbody::detail

#endif  // __wasm_simd128__

// The fixed-tick clock (Listing 8's "physics lag time" loop): elapsed wall time in, whole
// ticks out, at most a cap per frame, and the leftover as a fraction of a tick.
#include <cmath>
#include <limits>
#include <random>

#include "physics/clock.h"
#include "test_support.h"

namespace softbody::test {
namespace {

// With a tick of 1/64 s every time below is a short binary fraction: exact answers.
TEST(FixedClock, WholeTicksFromElapsedTime) {
    const double dt = 1.0 / 64.0;
    FixedClock clock(dt, 8);
    EXPECT_EQ(clock.advance(3 * dt), 3);
    EXPECT_EQ(clock.alpha(), 0.0);
    EXPECT_EQ(clock.advance(dt / 2), 0);  // half a tick: nothing to run yet
    EXPECT_EQ(clock.alpha(), 0.5);
    EXPECT_EQ(clock.advance(dt / 4), 0);
    EXPECT_EQ(clock.alpha(), 0.75);
    EXPECT_EQ(clock.advance(dt / 4), 1);  // the quarters add up to a whole tick
    EXPECT_EQ(clock.alpha(), 0.0);
    EXPECT_EQ(clock.advance(2.5 * dt), 2);
    EXPECT_EQ(clock.alpha(), 0.5);
    EXPECT_EQ(clock.dropped_ticks(), 0u);
}

// Decimal ticks: 3 x 0.02 s is a hair over 0.06 s in binary, so a frame of 0.06 s must still
// give three ticks (not two and a leftover of 0.99999 of a tick).
TEST(FixedClock, DecimalTickLengths) {
    FixedClock clock(0.02, 8);
    EXPECT_EQ(clock.advance(0.06), 3);
    // The leftover is rounding, not a tick: far below any fraction one could see.
    EXPECT_LT(clock.alpha(), 1e-6);
    EXPECT_GE(clock.alpha(), 0.0);
    EXPECT_EQ(clock.advance(0.01), 0);
    EXPECT_NEAR(clock.alpha(), 0.5, 1e-9);
}

// 60 Hz frames against a 50 Hz tick: 10 s of frames give 500 ticks, one tick short at most
// (rounding of the sum can leave the last tick a hair unfinished).
TEST(FixedClock, LongRunKeepsTime) {
    FixedClock clock(0.02, 8);
    long ticks = 0;
    for (int frame = 0; frame < 600; ++frame) {
        const int now = clock.advance(1.0 / 60.0);
        EXPECT_GE(now, 0);
        EXPECT_LE(now, 1);  // a 16.7 ms frame never owes two 20 ms ticks
        ticks += now;
        ASSERT_GE(clock.alpha(), 0.0);
        ASSERT_LT(clock.alpha(), 1.0);
    }
    EXPECT_GE(ticks, 499);
    EXPECT_LE(ticks, 500);
    EXPECT_EQ(clock.dropped_ticks(), 0u);
}

// A slow frame runs at most the cap and drops the rest of the whole ticks, but keeps the
// leftover fraction (dropping it would make the picture stutter).
TEST(FixedClock, CapsTicksPerFrameAndDropsTheRest) {
    {
        const double dt = 1.0 / 64.0;
        FixedClock clock(dt, 8);
        EXPECT_EQ(clock.advance(1.0 + dt / 2), 8);  // 64.5 ticks owed
        EXPECT_EQ(clock.dropped_ticks(), 56u);
        EXPECT_EQ(clock.alpha(), 0.5);
        EXPECT_EQ(clock.advance(dt / 2), 1);  // no snowball: the next frame is back to normal
        EXPECT_EQ(clock.alpha(), 0.0);
    }
    {
        FixedClock clock(0.02, 8);
        EXPECT_EQ(clock.advance(1.0), 8);  // 50 ticks owed
        EXPECT_EQ(clock.dropped_ticks(), 42u);
        EXPECT_LT(clock.alpha(), 1e-6);
        EXPECT_EQ(clock.advance(0.01), 0);
        EXPECT_NEAR(clock.alpha(), 0.5, 1e-9);
    }
    {
        FixedClock clock(0.02, 1);
        clock.set_max_ticks_per_frame(0);  // at least one tick a frame, always
        EXPECT_EQ(clock.advance(0.1), 1);
        EXPECT_EQ(clock.dropped_ticks(), 4u);
    }
}

TEST(FixedClock, IgnoresPausesAndClockHiccups) {
    FixedClock clock(1.0 / 64.0, 8);
    clock.advance(1.0 / 128.0);
    for (double bad : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                       -std::numeric_limits<double>::infinity()}) {
        EXPECT_EQ(clock.advance(bad), 0) << bad;
        EXPECT_EQ(clock.alpha(), 0.5) << bad;
        EXPECT_EQ(clock.dropped_ticks(), 0u) << bad;
    }
    clock.reset();
    EXPECT_EQ(clock.alpha(), 0.0);
}

TEST(FixedClock, ChangingDtKeepsTheFraction) {
    FixedClock clock(1.0 / 64.0, 8);
    clock.advance(0.75 / 64.0);
    clock.set_dt(1.0 / 32.0);
    EXPECT_EQ(clock.dt(), 1.0 / 32.0);
    EXPECT_EQ(clock.alpha(), 0.75);
    EXPECT_EQ(clock.advance(0.25 / 32.0), 1);
}

// Any sequence of frames: ticks within the cap, alpha in [0, 1), and run + dropped ticks
// account for all the time that passed (within one tick of rounding).
TEST(FixedClock, InvariantsOverRandomFrames) {
    for (const double dt : {0.02, 1.0 / 60.0, 0.005, 0.013}) {
        FixedClock clock(dt, 5);
        std::mt19937 rng(1);
        std::uniform_real_distribution<double> frame(0.0, 0.2);
        double elapsed = 0.0;
        long ticks = 0;
        for (int n = 0; n < 200000; ++n) {
            const double seconds = frame(rng);
            elapsed += seconds;
            const int now = clock.advance(seconds);
            ASSERT_GE(now, 0);
            ASSERT_LE(now, 5);
            ticks += now;
            ASSERT_GE(clock.alpha(), 0.0) << "dt " << dt << ", frame " << n;
            ASSERT_LT(clock.alpha(), 1.0) << "dt " << dt << ", frame " << n;
        }
        const double accounted = (double(ticks) + double(clock.dropped_ticks()) + clock.alpha()) * dt;
        // 200,000 frames summed in double: rounding of ~1e-16 relative each, far below 1e-6 s.
        EXPECT_NEAR(accounted, elapsed, 1e-6 + 1e-9 * elapsed) << "dt " << dt;
    }
}

}  // namespace
}  // namespace softbody::test

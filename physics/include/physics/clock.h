// Listing 8's "physics lag time" loop as an object: elapsed wall time goes in, a whole number
// of fixed ticks comes out. The physics only ever sees the fixed dt, never the frame time.
#pragma once

#include <cstdint>

namespace softbody {

class FixedClock {
public:
    explicit FixedClock(double dt = 0.02, int max_ticks_per_frame = 8);

    // Adds elapsed seconds to the lag and returns how many ticks to run now (at most the cap;
    // lag beyond the cap is dropped so one slow frame cannot snowball into slower ones).
    int advance(double elapsed_seconds);

    // Leftover lag as a fraction of a tick in [0, 1): how far to interpolate from the previous
    // tick's state toward the current one when drawing.
    double alpha() const { return lag_ / dt_; }

    void set_dt(double dt);
    double dt() const { return dt_; }
    void set_max_ticks_per_frame(int ticks) { max_ticks_ = ticks < 1 ? 1 : ticks; }
    void reset() { lag_ = 0.0; }
    std::uint64_t dropped_ticks() const { return dropped_; }

private:
    double dt_;
    int max_ticks_;
    double lag_ = 0.0;
    std::uint64_t dropped_ = 0;
};

}  // namespace softbody

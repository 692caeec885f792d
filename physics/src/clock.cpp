#include "physics/clock.h"

#include <cmath>

namespace softbody {

FixedClock::FixedClock(double dt, int max_ticks_per_frame) : dt_(dt), max_ticks_(max_ticks_per_frame < 1 ? 1 : max_ticks_per_frame) {}

void FixedClock::set_dt(double dt) {
    // Keep the same fraction of a tick pending, so interpolation does not jump.
    const double fraction = alpha();
    dt_ = dt;
    lag_ = fraction * dt_;
}

int FixedClock::advance(double elapsed_seconds) {
    if (!(elapsed_seconds > 0.0) || !std::isfinite(elapsed_seconds)) return 0;  // paused, or a clock hiccup
    lag_ += elapsed_seconds;
    // Tick lengths like 0.02 s are not binary fractions: 0.06 - 0.02 - 0.02 comes out a hair
    // under 0.02. A lag within a billionth of a tick of a whole tick is that whole tick, so a
    // frame of exactly three ticks runs three and alpha() stays below 1.
    const double whole = dt_ * (1.0 - 1e-9);
    int ticks = 0;
    while (lag_ >= whole && ticks < max_ticks_) {
        lag_ -= dt_;
        ++ticks;
    }
    if (lag_ >= whole) {
        const double excess = std::floor(lag_ / dt_ + 1e-9);
        dropped_ += static_cast<std::uint64_t>(excess);
        lag_ -= excess * dt_;
    }
    if (lag_ < 0.0) lag_ = 0.0;  // the hair taken by rounding up to a whole tick
    return ticks;
}

}  // namespace softbody

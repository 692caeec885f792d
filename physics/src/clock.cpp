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
    int ticks = 0;
    while (lag_ >= dt_ && ticks < max_ticks_) {
        lag_ -= dt_;
        ++ticks;
    }
    if (lag_ >= dt_) {
        const double excess = std::floor(lag_ / dt_);
        dropped_ += static_cast<std::uint64_t>(excess);
        lag_ -= excess * dt_;
    }
    return ticks;
}

}  // namespace softbody

// The energies of the last ten seconds, sampled once a frame, for the Energy tool's lines and
// the comparison's table; and what the rigid contacts did over the last second.
#pragma once

#include <cstddef>
#include <deque>
#include <utility>
#include <vector>

#include "physics/world.h"

namespace softbody::app {

struct EnergySample {
    double time, kinetic, gravity, elastic, total;
    double rotational;        // the rigid bodies' part of the kinetic energy
    double angular_momentum;  // |L| about the origin, every body
    double contacts;          // what the rigid contacts did in the last second (J; < 0: took)
    std::vector<double> compared;  // each compared world's total, in order
};

class EnergyRecord {
public:
    static constexpr std::size_t kSamples = 600;  // about ten seconds at 60 frames a second

    // After every tick: what its contacts did (kept for a second).
    void after_tick(const World& world);
    // Once a frame: the world's energies now, and the compared worlds' totals.
    void sample(World& world, const std::vector<double>& compared_totals);
    // The world went back to `time` (time travel): what is later is cut.
    void cut_after(double time);
    void clear();

    const std::deque<EnergySample>& samples() const { return samples_; }
    double contact_work_last_second() const;  // J, World::contact_energy() over the last second's ticks

private:
    std::deque<EnergySample> samples_;
    std::deque<std::pair<double, double>> contact_work_;  // (time, a tick's contact energy), the last second
};

}  // namespace softbody::app

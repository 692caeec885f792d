#include "gui/energy_record.h"

namespace softbody::app {

void EnergyRecord::after_tick(const World& world) {
    contact_work_.emplace_back(world.time(), world.contact_energy().total);
    while (!contact_work_.empty() && contact_work_.front().first <= world.time() - 1.0 + 1e-9) contact_work_.pop_front();
}

void EnergyRecord::sample(World& world, const std::vector<double>& compared_totals) {
    const Energy e = world.energy();
    samples_.push_back({world.time(), e.kinetic, e.gravity, e.elastic, e.total(), e.rotational, length(world.angular_momentum()),
                        contact_work_last_second(), compared_totals});
    while (samples_.size() > kSamples) samples_.pop_front();
}

void EnergyRecord::cut_after(double time) {
    while (!samples_.empty() && samples_.back().time >= time) samples_.pop_back();
    while (!contact_work_.empty() && contact_work_.back().first > time) contact_work_.pop_back();
}

void EnergyRecord::clear() {
    samples_.clear();
    contact_work_.clear();
}

double EnergyRecord::contact_work_last_second() const {
    double sum = 0.0;
    for (const auto& [time, work] : contact_work_) sum += work;
    return sum;
}

}  // namespace softbody::app

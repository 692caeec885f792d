// Time travel (history.h): keyframes and the inputs of every tick, replayed.
#include "physics/history.h"

#include <algorithm>

namespace softbody {

History::History(std::uint64_t keyframe_every, std::uint64_t capacity_ticks)
    : keyframe_every_(std::max<std::uint64_t>(1, keyframe_every)), capacity_ticks_(std::max<std::uint64_t>(1, capacity_ticks)) {}

History::Settings History::settings_of(const World& world) { return world.def(); }

// Only what differs is set: setting the grab or the keys marks the world's energy baseline
// stale (divergence detection), and a replay must do exactly what the live run did. What was
// made or unmade between two ticks is not among the inputs: a keyframe holds it (keyframe_now).
void History::apply(World& world, const TickInputs& inputs) {
    if (inputs.settings) {
        const Settings& s = *inputs.settings;
        if (!(world.settings() == s.settings)) world.set_settings(s.settings);
        for (std::size_t b = 0; b < world.soft_body_count() && b < s.soft_bodies.size(); ++b) {
            const SoftBodyId id = world.soft_body_id(b);
            if (!(world.def(id) == s.soft_bodies[b]) && world.def(id).name == s.soft_bodies[b].name) world.set_def(id, s.soft_bodies[b]);
        }
        for (std::size_t b = 0; b < world.rigid_body_count() && b < s.rigid_bodies.size(); ++b) {
            const RigidBodyId id = world.rigid_body_id(b);
            if (!(world.def(id) == s.rigid_bodies[b]) && world.def(id).name == s.rigid_bodies[b].name) world.set_def(id, s.rigid_bodies[b]);
        }
        for (std::size_t k = 0; k < world.spring_count() && k < s.springs.size(); ++k) {
            const SpringId id = world.spring_id(k);
            if (!(world.def(id) == s.springs[k]) && world.def(id).name == s.springs[k].name) world.set_def(id, s.springs[k]);
        }
    }
    if (world.grab() != inputs.grab) world.set_grab(inputs.grab);
}

void History::start(const World& world) {
    keyframes_.clear();
    inputs_.clear();
    keyframes_.push_back({world.ticks(), world.snapshot()});
    inputs_start_ = newest_ = world.ticks();
    last_settings_ = std::make_shared<const Settings>(settings_of(world));
}

void History::before_tick(World& world) {
    const std::uint64_t t = world.ticks();
    if (keyframes_.empty() || t < oldest_tick() || t > newest_) start(world);  // ticked behind our back
    if (t < newest_) {
        // Something the inputs cannot replay happened at this tick (a pin, a body made or
        // unmade): the world takes it from that moment's keyframe before going on.
        const auto at = std::lower_bound(keyframes_.begin(), keyframes_.end(), t,
                                         [](const Keyframe& k, std::uint64_t tick) { return k.tick < tick; });
        if (at != keyframes_.end() && at->tick == t && at->forced) world.restore(at->state);
        apply(world, inputs_[t - inputs_start_]);  // the past: what this tick ran with
        return;
    }
    // The newest tick: record what it runs with (a diverged world's tick that did not happen
    // is recorded again, not twice).
    Settings now = settings_of(world);
    if (!last_settings_ || !(*last_settings_ == now)) last_settings_ = std::make_shared<const Settings>(std::move(now));
    inputs_.resize(t - inputs_start_);
    inputs_.push_back({world.grab(), last_settings_});
}

void History::after_tick(const World& world) {
    const std::uint64_t t = world.ticks();
    if (t <= newest_) return;  // replayed: the keyframes are there already
    newest_ = t;
    if (t % keyframe_every_ == 0 && keyframes_.back().tick < t) keyframes_.push_back({t, world.snapshot()});
    trim();
}

void History::drop_after(std::uint64_t tick) {
    while (keyframes_.size() > 1 && keyframes_.back().tick > tick) keyframes_.pop_back();
    if (tick >= inputs_start_ && tick - inputs_start_ < inputs_.size()) inputs_.resize(tick - inputs_start_);
    newest_ = std::min(newest_, tick);
}

void History::branch(const World& world) {
    if (!keyframes_.empty() && in_past(world)) drop_after(world.ticks());
}

void History::keyframe_now(const World& world) {
    branch(world);
    const std::uint64_t t = world.ticks();
    if (keyframes_.empty() || t < oldest_tick() || t > newest_) {
        start(world);
        return;
    }
    if (keyframes_.back().tick == t) keyframes_.pop_back();
    keyframes_.push_back({t, world.snapshot(), true});
}

void History::trim() {
    // Keep the oldest keyframe at or before newest - capacity, so the whole capacity is there.
    while (keyframes_.size() > 1 && newest_ - keyframes_[1].tick >= capacity_ticks_) keyframes_.pop_front();
    while (inputs_start_ < keyframes_.front().tick && !inputs_.empty()) {
        inputs_.pop_front();
        ++inputs_start_;
    }
}

std::uint64_t History::go_to(World& world, std::uint64_t tick) {
    if (keyframes_.empty()) return world.ticks();
    tick = std::clamp(tick, oldest_tick(), newest_);
    // The last keyframe at or before the tick.
    auto it = std::upper_bound(keyframes_.begin(), keyframes_.end(), tick,
                               [](std::uint64_t t, const Keyframe& k) { return t < k.tick; });
    --it;
    world.restore(it->state);
    while (world.ticks() < tick && world.status() == Status::Ok) {
        before_tick(world);
        world.tick();
    }
    // Going into the next tick with what it ran with, so the panels show the keys of that moment.
    if (world.ticks() < newest_) apply(world, inputs_[world.ticks() - inputs_start_]);
    return world.ticks();
}

std::size_t History::bytes() const {
    std::size_t total = sizeof(*this) + inputs_.size() * sizeof(TickInputs);
    for (const Keyframe& k : keyframes_) total += sizeof(Keyframe) + k.state.bytes();
    return total;
}

}  // namespace softbody

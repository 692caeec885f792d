// Time travel: the recent past of a world, to scrub back to, step back through and play on from.
//
// Two records, kept for the last `capacity_ticks` ticks:
//   - a keyframe (World::snapshot) every `keyframe_every` ticks, and one more wherever something
//     the inputs below cannot replay happened (a pin set or freed, a body or spring made or
//     unmade);
//   - the inputs of every tick: the grab and the keys (the world's settings and every body's
//     and spring's definition, keys.h) the tick ran with.
// Going to tick T restores the last keyframe at or before T and runs the ticks between with their
// recorded inputs, so the world at T is bit for bit the one that was there. Playing on from the
// past replays the recorded inputs to the end of the record, then goes on live: when nothing
// is changed, the future is the one that happened. Changing anything in the past (a key, a
// grab, a pin) drops the recorded future from that tick: from there on, it is a new one.
//
// Cost: a keyframe holds, for each particle, x, v, Verlet's last step and the previous tick's x
// (4 x 12 bytes) and its inverse mass (4 bytes), 52 bytes; 5,000 particles take 260 KB, and
// 20 s at one keyframe every 10 ticks of 0.02 s (100 keyframes) 26 MB. Going anywhere
// re-simulates at most keyframe_every - 1 ticks.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include "physics/world.h"

namespace softbody {

class History {
public:
    static constexpr std::uint64_t kDefaultKeyframeEvery = 10;
    static constexpr std::uint64_t kDefaultCapacityTicks = 1000;  // 20 s at dt = 0.02 s

    explicit History(std::uint64_t keyframe_every = kDefaultKeyframeEvery,
                     std::uint64_t capacity_ticks = kDefaultCapacityTicks);

    // Forgets everything and starts the record at the world's current tick.
    void start(const World& world);

    // Around every World::tick(): before_tick replays the recorded inputs when the world is in
    // the past, or records the world's current ones when it is at the newest tick; after_tick
    // keeps a keyframe when one is due and forgets what is older than the capacity.
    void before_tick(World& world);
    void after_tick(const World& world);

    // Something the inputs cannot replay happened at the current tick (a pin): keep a keyframe
    // here. In the past, the recorded future is dropped first (see branch()).
    void keyframe_now(const World& world);

    // The user changed something at the world's current tick: when that is in the past, the
    // recorded future is no longer what would happen, and is dropped.
    void branch(const World& world);

    // Puts the world at `tick` (clamped to the record), replaying from the keyframe before it.
    // Returns the tick it got to. Stops early if the world diverges on the way.
    std::uint64_t go_to(World& world, std::uint64_t tick);

    bool in_past(const World& world) const { return world.ticks() < newest_; }
    std::uint64_t oldest_tick() const { return keyframes_.empty() ? 0 : keyframes_.front().tick; }
    std::uint64_t newest_tick() const { return newest_; }
    std::size_t keyframe_count() const { return keyframes_.size(); }
    std::size_t bytes() const;  // the memory the record holds
    std::uint64_t keyframe_every() const { return keyframe_every_; }
    std::uint64_t capacity_ticks() const { return capacity_ticks_; }

private:
    using Settings = WorldDef;  // the keys, as World::def() gives them
    struct TickInputs {
        std::optional<Grab> grab;
        std::shared_ptr<const Settings> settings;
    };
    struct Keyframe {
        std::uint64_t tick = 0;
        WorldSnapshot state;
        bool forced = false;  // kept by keyframe_now: what the inputs cannot replay happened here
    };

    static Settings settings_of(const World& world);
    static void apply(World& world, const TickInputs& inputs);
    void drop_after(std::uint64_t tick);  // forget keyframes after `tick` and inputs from it
    void trim();

    std::uint64_t keyframe_every_, capacity_ticks_;
    std::deque<Keyframe> keyframes_;
    std::deque<TickInputs> inputs_;  // inputs_[t - inputs_start_]: what tick t ran with
    std::uint64_t inputs_start_ = 0;
    std::uint64_t newest_ = 0;       // the latest tick the record reaches
    std::shared_ptr<const Settings> last_settings_;
};

}  // namespace softbody

// The session's time (session.h): the fixed-tick clock, each tick recorded or replayed, travel
// through the recorded past, and the compared worlds stepped in lockstep.
#include <algorithm>
#include <chrono>
#include <cmath>

#include "gui/session.h"

namespace softbody::app {

void Session::advance(double wall_seconds) {
    ticks_last_frame_ = 0;
    clock_.set_max_ticks_per_frame(max_ticks_per_frame);
    if (paused || world_->status() != Status::Ok) return;
    const int ticks = clock_.advance(wall_seconds * time_scale);
    if (ticks == 0) return;
    const auto start = std::chrono::steady_clock::now();
    for (int t = 0; t < ticks && world_->status() == Status::Ok; ++t) {
        tick_once();
        ++ticks_last_frame_;
    }
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    physics_ms_per_tick_ = ms / std::max(1, ticks_last_frame_);
    if (world_->status() != Status::Ok) error_ = world_->divergence();
    sample_energy();
}

void Session::single_tick() {
    if (world_->status() != Status::Ok) return;
    tick_once();
    ticks_last_frame_ = 1;
    if (world_->status() != Status::Ok) error_ = world_->divergence();
    sample_energy();
}

void Session::tick_once() {
    const bool replaying = history_.in_past(*world_);
    history_.before_tick(*world_);
    world_->tick();
    history_.after_tick(*world_);
    for (const auto& observe : on_tick) observe(*world_);
    energy_.after_tick(*world_);
    // The compared worlds in lockstep (each replaying its own record when in the past).
    for (ComparedWorld& c : compared_) {
        if (c.world->status() != Status::Ok) continue;
        c.history.before_tick(*c.world);
        c.world->tick();
        c.history.after_tick(*c.world);
    }
    note_collision();
    if (replaying) after_travel();
}

void Session::changed() {
    history_.branch(*world_);
    for (ComparedWorld& c : compared_) c.history.branch(*c.world);
}

void Session::go_to_tick(std::uint64_t tick) {
    paused = true;
    history_.go_to(*world_, tick);
    for (ComparedWorld& c : compared_) c.history.go_to(*c.world, tick);
    // The energy plot and the last collision come back with the world; the plot is cut at now.
    energy_.cut_after(world_->time());
    sample_energy();
    last_collision_.reset();
    clock_.reset();
    after_travel();
    if (world_->status() == Status::Ok) error_.clear();  // back before it diverged
    else error_ = world_->divergence();
}

void Session::rewind(double seconds) {
    const double dt = double(world_->settings().dt);
    const auto back = static_cast<std::uint64_t>(std::llround(std::max(0.0, seconds) / dt));
    go_to_tick(world_->ticks() > back ? world_->ticks() - back : 0);
}

// A replayed tick may bring back keys of that moment, and a keyframe what the world held: the
// clock's dt follows, and a selection of a body no longer there is dropped.
void Session::after_travel() {
    clock_.set_dt(world_->settings().dt);
    if (selected_body_ >= world_->soft_body_count()) selected_body_ = 0;
}

// A collision, not resting contact: a point closing faster than two steps of gravity (and at
// least 1 cm/s, for a world without gravity). The one with the largest impulse is kept.
void Session::note_collision() {
    const World& world = *world_;
    const double h = double(world.settings().dt) / world.substeps_in_use();
    const double closing = std::max(0.01, 2.0 * std::abs(double(world.settings().gravity.z)) * h);
    const RigidContact* hardest = nullptr;
    for (const RigidContact& c : world.contacts()) {
        if (c.approach_speed > closing && (!hardest || c.normal_impulse > hardest->normal_impulse)) hardest = &c;
    }
    if (!hardest) return;
    const RigidContact& c = *hardest;
    LastCollision hit;
    hit.time = world.time();
    hit.body_1 = c.soft >= 0 ? "particle " + std::to_string(c.a) + " of '" + world.soft_body(std::size_t(c.soft)).name() + "'"
                             : world.rigid_body(c.a).name;
    hit.body_2 = c.b < 0 ? "the ground" : world.rigid_body(std::size_t(c.b)).name;
    hit.points = std::size_t(std::count_if(world.contacts().begin(), world.contacts().end(), [&](const RigidContact& d) {
        return d.soft == c.soft && d.b == c.b && (c.soft >= 0 || d.a == c.a);
    }));
    hit.terms = world.impulse_terms(c);
    last_collision_ = std::move(hit);
}

void Session::sample_energy() {
    std::vector<double> compared;
    for (ComparedWorld& c : compared_) compared.push_back(c.world->energy().total());
    energy_.sample(*world_, compared);
}

// --- Comparing integrators ------------------------------------------------------------------

bool Session::compare(const std::vector<CompareSetup>& others) {
    if (others.size() > 3) {
        error_ = "compare: at most three integrators beside the main world's";
        return false;
    }
    compared_.clear();
    if (others.empty()) return true;  // back to one world, where it is
    for (const CompareSetup& setup : others) compared_.push_back(ComparedWorld{setup, nullptr, History{}});
    reset();  // the main world from t = 0, and the copies built beside it
    return compared_.size() == others.size();
}

WorldSettings Session::compared_settings(const CompareSetup& setup, WorldSettings settings) const {
    settings.integrator = setup.integrator;
    settings.auto_substeps = setup.auto_substeps;
    if (!setup.auto_substeps) settings.substeps = setup.substeps;
    return settings;
}

bool Session::build_compared() {
    const Scene base = scene();
    try {
        for (ComparedWorld& c : compared_) {
            Scene scene = base;
            scene.settings = compared_settings(c.setup, base.settings);
            c.world = std::make_unique<World>(scene, WorldOptions{kDefaultThreads, false});
            c.history.start(*c.world);
        }
    } catch (const std::exception& e) {
        compared_.clear();
        error_ = std::string("compare: ") + e.what();
        return false;
    }
    energy_.clear();
    sample_energy();
    return true;
}

}  // namespace softbody::app

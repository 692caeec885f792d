// The world the user is shaping, and its time: the scene loaded, the keys edited, the bodies
// added and taken out, the fixed-tick clock that runs it, the recorded past to travel back
// through, and the copies of it stepped by other integrators. No GLFW, no ImGui, no camera: the
// view (view.h) draws it, the tools (tool.h) show and edit it.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gui/energy_record.h"
#include "physics/clock.h"
#include "physics/history.h"
#include "physics/inspect.h"
#include "physics/keys.h"
#include "physics/scene_io.h"
#include "physics/world.h"

namespace softbody::app {

// One more world in the integrator comparison: the same scene, another integrator (with its
// own substeps), stepped in lockstep with the main one and drawn beside it in its own colour.
struct CompareSetup {
    Integrator integrator = Integrator::ExplicitEuler;
    bool auto_substeps = true;
    int substeps = 1;  // when not automatic
};
struct ComparedWorld {
    CompareSetup setup;
    std::unique_ptr<World> world;
    History history;
};

// The hardest hit of the latest tick that had one: Eq. 38 term by term for its main point.
struct LastCollision {
    double time = 0.0;           // s
    std::string body_1, body_2;  // names: a rigid body, a soft body's particle, or the ground
    std::size_t points = 1;      // how many points that pair of bodies touched at
    ImpulseTerms terms;
};

// What the user is looking into: a particle of a soft body, or a rigid body (the inspector).
struct Inspected {
    bool rigid = false;
    std::size_t body = 0;
    std::uint32_t particle = 0;
};

class Session {
public:
    // Builds the first world; throws InputError when it cannot (the caller has nothing to show).
    explicit Session(const Scene& scene);

    // --- Loading: never throws; on failure the current world stays and error() says why ----
    bool load(const Scene& scene);
    bool load_scene_file(const std::string& path);
    bool load_mesh_file(const std::string& path);  // the selected soft body takes it
    // A file dropped or opened: a scene file (.json) loads as a scene, anything else as a mesh.
    bool open_file(const std::string& path);
    bool save_preset(const std::string& path, bool overwrite);
    void reset();
    // The scene as it stands: what a preset saves (every key and body now, the lesson's words).
    Scene scene() const;
    // The scene as loaded: a lesson's title, text and closed form (the world holds the rest).
    const Scene& lesson() const { return lesson_; }
    std::uint64_t loads() const { return loads_; }  // how many worlds were loaded (the view frames each new one)
    const std::string& source() const { return source_; }  // scene or mesh the world came from
    void set_source(std::string source) { source_ = std::move(source); }

    // --- Keys: those that apply at once do so now, the others at reset (keys.h), through the
    // world's own setters; the compared copies follow. A bad value is shown as the error.
    void edit_settings(const WorldSettings& settings);
    void edit_body(std::size_t body, const SoftBodyDef& def);
    void edit_rigid_body(std::size_t index, const RigidBodyDef& def);
    // One key as --set names it: "dt", "stiffness" (every soft body's), NAME.KEY.
    void set_key(const std::string& key, const std::string& value);
    bool reset_pending() const { return world_->reset_pending(); }
    // The soft body the Parameters tool edits (clicking or grabbing a soft body selects it).
    std::size_t selected_body() const { return selected_body_ < world_->soft_body_count() ? selected_body_ : 0; }
    void select_body(std::size_t body) { selected_body_ = body; }

    // --- What is in the world: made in the running world, the others keeping their motion;
    // time travel goes back across it. False and error() when it cannot be made.
    enum class AddKind { SoftBall, SoftCube, RigidBox, RigidBall, MeshFile };
    bool add_body(AddKind kind, const Vec3& at, const std::string& mesh = {});
    bool remove_body(bool rigid, std::size_t index);
    void toggle_pin(std::size_t body, std::uint32_t particle);
    void set_grab(std::optional<Grab> grab);  // the mouse's pull (view.h makes it)

    // --- Time ----------------------------------------------------------------------------------
    // Feeds elapsed wall time (times time_scale) to the clock and runs the whole ticks due.
    void advance(double wall_seconds);
    void single_tick();  // in the past: the next recorded tick
    bool paused = false;
    double time_scale = 1.0;
    int max_ticks_per_frame = 8;
    double alpha() const { return paused || world_->status() != Status::Ok ? 1.0 : clock_.alpha(); }
    int ticks_last_frame() const { return ticks_last_frame_; }
    double physics_ms_per_tick() const { return physics_ms_per_tick_; }
    // Called after every tick of the main world (a lesson's meter, a tool's record).
    std::vector<std::function<void(const World&)>> on_tick;

    // --- Time travel: the last 1,000 ticks (20 s) are kept (physics/history.h). Going to a
    // recorded tick pauses there; play goes on from it (replaying what was recorded, then
    // live). A change made in the past (a key, a grab, a pin) drops the recorded future.
    void go_to_tick(std::uint64_t tick);
    void step_back() { go_to_tick(world_->ticks() == 0 ? 0 : world_->ticks() - 1); }
    void rewind(double seconds);
    const History& history() const { return history_; }
    bool in_past() const { return history_.in_past(*world_); }

    // --- Comparing integrators: the scene again from t = 0 beside one to three copies of it,
    // ticked in lockstep (the mouse acts on the main world alone; keys, pins, resets and the
    // timeline on all). Empty: back to one world. False and error() when a copy cannot be made.
    bool compare(const std::vector<CompareSetup>& others);
    const std::vector<ComparedWorld>& compared() const { return compared_; }
    bool comparing() const { return !compared_.empty(); }

    // --- What the tools show ---------------------------------------------------------------
    World& world() { return *world_; }
    const World& world() const { return *world_; }
    const EnergyRecord& energy() const { return energy_; }
    const std::optional<LastCollision>& last_collision() const { return last_collision_; }
    const std::string& error() const { return error_; }
    void set_error(std::string message) { error_ = std::move(message); }
    void clear_error() { error_.clear(); }
    // What a user's action did, said once (a preset saved, a link copied); cleared by the user.
    const std::string& notice() const { return notice_; }
    void set_notice(std::string message) { notice_ = std::move(message); }
    void clear_notice() { notice_.clear(); }
    // The keys changed since the scene was loaded, as `--set` takes them (what a link carries).
    ChangedKeys changed_keys() const { return softbody::changed_keys(lesson_, world_->def()); }

    // The inspector: one particle's forces, equation by equation, or one rigid body's.
    void inspect(const Inspected& what);
    void stop_inspecting() { inspected_.reset(); }
    std::optional<ParticleInspection> particle_inspection() const;
    std::optional<RigidInspection> rigid_inspection() const;

private:
    void after_load(const Scene& scene);
    void after_travel();
    void after_structure_change();
    void tick_once();
    void changed();  // the user changed the world: in the past, the recorded future is dropped
    void note_collision();
    void sample_energy();
    WorldSettings compared_settings(const CompareSetup& setup, WorldSettings settings) const;
    bool build_compared();
    std::string unique_name(const std::string& stem) const;

    std::unique_ptr<World> world_;
    Scene lesson_;  // the scene loaded: its title, text and closed form (the world keeps the rest)
    FixedClock clock_;
    History history_;
    std::vector<ComparedWorld> compared_;
    EnergyRecord energy_;
    std::optional<LastCollision> last_collision_;
    std::optional<Inspected> inspected_;
    std::string error_, notice_, source_;
    std::size_t selected_body_ = 0;
    int ticks_last_frame_ = 0;
    std::uint64_t loads_ = 0;
    double physics_ms_per_tick_ = 0.0;
};

}  // namespace softbody::app

// The interactive session: the world being simulated, the fixed-tick clock that advances it,
// the view of it (camera, overlays), the mouse's grab, the energy history and the last error.
// No GLFW and no ImGui in here: the window and the panels drive it.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "physics/clock.h"
#include "physics/history.h"
#include "physics/inspect.h"
#include "physics/keys.h"
#include "physics/scene_io.h"
#include "physics/world.h"
#include "render/frame.h"

namespace softbody::app {

struct EnergySample {
    double time, kinetic, gravity, elastic, total;
    double rotational;        // the rigid bodies' part of the kinetic energy
    double angular_momentum;  // |L| about the origin, every body
    double contacts;          // what the rigid contacts did in the last second (J; < 0: took)
    std::vector<double> compared;  // each compared world's total (Demo::compared()), in order
};

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
    glm::vec3 offset{0.0f};  // where it is drawn, from the main world, m
    glm::vec3 color{0.5f};   // sRGB
};
// Each integrator's colour in the comparison (the main world's too).
glm::vec3 integrator_color(Integrator integrator);

// The hardest hit of the latest tick that had one: Eq. 38 term by term for its main point.
struct LastCollision {
    double time = 0.0;           // s
    std::string body_1, body_2;  // names: a rigid body, a soft body's particle, or the ground
    std::size_t points = 1;      // how many points that pair of bodies touched at
    ImpulseTerms terms;
};

// What the mouse is over: a particle of a soft body, or a point on a rigid body.
struct Pick {
    bool rigid = false;
    std::uint32_t body = 0;      // soft or rigid body index
    std::uint32_t particle = 0;  // soft
    Vec3d point;                 // rigid: body axes from the centre of mass
    float depth = 0.0f;          // along the view, m: the nearest pick wins
};

class Demo {
public:
    // Builds the first world; throws InputError when it cannot (the caller has nothing to show).
    explicit Demo(const Scene& scene);

    // --- Loading: never throws; on failure the current world stays and error() says why ----
    bool load(const Scene& scene);             // a whole new scene
    bool load_scene_file(const std::string& path);
    bool load_mesh_file(const std::string& path);
    bool save_preset(const std::string& path, bool overwrite);  // false + error() on failure
    void reset();

    // Key edits from the UI: keys that apply at once do so now, the others at reset (keys.h),
    // through the world's own setters (the compared copies follow). A bad value is shown as
    // the error, never thrown.
    void edit_settings(const WorldSettings& settings);
    // The soft body the Parameters panel edits (clicking a soft body selects it).
    std::size_t selected_body() const { return selected_body_ < world_->soft_body_count() ? selected_body_ : 0; }
    void select_body(std::size_t body) { selected_body_ = body; }
    void edit_body(std::size_t body, const SoftBodyDef& def);
    void edit_rigid_body(std::size_t index, const RigidBodyDef& def);
    // One key as --set takes it: "dt", "stiffness" (every soft body's), NAME.KEY for a named
    // body or spring.
    void set_key(const std::string& key, const std::string& value);

    // The Add menu: a body dropped above the scene where the camera looks, made in the running
    // world (the others keep their motion). False and error() when it cannot be made.
    enum class AddKind { SoftBall, SoftCube, RigidBox, RigidBall, MeshFile };
    bool add_body(AddKind kind, const std::string& mesh = {});
    // Takes a body out of the world (and the springs attached to it). Time travel goes back
    // across it.
    bool remove_body(bool rigid, std::size_t index);

    // The scene as it stands: what a preset saves (every key and body now, the lesson's words).
    Scene scene() const;
    bool reset_pending() const;  // a key that applies at reset differs from what the world was built with

    // --- Time ----------------------------------------------------------------------------------
    // Feeds elapsed wall time (times time_scale) to the clock and runs the whole ticks due.
    void advance(double wall_seconds);
    void single_tick();  // in the past: the next recorded tick
    bool paused = false;
    double time_scale = 1.0;
    int max_ticks_per_frame = 8;
    std::function<void(const World&)> on_tick;  // after every tick (the Lesson panel measures)

    // --- Time travel: the last 1,000 ticks (20 s) are kept (physics/history.h) ------------------
    // Going to a recorded tick pauses there; play goes on from it (replaying what was recorded,
    // then live). A change made in the past (a key, a grab, a pin) drops the recorded future.
    void go_to_tick(std::uint64_t tick);
    void step_back() { go_to_tick(world_->ticks() == 0 ? 0 : world_->ticks() - 1); }
    void rewind(double seconds);  // back this long (as far as the record goes)
    const History& history() const { return history_; }
    bool in_past() const { return history_.in_past(*world_); }

    // --- Comparing integrators --------------------------------------------------------------
    // Starts the scene again from t = 0 beside one to three copies of it, each with its own
    // integrator and substeps, ticked in lockstep with the main world (the mouse's grab acts
    // on the main world alone; keys, pins, resets and the timeline act on all). Drawn side by
    // side (or overlaid) in each integrator's colour. Empty: back to one world. False and
    // error() when a copy cannot be made.
    bool compare(const std::vector<CompareSetup>& others);
    const std::vector<ComparedWorld>& compared() const { return compared_; }
    bool comparing() const { return !compared_.empty(); }
    bool compare_overlaid = false;  // draw the copies over the main world instead of beside it

    // --- What the panels show ------------------------------------------------------------------
    World& world() { return *world_; }
    const World& world() const { return *world_; }
    int ticks_last_frame() const { return ticks_last_frame_; }
    double physics_ms_per_tick() const { return physics_ms_per_tick_; }
    const std::deque<EnergySample>& energy_history() const { return energy_; }
    double contact_work_last_second() const;  // J, World::contact_energy() over the last second's ticks
    const std::optional<LastCollision>& last_collision() const { return last_collision_; }
    const std::string& error() const { return error_; }
    void set_error(std::string message) { error_ = std::move(message); }
    void clear_error() { error_.clear(); }
    const std::string& source() const { return source_; }  // scene or mesh the world came from
    void set_source(std::string source) { source_ = std::move(source); }

    // --- View ----------------------------------------------------------------------------------
    render::Camera camera;
    render::Overlays overlays;
    render::Appearance appearance;
    // Camera follow: the view moves with the bodies' centre (every moving body's centre of mass,
    // weighted by mass), horizontally and smoothed, keeping them where the framing (or a pan)
    // put them in the view; it holds still while the mouse pulls a body. On by default for a
    // scene with one moving body (fixed bodies are scenery); the Display panel and T toggle it.
    bool follow = false;
    // Sleeping rigid bodies drawn dimmer (the Display panel): what the physics skips shows.
    bool dim_sleeping = true;
    void follow_bodies(double seconds);  // one frame's worth (Demo::advance calls it)
    void pan(float dx, float dy);        // the camera's pan, which a follow keeps
    // The view's shape: width / height, and the fraction of its width to move a framed body
    // right by (to centre it in the part the panels leave free). Set by the window each frame.
    void set_view(float aspect, float shift) {
        view_aspect_ = aspect;
        view_shift_ = shift;
    }
    // Points the camera at the body and the ground below it.
    void frame_body();
    render::Frame make_frame() const;

    // --- Mouse ---------------------------------------------------------------------------------
    // What is under pixel (x, y) of a width x height view: a soft body's particle drawn
    // nearest, within `radius` px, or the point of a rigid body's surface the ray meets first,
    // whichever is nearer the eye.
    std::optional<Pick> pick(float x, float y, float width, float height, float radius) const;
    void begin_grab(const Pick& pick, float x, float y, float width, float height);
    void drag(float x, float y, float width, float height);
    void end_grab();
    bool grabbing() const { return world_->grab().has_value(); }
    void toggle_pin(std::size_t body, std::uint32_t particle);

    // --- The inspector: one particle's forces, equation by equation, or one rigid body's ----
    void inspect(const Pick& pick);
    void inspect_particle(std::size_t body, std::uint32_t particle);
    void stop_inspecting();
    // What acts on the inspected particle now; empty when none is inspected (or it is gone).
    std::optional<ParticleInspection> particle_inspection() const;
    std::optional<RigidInspection> rigid_inspection() const;

private:
    void after_load(const Scene& scene);
    void run_due_ticks(double wall_seconds);
    void keep_framing_offset();  // the framing's place of the bodies in the view, for the follow
    void sample_energy();
    void note_collision();  // after each tick
    void tick_once();       // one tick, recorded or replayed
    void changed();         // the user changed the world: in the past, the recorded future is dropped
    void after_travel();    // the panels' records follow the world to its new moment
    WorldSettings compared_settings(const ComparedWorld& copy, WorldSettings settings) const;  // its integrator and substeps
    bool build_compared();  // the copies from the scene as it stands, at the main world's tick 0
    void after_keys();
    void after_structure_change();
    std::string unique_name(const std::string& stem) const;

    std::unique_ptr<World> world_;
    Scene lesson_;           // the scene loaded: its title, text and closed form (the world keeps the rest)
    FixedClock clock_;
    History history_;
    std::vector<ComparedWorld> compared_;
    std::string error_;
    std::string source_;
    std::deque<EnergySample> energy_;
    std::deque<std::pair<double, double>> contact_work_;  // (time, a tick's contact energy), the last second
    std::optional<LastCollision> last_collision_;
    std::optional<std::pair<std::size_t, std::uint32_t>> inspected_particle_;  // soft body, particle
    std::optional<std::size_t> inspected_rigid_;
    int ticks_last_frame_ = 0;
    double physics_ms_per_tick_ = 0.0;
    float grab_depth_ = 0.0f;
    std::size_t selected_body_ = 0;
    float view_aspect_ = 1.6f, view_shift_ = 0.0f;  // distance along the view direction of the grab plane
    // Where the camera's target sits from the bodies' centre, level: along the camera's right
    // and its level forward (m), so an orbit keeps the bodies where they are in the view.
    glm::vec2 follow_offset_{0.0f};
};

}  // namespace softbody::app

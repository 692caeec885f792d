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
#include "physics/inspect.h"
#include "physics/params.h"
#include "physics/scene_io.h"
#include "physics/world.h"
#include "render/frame.h"

namespace softbody::app {

struct EnergySample {
    double time, kinetic, gravity, elastic, total;
    double rotational;        // the rigid bodies' part of the kinetic energy
    double angular_momentum;  // |L| about the origin, every body
};

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

    // Parameter edits from the UI: live keys apply now, the others at reset (see params.h).
    void edit(const Params& params);
    const Params& params() const { return world_->params(); }
    // A rigid body's keys: restitution and friction apply now, the rest at reset.
    void edit_rigid_body(std::size_t index, const RigidBodyDef& def);
    const RigidBodyDef& rigid_body_def(std::size_t index) const { return scene_.rigid_bodies[index]; }
    // One key as --set takes it: a world or flat-body key, or NAME.KEY for a named body. Shows
    // what is wrong as the error instead of throwing.
    void set_key(const std::string& key, const std::string& value);
    // The scene as it stands: what a preset saves (the current params, every body).
    Scene scene() const;
    bool reset_pending() const;  // a key that applies at reset differs from what the world was built with

    // --- Time ----------------------------------------------------------------------------------
    // Feeds elapsed wall time (times time_scale) to the clock and runs the whole ticks due.
    void advance(double wall_seconds);
    void single_tick();
    bool paused = false;
    double time_scale = 1.0;
    int max_ticks_per_frame = 8;
    std::function<void(const World&)> on_tick;  // after every tick (the Lesson panel measures)

    // --- What the panels show ------------------------------------------------------------------
    World& world() { return *world_; }
    const World& world() const { return *world_; }
    int ticks_last_frame() const { return ticks_last_frame_; }
    double physics_ms_per_tick() const { return physics_ms_per_tick_; }
    const std::deque<EnergySample>& energy_history() const { return energy_; }
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
    bool follow = false;  // keep the camera's target over the centre of mass
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
    // What is under pixel (x, y) of a width x height view: the first soft body's particle drawn
    // nearest, within `radius` px, or the point of a rigid body's surface the ray meets first,
    // whichever is nearer the eye.
    std::optional<Pick> pick(float x, float y, float width, float height, float radius) const;
    void begin_grab(const Pick& pick, float x, float y, float width, float height);
    void drag(float x, float y, float width, float height);
    void end_grab();
    bool grabbing() const { return world_->grab().has_value(); }
    void toggle_pin(std::uint32_t particle);

    // --- The inspector: one particle's forces, equation by equation, or one rigid body's ----
    void inspect(const Pick& pick);
    void inspect_particle(std::size_t body, std::uint32_t particle);
    void stop_inspecting();
    // What acts on the inspected particle now; empty when none is inspected (or it is gone).
    std::optional<ParticleInspection> particle_inspection() const;
    std::optional<RigidInspection> rigid_inspection() const;

private:
    void after_load(const Scene& scene);
    void sample_energy();
    void note_collision();  // after each tick

    std::unique_ptr<World> world_;
    Scene scene_;            // what the current world was built from (its params kept by the world)
    std::vector<RigidBodyDef> built_rigid_bodies_;  // the rigid bodies as the world was built
    FixedClock clock_;
    std::string error_;
    std::string source_;
    std::deque<EnergySample> energy_;
    std::optional<LastCollision> last_collision_;
    std::optional<std::pair<std::size_t, std::uint32_t>> inspected_particle_;  // soft body, particle
    std::optional<std::size_t> inspected_rigid_;
    int ticks_last_frame_ = 0;
    double physics_ms_per_tick_ = 0.0;
    float grab_depth_ = 0.0f;
    float view_aspect_ = 1.6f, view_shift_ = 0.0f;  // distance along the view direction of the grab plane
};

}  // namespace softbody::app

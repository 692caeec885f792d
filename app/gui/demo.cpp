#include "gui/demo.h"

#include "body_view.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>

#include "physics/error.h"
#include "physics/mesh.h"
#include "physics/scene_io.h"

namespace softbody::app {

namespace {

constexpr std::size_t kEnergySamples = 600;  // about ten seconds at 60 frames a second

// The ray under pixel (x, y): origin on the near plane, unit direction.
void mouse_ray(const render::Camera& camera, float x, float y, float width, float height, glm::vec3& origin,
               glm::vec3& direction) {
    const glm::mat4 inverse = glm::inverse(camera.projection(width / height) * camera.view());
    const float nx = 2.0f * x / width - 1.0f, ny = 1.0f - 2.0f * y / height;
    glm::vec4 near = inverse * glm::vec4(nx, ny, -1.0f, 1.0f), far = inverse * glm::vec4(nx, ny, 1.0f, 1.0f);
    near /= near.w;
    far /= far.w;
    origin = glm::vec3(near);
    direction = glm::normalize(glm::vec3(far) - glm::vec3(near));
}

// The camera's follow (Demo::follow_bodies): how long the view takes to catch up with the
// bodies, as the time constant of an exponential approach. Long enough that a bounce or a
// wobble does not shake the view, short enough that a rolling body stays in it (0.4 s behind
// at 1 m/s is 0.4 m).
constexpr double kFollowSeconds = 0.4;

// The centre of every body that moves (soft bodies and rigid bodies that are not fixed), each
// weighted by its mass; empty when nothing moves.
std::optional<glm::vec3> moving_centre(const World& world) {
    glm::dvec3 sum(0.0);
    double mass = 0.0;
    for (std::size_t b = 0; b < world.soft_body_count(); ++b) {
        const SoftBody& body = world.soft_body(b);
        const std::size_t n = body.particle_count();
        if (n == 0) continue;
        glm::dvec3 c(0.0);
        for (std::size_t i = 0; i < n; ++i) c += glm::dvec3(body.x.x[i], body.x.y[i], body.x.z[i]);
        const double m = double(body.mass) * double(n);
        sum += c / double(n) * m;
        mass += m;
    }
    for (std::size_t b = 0; b < world.rigid_body_count(); ++b) {
        if (world.rigid_body(b).fixed) continue;
        const Vec3d x = world.rigid_motion(b).x;
        sum += glm::dvec3(x.x, x.y, x.z) * world.rigid_body(b).mass;
        mass += world.rigid_body(b).mass;
    }
    if (!(mass > 0.0)) return std::nullopt;
    return glm::vec3(sum / mass);
}

std::size_t moving_body_count(const World& world) {
    std::size_t n = world.soft_body_count();
    for (std::size_t b = 0; b < world.rigid_body_count(); ++b) n += world.rigid_body(b).fixed ? 0 : 1;
    return n;
}

// The camera's level axes: its right, and its forward without the pitch.
void level_axes(const render::Camera& camera, glm::vec2& right, glm::vec2& forward) {
    const glm::vec3 r = camera.right();
    right = glm::normalize(glm::vec2(r.x, r.y));
    forward = glm::vec2(-right.y, right.x);  // z x right: the forward direction, level
}

}  // namespace

Demo::Demo(const Scene& scene) : clock_(scene.settings.dt) {
    world_ = std::make_unique<World>(scene, WorldOptions{hardware_threads(), false});
    after_load(scene);
}

bool Demo::load(const Scene& scene) {
    try {
        auto world = std::make_unique<World>(scene, WorldOptions{hardware_threads(), false});
        world_ = std::move(world);
        after_load(scene);
        error_.clear();
        return true;
    } catch (const std::exception& e) {
        error_ = e.what();
        return false;
    }
}

void Demo::after_load(const Scene& scene) {
    lesson_ = scene;
    clock_ = FixedClock(scene.settings.dt, max_ticks_per_frame);
    energy_.clear();
    contact_work_.clear();
    last_collision_.reset();
    compared_.clear();  // a new scene: one world again
    selected_body_ = 0;
    stop_inspecting();
    match_ground(scene.settings, appearance);
    follow = moving_body_count(*world_) == 1;  // one body: the view goes where it goes
    frame_body();
    sample_energy();
    history_.start(*world_);
}

bool Demo::load_scene_file(const std::string& path) {
    try {
        const Scene scene = load_scene(path);
        if (!load(scene)) return false;
        source_ = path;
        return true;
    } catch (const std::exception& e) {
        error_ = e.what();
        return false;
    }
}

bool Demo::load_mesh_file(const std::string& path) {
    // The selected soft body takes the mesh (a scene without one gets a soft body of it).
    Scene scene = this->scene();
    if (scene.soft_bodies.empty()) {
        SoftBodyDef body;
        body.name = unique_name("body");
        scene.soft_bodies.push_back(body);
    }
    SoftBodyDef& body = scene.soft_bodies[std::min(selected_body(), scene.soft_bodies.size() - 1)];
    body.mesh = path;
    body.geometry.reset();
    body.pinned.clear();     // vertex numbers of another mesh mean nothing here
    fit_brought_mesh(body);  // sized and stood up: the last mesh's scale is not this one's
    if (!load(scene)) return false;
    source_ = path;
    return true;
}

Scene Demo::scene() const {
    Scene scene = lesson_;
    static_cast<WorldDef&>(scene) = world_->def();
    return scene;
}

bool Demo::save_preset(const std::string& path, bool overwrite) {
    try {
        save_scene(path, scene(), overwrite ? Overwrite::Yes : Overwrite::No);
        return true;
    } catch (const std::exception& e) {
        error_ = e.what();
        return false;
    }
}

void Demo::reset() {
    std::vector<CompareSetup> setups;
    for (const ComparedWorld& c : compared_) setups.push_back(c.setup);
    compared_.clear();  // made again below, once the main world is back at its start
    try {
        world_->reset();
    } catch (const std::exception& e) {
        error_ = e.what();
        return;
    }
    clock_.reset();
    energy_.clear();
    contact_work_.clear();
    last_collision_.reset();
    sample_energy();
    history_.start(*world_);
    if (setups.empty()) return;
    for (const CompareSetup& setup : setups) compared_.push_back(ComparedWorld{setup, nullptr, History{}, {}, {}});
    build_compared();
}

glm::vec3 integrator_color(Integrator integrator) {
    switch (integrator) {
        case Integrator::Verlet: return {0.93f, 0.45f, 0.24f};           // orange, the demo's own
        case Integrator::SymplecticEuler: return {0.24f, 0.52f, 0.86f};  // blue
        case Integrator::ExplicitEuler: return {0.66f, 0.36f, 0.84f};    // purple
        case Integrator::RK4: return {0.32f, 0.72f, 0.40f};              // green
    }
    return {0.5f, 0.5f, 0.5f};
}

bool Demo::compare(const std::vector<CompareSetup>& others) {
    if (others.size() > 3) {
        error_ = "compare: at most three integrators beside the main world's";
        return false;
    }
    compared_.clear();
    if (others.empty()) {  // back to one world, where it is
        frame_body();
        return true;
    }
    for (const CompareSetup& setup : others) compared_.push_back(ComparedWorld{setup, nullptr, History{}, {}, {}});
    reset();  // the main world from t = 0, and the copies built beside it
    return compared_.size() == others.size();
}

WorldSettings Demo::compared_settings(const ComparedWorld& copy, WorldSettings settings) const {
    settings.integrator = copy.setup.integrator;
    settings.auto_substeps = copy.setup.auto_substeps;
    if (!copy.setup.auto_substeps) settings.substeps = copy.setup.substeps;
    return settings;
}

bool Demo::build_compared() {
    const Scene base = scene();
    // Side by side across the view, each a few body sizes from the last.
    const WorldBounds bounds = world_bounds(*world_);
    const float spacing = 3.5f * std::max(bounds.radius, 0.3f);
    glm::vec3 across = glm::cross(camera.forward(), glm::vec3(0.0f, 0.0f, 1.0f));
    across.z = 0.0f;
    across = glm::length(across) > 1e-3f ? glm::normalize(across) : glm::vec3(1.0f, 0.0f, 0.0f);
    try {
        for (std::size_t k = 0; k < compared_.size(); ++k) {
            ComparedWorld& c = compared_[k];
            Scene scene = base;
            scene.settings = compared_settings(c, base.settings);
            c.world = std::make_unique<World>(scene, WorldOptions{hardware_threads(), false});
            c.history.start(*c.world);
            c.offset = across * (spacing * float(k + 1));
            c.color = integrator_color(c.setup.integrator);
        }
    } catch (const std::exception& e) {
        compared_.clear();
        error_ = std::string("compare: ") + e.what();
        return false;
    }
    energy_.clear();
    contact_work_.clear();
    sample_energy();
    frame_body();
    return true;
}

void Demo::edit_settings(const WorldSettings& settings) {
    try {
        if (!(settings == world_->settings())) changed();
        world_->set_settings(settings);
        for (ComparedWorld& c : compared_) c.world->set_settings(compared_settings(c, settings));
        after_keys();
    } catch (const std::exception& e) {
        error_ = e.what();
    }
}

void Demo::edit_rigid_body(std::size_t index, const RigidBodyDef& def) {
    if (index >= world_->rigid_body_count()) return;
    try {
        const RigidBodyId id = world_->rigid_body_id(index);
        if (!(def == world_->def(id))) changed();
        world_->set_def(id, def);
        for (ComparedWorld& c : compared_) c.world->set_def(c.world->rigid_body_id(index), def);
    } catch (const std::exception& e) {
        error_ = e.what();
    }
}

void Demo::edit_body(std::size_t body, const SoftBodyDef& def) {
    if (body >= world_->soft_body_count()) return;
    try {
        const SoftBodyId id = world_->soft_body_id(body);
        if (!(def == world_->def(id))) changed();
        world_->set_def(id, def);
        for (ComparedWorld& c : compared_) c.world->set_def(c.world->soft_body_id(body), def);
    } catch (const std::exception& e) {
        error_ = e.what();
    }
}

std::string Demo::unique_name(const std::string& stem) const {
    const std::vector<std::string> taken = names(world_->def());
    if (std::find(taken.begin(), taken.end(), stem) == taken.end()) return stem;
    for (int n = 2;; ++n) {
        const std::string name = stem + std::to_string(n);
        if (std::find(taken.begin(), taken.end(), name) == taken.end()) return name;
    }
}

bool Demo::add_body(AddKind kind, const std::string& mesh) {
    // Above the scene where the camera looks: over its target, clear of the highest body.
    const WorldBounds bounds = world_bounds(*world_);
    const float top = world_->soft_body_count() + world_->rigid_body_count() > 0 ? bounds.centre.z + bounds.radius : 0.0f;
    const float size = 0.5f;
    const WorldSettings& settings = world_->settings();
    const Vec3 at{camera.target.x, camera.target.y, std::max(top, settings.ground ? settings.ground_height : 0.0f) + size + 0.3f};
    // Made in the running world (and in each compared copy), the others going on from where they are.
    try {
        changed();
        if (kind == AddKind::RigidBox || kind == AddKind::RigidBall) {
            RigidBodyDef def;
            def.name = unique_name(kind == AddKind::RigidBox ? "box1" : "ball1");
            def.shape = kind == AddKind::RigidBox ? ShapeKind::Box : ShapeKind::Sphere;
            if (def.shape == ShapeKind::Box) def.size = Vec3d{size, size, size};
            else def.radius = 0.5 * size;
            def.density = 150.0;
            def.position = Vec3d(at);
            world_->create_rigid_body(def);
            for (ComparedWorld& c : compared_) c.world->create_rigid_body(def);
        } else {
            SoftBodyDef body;
            body.name = unique_name(kind == AddKind::SoftBall ? "jelly_ball1" : kind == AddKind::SoftCube ? "jelly_cube1" : "mesh1");
            body.mesh = kind == AddKind::SoftBall ? "ball:2" : kind == AddKind::SoftCube ? "cube:4" : mesh;
            if (kind == AddKind::MeshFile) fit_brought_mesh(body);  // sized and stood up, as a dropped file is
            else {
                body.scale = size;
                body.up_axis = "z";
            }
            body.particle_mass = 0.05f;
            body.stiffness = 60.0f;
            body.damping = 1.5f;
            body.position = at;
            const SoftBodyId id = world_->create_soft_body(body);
            body.geometry = world_->def(id).geometry;  // loaded once
            for (ComparedWorld& c : compared_) c.world->create_soft_body(body);
        }
    } catch (const std::exception& e) {
        error_ = e.what();
        return false;
    }
    after_structure_change();
    return true;
}

bool Demo::remove_body(bool rigid, std::size_t index) {
    try {
        changed();
        if (rigid) {
            if (index >= world_->rigid_body_count()) return false;
            for (ComparedWorld& c : compared_) c.world->destroy(c.world->rigid_body_id(index));
            world_->destroy(world_->rigid_body_id(index));
        } else {
            if (index >= world_->soft_body_count()) return false;
            for (ComparedWorld& c : compared_) c.world->destroy(c.world->soft_body_id(index));
            world_->destroy(world_->soft_body_id(index));
        }
    } catch (const std::exception& e) {
        error_ = e.what();
        return false;
    }
    after_structure_change();
    return true;
}

// Something was made or unmade: a keyframe there (time travel goes back across it), and what
// the panels held about the bodies starts again.
void Demo::after_structure_change() {
    history_.keyframe_now(*world_);
    for (ComparedWorld& c : compared_) c.history.keyframe_now(*c.world);
    last_collision_.reset();
    stop_inspecting();
    if (selected_body_ >= world_->soft_body_count()) selected_body_ = 0;
    error_.clear();
}

void Demo::set_key(const std::string& key, const std::string& value) {
    try {
        // Checked on a copy of the definition first, so a bad value changes nothing and a good
        // one drops the recorded future only when it changes something.
        WorldDef def = world_->def();
        const ThingNames names = thing_names(def);
        const std::vector<KeyTarget> targets = resolve_key(key, names);
        const KeyValue v = parse_key_text(targets.front(), names, value);
        bool differs = false;
        for (const KeyTarget& t : targets) differs = differs || !(get_key(def, t) == v);
        if (differs) changed();
        world_->set_key(key, v);
        // The compared copies keep their own integrator and substeps.
        const bool own = targets.front().owner == KeyOwner::World &&
                         (key == "integrator" || key == "auto_substeps" || key == "substeps");
        if (!own) {
            for (ComparedWorld& c : compared_) c.world->set_key(key, v);
        }
        after_keys();
    } catch (const std::exception& e) {
        error_ = e.what();
    }
}

// What follows the world's keys outside it: the clock's tick and the ground as drawn.
void Demo::after_keys() {
    clock_.set_dt(world_->settings().dt);
    match_ground(world_->settings(), appearance);
}

bool Demo::reset_pending() const { return world_->reset_pending(); }

void Demo::advance(double wall_seconds) {
    run_due_ticks(wall_seconds);
    follow_bodies(wall_seconds);  // paused too: the view still catches up (after a step back, say)
}

void Demo::run_due_ticks(double wall_seconds) {
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

// The target approaches the bodies' centre plus the offset the framing gave it, level, with
// the time constant kFollowSeconds: 1 - exp(-t / tau) of the way each frame, which is the same
// motion whatever the frame rate. Its height is left alone, so the ground stays where it is in
// the view while a body bounces. While the mouse pulls a body the camera holds still: moving
// it would move the point the body is pulled toward, and the body after it.
void Demo::follow_bodies(double seconds) {
    if (!follow || grabbing() || !(seconds > 0.0)) return;
    const std::optional<glm::vec3> centre = moving_centre(*world_);
    if (!centre) return;
    glm::vec2 right, forward;
    level_axes(camera, right, forward);
    const glm::vec2 wanted = glm::vec2(*centre) + right * follow_offset_.x + forward * follow_offset_.y;
    const float a = float(1.0 - std::exp(-seconds / kFollowSeconds));
    const glm::vec2 now = glm::vec2(camera.target) + (wanted - glm::vec2(camera.target)) * a;
    camera.target.x = now.x;
    camera.target.y = now.y;
}

void Demo::pan(float dx, float dy) {
    const glm::vec3 before = camera.target;
    camera.pan(dx, dy);
    // Following, the pan moves where the bodies sit in the view, and the follow keeps that.
    glm::vec2 right, forward;
    level_axes(camera, right, forward);
    const glm::vec2 moved(camera.target - before);
    follow_offset_ += glm::vec2(glm::dot(moved, right), glm::dot(moved, forward));
}

void Demo::keep_framing_offset() {
    const std::optional<glm::vec3> centre = moving_centre(*world_);
    if (!centre) return;
    glm::vec2 right, forward;
    level_axes(camera, right, forward);
    const glm::vec2 d = glm::vec2(camera.target) - glm::vec2(*centre);
    follow_offset_ = {glm::dot(d, right), glm::dot(d, forward)};
}

void Demo::single_tick() {
    if (world_->status() != Status::Ok) return;
    tick_once();
    ticks_last_frame_ = 1;
    if (world_->status() != Status::Ok) error_ = world_->divergence();
    sample_energy();
}

void Demo::tick_once() {
    const bool replaying = history_.in_past(*world_);
    history_.before_tick(*world_);
    world_->tick();
    history_.after_tick(*world_);
    if (on_tick) on_tick(*world_);
    // What the contacts did, kept for a second: the energy panel's "contacts" line.
    contact_work_.emplace_back(world_->time(), world_->contact_energy().total);
    while (!contact_work_.empty() && contact_work_.front().first <= world_->time() - 1.0 + 1e-9) contact_work_.pop_front();
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

void Demo::changed() {
    history_.branch(*world_);
    for (ComparedWorld& c : compared_) c.history.branch(*c.world);
}

void Demo::go_to_tick(std::uint64_t tick) {
    paused = true;
    history_.go_to(*world_, tick);
    for (ComparedWorld& c : compared_) c.history.go_to(*c.world, tick);
    // The energy plot and the last collision come back with the world; the plot is cut at now.
    while (!energy_.empty() && energy_.back().time >= world_->time()) energy_.pop_back();
    while (!contact_work_.empty() && contact_work_.back().first > world_->time()) contact_work_.pop_back();
    sample_energy();
    last_collision_.reset();
    clock_.reset();
    after_travel();
    if (world_->status() == Status::Ok) error_.clear();  // back before it diverged
    else error_ = world_->divergence();
}

void Demo::rewind(double seconds) {
    const double dt = double(world_->settings().dt);
    const auto back = static_cast<std::uint64_t>(std::llround(std::max(0.0, seconds) / dt));
    go_to_tick(world_->ticks() > back ? world_->ticks() - back : 0);
}

// A replayed tick may bring back keys of that moment, and a keyframe what the world held: the
// clock's dt and the ground follow, and a selection of a body no longer there is dropped.
void Demo::after_travel() {
    after_keys();
    if (selected_body_ >= world_->soft_body_count()) selected_body_ = 0;
}

// A collision, not resting contact: a point closing faster than two steps of gravity (and at
// least 1 cm/s, for a world without gravity). The one with the largest impulse is kept.
void Demo::note_collision() {
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

double Demo::contact_work_last_second() const {
    double sum = 0.0;
    for (const auto& [time, work] : contact_work_) sum += work;
    return sum;
}

void Demo::sample_energy() {
    const Energy e = world_->energy();
    std::vector<double> compared;
    for (ComparedWorld& c : compared_) compared.push_back(c.world->energy().total());
    energy_.push_back({world_->time(), e.kinetic, e.gravity, e.elastic, e.total(), e.rotational,
                       length(world_->angular_momentum()), contact_work_last_second(), std::move(compared)});
    while (energy_.size() > kEnergySamples) energy_.pop_front();
}

void Demo::frame_body() {
    const float aspect = view_aspect_, shift = view_shift_;
    // Frame the bodies and the ground below them, so the whole fall is in view.
    WorldBounds bounds = world_bounds(*world_);
    if (comparing() && !compare_overlaid) {
        // The copies beside it too: the sphere around all of them.
        glm::vec3 low = bounds.centre - bounds.radius, high = bounds.centre + bounds.radius;
        for (const ComparedWorld& c : compared_) {
            low = glm::min(low, bounds.centre + c.offset - bounds.radius);
            high = glm::max(high, bounds.centre + c.offset + bounds.radius);
        }
        bounds.centre = 0.5f * (low + high);
        bounds.radius = 0.5f * glm::length(high - low);
    }
    const glm::vec3 com = bounds.centre;
    const float radius = std::max(bounds.radius, 0.25f);
    const float ground = world_->settings().ground_height;
    const float bottom = world_->settings().ground ? std::min(ground, com.z - radius) : com.z - radius;
    const float top = com.z + radius;
    const glm::vec3 centre{com.x, com.y, 0.5f * (top + bottom)};
    camera.frame(centre, std::max(0.5f * (top - bottom), radius) * 1.15f, aspect * (1.0f - 2.0f * shift));
    const float view_width = 2.0f * camera.distance * std::tan(0.5f * camera.fov_y) * aspect;
    camera.pan(-shift * view_width, 0.0f);
    keep_framing_offset();
}

void Demo::inspect(const Pick& pick) {
    if (pick.rigid) {
        inspected_particle_.reset();
        inspected_rigid_ = pick.body;
    } else {
        inspect_particle(pick.body, pick.particle);
        selected_body_ = pick.body;
    }
}

void Demo::inspect_particle(std::size_t body, std::uint32_t particle) {
    inspected_rigid_.reset();
    inspected_particle_ = {body, particle};
}

void Demo::stop_inspecting() {
    inspected_particle_.reset();
    inspected_rigid_.reset();
}

std::optional<ParticleInspection> Demo::particle_inspection() const {
    if (!inspected_particle_) return std::nullopt;
    const auto [body, particle] = *inspected_particle_;
    if (body >= world_->soft_body_count() || particle >= world_->soft_body(body).particle_count()) return std::nullopt;
    return softbody::inspect_particle(*world_, body, particle);
}

std::optional<RigidInspection> Demo::rigid_inspection() const {
    if (!inspected_rigid_ || *inspected_rigid_ >= world_->rigid_body_count()) return std::nullopt;
    return inspect_rigid(*world_, *inspected_rigid_);
}

namespace {

// The inspector's arrows: each force at its particle (or centre of mass), one colour per
// equation, the largest six tenths of the bodies' radius long.
glm::vec3 equation_color(const std::string& equation) {
    if (equation == "Listing 8" || equation == "Listing 9") return {0.20f, 0.55f, 0.95f};  // weight: blue
    if (equation == "Eq. 21") return {0.90f, 0.20f, 0.20f};                               // springs: red
    if (equation == "Eq. 22") return {0.95f, 0.60f, 0.10f};                               // dampers: orange
    if (equation == "Eq. 23") return {0.55f, 0.80f, 0.95f};                               // drag: sky
    if (equation == "Eq. 24" || equation == "Eq. 25") return {0.60f, 0.30f, 0.80f};       // friction: purple
    if (equation == "contact" || equation == "Eq. 37" || equation == "Eq. 38") return {0.20f, 0.70f, 0.35f};  // green
    return {0.45f, 0.45f, 0.45f};
}

}  // namespace

render::Frame Demo::make_frame() const {
    render::Frame frame;
    const World& w = *world_;
    world_view(w, paused || w.status() != Status::Ok ? 1.0f : static_cast<float>(clock_.alpha()), frame);
    if (dim_sleeping) {
        // Half way to a mid grey, and darker: still the body's own colour, but plainly resting.
        for (std::size_t b = 0; b < w.rigid_body_count(); ++b) {
            if (w.rigid_asleep(b)) frame.rigid_bodies[b].color = glm::mix(frame.rigid_bodies[b].color, glm::vec3(0.35f), 0.55f);
        }
    }
    frame.camera = camera;
    frame.overlays = overlays;
    frame.appearance = appearance;
    if (comparing()) {
        // Every world in its integrator's colour, the copies beside the main one (or over it).
        const float alpha = paused || w.status() != Status::Ok ? 1.0f : static_cast<float>(clock_.alpha());
        const glm::vec3 own = integrator_color(w.settings().integrator);
        for (render::BodyView& v : frame.soft_bodies) v.color = own;
        for (render::RigidBodyView& v : frame.rigid_bodies) {
            if (!v.fixed) v.color = own;
        }
        for (const ComparedWorld& c : compared_) {
            const glm::vec3 offset = compare_overlaid ? glm::vec3(0.0f) : c.offset;
            const World& copy = *c.world;
            const float a = copy.status() == Status::Ok ? alpha : 1.0f;
            for (std::size_t b = 0; b < copy.soft_body_count(); ++b) {
                render::BodyView v = soft_body_view(copy.soft_body(b), a);
                v.offset = offset;
                v.color = c.color;
                frame.soft_bodies.push_back(v);
            }
            for (std::size_t b = 0; b < copy.rigid_body_count(); ++b) {
                render::RigidBodyView v = rigid_body_view(copy, b, a);
                v.position += offset;
                v.previous_position += offset;
                if (!v.fixed) v.color = c.color;
                frame.rigid_bodies.push_back(v);
            }
        }
    }
    if (const auto& grab = w.grab()) {
        frame.overlays.grab = true;
        frame.overlays.grab_target = to_glm(grab->target);
        if (grab->rigid) {
            const RigidMotion m = w.rigid_motion(grab->body);
            frame.overlays.grab_on_rigid = true;
            frame.overlays.grab_point = to_glm(m.x + m.R * grab->point);
        } else {
            frame.overlays.grab_particle = grab->particle;
        }
    }
    const float size = std::max(world_bounds(w).radius, 0.05f);
    if (const auto in = particle_inspection()) {
        float largest = 0.0f;
        for (const ForceTerm& t : in->terms) largest = std::max(largest, length(t.force));
        for (const ForceTerm& t : in->terms) {
            if (largest > 0.0f && length(t.force) > 1e-3f * largest) {
                frame.arrows.push_back({to_glm(Vec3d(in->x)), to_glm(Vec3d(t.force)) * (0.6f * size / largest), equation_color(t.equation)});
            }
        }
        frame.arrows.push_back({to_glm(Vec3d(in->x)), glm::vec3(0.0f, 0.0f, 0.04f * size), glm::vec3(0.1f), 6.0f});  // the marker
    }
    if (const auto in = rigid_inspection()) {
        const Vec3d centre = w.rigid_motion(in->body).x;
        double largest = 0.0;
        for (const WrenchTerm& t : in->terms) largest = std::max(largest, length(t.force));
        for (const WrenchTerm& t : in->terms) {
            if (largest > 0.0 && length(t.force) > 1e-3 * largest) {
                frame.arrows.push_back({to_glm(centre), to_glm(t.force) * float(0.6 * size / largest), equation_color(t.equation)});
            }
        }
    }
    return frame;
}

namespace {

// Where a ray first meets a mesh's triangles (Moller-Trumbore), as a distance along it; none
// when it misses.
std::optional<float> ray_mesh(const Mesh& mesh, const glm::vec3& origin, const glm::vec3& direction) {
    std::optional<float> nearest;
    for (std::size_t k = 0; k + 2 < mesh.triangles.size(); k += 3) {
        const Vec3 a = mesh.positions[mesh.render_vertices[mesh.triangles[k]].particle];
        const Vec3 b = mesh.positions[mesh.render_vertices[mesh.triangles[k + 1]].particle];
        const Vec3 c = mesh.positions[mesh.render_vertices[mesh.triangles[k + 2]].particle];
        const glm::vec3 p0 = to_glm(a), e1 = to_glm(b) - p0, e2 = to_glm(c) - p0;
        const glm::vec3 h = glm::cross(direction, e2);
        const float det = glm::dot(e1, h);
        if (std::abs(det) < 1e-12f) continue;
        const glm::vec3 s = origin - p0;
        const float u = glm::dot(s, h) / det;
        if (u < 0.0f || u > 1.0f) continue;
        const glm::vec3 q = glm::cross(s, e1);
        const float v = glm::dot(direction, q) / det;
        if (v < 0.0f || u + v > 1.0f) continue;
        const float t = glm::dot(e2, q) / det;
        if (t > 0.0f && (!nearest || t < *nearest)) nearest = t;
    }
    return nearest;
}

}  // namespace

std::optional<Pick> Demo::pick(float x, float y, float width, float height, float radius) const {
    const glm::mat4 clip = camera.projection(width / height) * camera.view();
    std::optional<Pick> best;
    for (std::size_t b = 0; b < world_->soft_body_count(); ++b) {
        const auto& p = world_->soft_body(b).x;
        for (std::size_t i = 0; i < p.size(); ++i) {
            const glm::vec4 c = clip * glm::vec4(to_glm(p[i]), 1.0f);
            if (c.w <= 0.0f) continue;
            const float sx = (c.x / c.w * 0.5f + 0.5f) * width, sy = (0.5f - c.y / c.w * 0.5f) * height;
            const float d2 = (sx - x) * (sx - x) + (sy - y) * (sy - y);
            if (d2 > radius * radius) continue;
            // Within reach: the nearest to the eye wins (it is the one drawn in front).
            if (!best || c.w < best->depth) {
                best = Pick{false, static_cast<std::uint32_t>(b), static_cast<std::uint32_t>(i), {}, c.w};
            }
        }
    }
    // Rigid bodies: the ray against each body's own mesh, in its own axes.
    glm::vec3 origin, direction;
    mouse_ray(camera, x, y, width, height, origin, direction);
    for (std::size_t b = 0; b < world_->rigid_body_count(); ++b) {
        if (world_->rigid_body(b).fixed) continue;
        const glm::mat4 model = render::model_matrix(rigid_body_view(*world_, b));
        const glm::mat4 to_body = glm::inverse(model);
        const glm::vec3 o(to_body * glm::vec4(origin, 1.0f));
        const glm::vec3 d(to_body * glm::vec4(direction, 0.0f));
        const auto t = ray_mesh(world_->rigid_body(b).render_mesh, o, d);
        if (!t) continue;
        // The map to body axes is affine, so one distance t serves both rays.
        const glm::vec3 hit_world = origin + direction * *t;
        const glm::vec3 hit_body = o + d * *t;
        const float depth = glm::dot(hit_world - camera.eye(), camera.forward());
        if (!best || depth < best->depth) {
            best = Pick{true, static_cast<std::uint32_t>(b), 0, Vec3d{hit_body.x, hit_body.y, hit_body.z}, depth};
        }
    }
    return best;
}

void Demo::begin_grab(const Pick& pick, float x, float y, float width, float height) {
    Grab grab;
    glm::vec3 at;
    if (pick.rigid) {
        const RigidMotion m = world_->rigid_motion(pick.body);
        const Vec3d p = m.x + m.R * pick.point;
        at = to_glm(p);
        grab.rigid = true;
        grab.body = pick.body;
        grab.point = pick.point;
    } else {
        at = to_glm(world_->soft_body(pick.body).x[pick.particle]);
        grab.body = pick.body;
        grab.particle = pick.particle;
        selected_body_ = pick.body;  // the body grabbed is the body the Parameters panel edits
    }
    grab_depth_ = glm::dot(at - camera.eye(), camera.forward());
    grab.target = {at.x, at.y, at.z};
    changed();
    world_->set_grab(grab);
    drag(x, y, width, height);
}

void Demo::drag(float x, float y, float width, float height) {
    if (!world_->grab()) return;
    glm::vec3 origin, direction;
    mouse_ray(camera, x, y, width, height, origin, direction);
    // Where the ray meets the plane facing the camera at the grabbed particle's depth.
    const float along = glm::dot(direction, camera.forward());
    if (along <= 1e-4f) return;
    const float t = (grab_depth_ - glm::dot(origin - camera.eye(), camera.forward())) / along;
    const glm::vec3 target = origin + direction * t;
    Grab grab = *world_->grab();
    grab.target = {target.x, target.y, target.z};
    changed();
    world_->set_grab(grab);
}

void Demo::end_grab() {
    if (!world_->grab()) return;
    changed();
    world_->set_grab(std::nullopt);
}

void Demo::toggle_pin(std::size_t body, std::uint32_t particle) {
    if (body >= world_->soft_body_count() || particle >= world_->soft_body(body).particle_count()) return;
    // The world keeps a pin as a vertex number in the body's keys: it survives a reset and a
    // saved preset. A pin is part of the state, not of a tick's inputs: a keyframe here.
    const bool pin = !world_->soft_body(body).is_pinned(particle);
    changed();
    world_->set_pinned(body, particle, pin);
    history_.keyframe_now(*world_);
    for (ComparedWorld& c : compared_) {
        c.world->set_pinned(body, particle, pin);
        c.history.keyframe_now(*c.world);
    }
}

}  // namespace softbody::app

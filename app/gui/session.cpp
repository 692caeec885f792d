// The world the user shapes (session.h): loading, keys, bodies made and unmade, pins and grabs.
// Its time (the clock, time travel, the comparison) is session_time.cpp's.
#include "gui/session.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "physics/error.h"
#include "physics/generated.h"

namespace softbody::app {

Session::Session(const Scene& scene) : clock_(scene.settings.dt) {
    world_ = std::make_unique<World>(scene, WorldOptions{kDefaultThreads, false});
    after_load(scene);
}

bool Session::load(const Scene& scene) {
    try {
        auto world = std::make_unique<World>(scene, WorldOptions{kDefaultThreads, false});
        world_ = std::move(world);
        after_load(scene);
        error_.clear();
        return true;
    } catch (const std::exception& e) {
        error_ = e.what();
        return false;
    }
}

void Session::after_load(const Scene& scene) {
    ++loads_;
    lesson_ = scene;
    clock_ = FixedClock(scene.settings.dt, max_ticks_per_frame);
    energy_.clear();
    last_collision_.reset();
    compared_.clear();  // a new scene: one world again
    selected_body_ = 0;
    inspected_.reset();
    sample_energy();
    history_.start(*world_);
}

bool Session::load_scene_file(const std::string& path) {
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

bool Session::load_mesh_file(const std::string& path) {
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

bool Session::open_file(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char ch) { return char(std::tolower(ch)); });
    return extension == ".json" ? load_scene_file(path) : load_mesh_file(path);
}

Scene Session::scene() const {
    Scene scene = lesson_;
    static_cast<WorldDef&>(scene) = world_->def();
    return scene;
}

bool Session::save_preset(const std::string& path, bool overwrite) {
    try {
        save_scene(path, scene(), overwrite ? Overwrite::Yes : Overwrite::No);
        notice_ = "Saved " + path + " (open it with Presets > Load, or drop it on the window)";
        return true;
    } catch (const std::exception& e) {
        error_ = e.what();
        return false;
    }
}

void Session::reset() {
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
    last_collision_.reset();
    sample_energy();
    history_.start(*world_);
    if (setups.empty()) return;
    for (const CompareSetup& setup : setups) compared_.push_back(ComparedWorld{setup, nullptr, History{}});
    build_compared();
}

// --- Keys ---------------------------------------------------------------------------------

void Session::edit_settings(const WorldSettings& settings) {
    try {
        if (!(settings == world_->settings())) changed();
        world_->set_settings(settings);
        for (ComparedWorld& c : compared_) c.world->set_settings(compared_settings(c.setup, settings));
        clock_.set_dt(world_->settings().dt);
    } catch (const std::exception& e) {
        error_ = e.what();
    }
}

void Session::edit_rigid_body(std::size_t index, const RigidBodyDef& def) {
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

void Session::edit_body(std::size_t body, const SoftBodyDef& def) {
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

void Session::set_key(const std::string& key, const std::string& value) {
    try {
        // Read against the world as it is, so a bad value changes nothing, and a good one drops
        // the recorded future only when it changes something.
        const WorldDef def = world_->def();
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
        clock_.set_dt(world_->settings().dt);
    } catch (const std::exception& e) {
        error_ = e.what();
    }
}

// --- What is in the world -------------------------------------------------------------------

std::string Session::unique_name(const std::string& stem) const {
    const std::vector<std::string> taken = names(world_->def());
    if (std::find(taken.begin(), taken.end(), stem) == taken.end()) return stem;
    for (int n = 2;; ++n) {
        const std::string name = stem + std::to_string(n);
        if (std::find(taken.begin(), taken.end(), name) == taken.end()) return name;
    }
}

bool Session::add_body(AddKind kind, const Vec3& at, const std::string& mesh) {
    constexpr float kSize = 0.5f;  // m across
    try {
        changed();
        if (kind == AddKind::RigidBox || kind == AddKind::RigidBall) {
            RigidBodyDef def;
            def.name = unique_name(kind == AddKind::RigidBox ? "box1" : "ball1");
            def.shape = kind == AddKind::RigidBox ? ShapeKind::Box : ShapeKind::Sphere;
            if (def.shape == ShapeKind::Box) def.size = Vec3d{kSize, kSize, kSize};
            else def.radius = 0.5 * kSize;
            def.density = 150.0;
            def.position = Vec3d(at);
            world_->create_rigid_body(def);
            for (ComparedWorld& c : compared_) c.world->create_rigid_body(def);
        } else {
            SoftBodyDef body;
            body.name = unique_name(kind == AddKind::SoftBall ? "jelly_ball1" : kind == AddKind::SoftCube ? "jelly_cube1" : "mesh1");
            body.mesh = kind == AddKind::SoftBall ? "ball:2" : kind == AddKind::SoftCube ? "cube:4" : mesh;
            if (kind == AddKind::MeshFile) {
                fit_brought_mesh(body);  // sized and stood up, as a dropped file is
            } else {
                body.scale = kSize;
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

bool Session::remove_body(bool rigid, std::size_t index) {
    if (index >= (rigid ? world_->rigid_body_count() : world_->soft_body_count())) return false;
    try {
        changed();
        if (rigid) {
            for (ComparedWorld& c : compared_) c.world->destroy(c.world->rigid_body_id(index));
            world_->destroy(world_->rigid_body_id(index));
        } else {
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
// the tools held about the bodies starts again.
void Session::after_structure_change() {
    history_.keyframe_now(*world_);
    for (ComparedWorld& c : compared_) c.history.keyframe_now(*c.world);
    last_collision_.reset();
    inspected_.reset();
    if (selected_body_ >= world_->soft_body_count()) selected_body_ = 0;
    error_.clear();
}

void Session::toggle_pin(std::size_t body, std::uint32_t particle) {
    if (body >= world_->soft_body_count() || particle >= world_->soft_body(body).particle_count()) return;
    // The world keeps a pin as a vertex number in the body's keys: it survives a reset and a
    // saved preset. A pin is part of the state, not of a tick's inputs: a keyframe here.
    const bool pin = !world_->soft_body(body).is_pinned(particle);
    world_->set_pinned(body, particle, pin);
    history_.keyframe_now(*world_);
    for (ComparedWorld& c : compared_) {
        c.world->set_pinned(body, particle, pin);
        c.history.keyframe_now(*c.world);
    }
}

void Session::set_grab(std::optional<Grab> grab) {
    changed();
    if (grab && !grab->rigid) selected_body_ = grab->body;  // the body grabbed is the body the Parameters tool edits
    world_->set_grab(grab);
}

// --- The inspector --------------------------------------------------------------------------

void Session::inspect(const Inspected& what) {
    inspected_ = what;
    if (!what.rigid) selected_body_ = what.body;
}

std::optional<ParticleInspection> Session::particle_inspection() const {
    if (!inspected_ || inspected_->rigid) return std::nullopt;
    const Inspected& in = *inspected_;
    if (in.body >= world_->soft_body_count() || in.particle >= world_->soft_body(in.body).particle_count()) return std::nullopt;
    return softbody::inspect_particle(*world_, in.body, in.particle);
}

std::optional<RigidInspection> Session::rigid_inspection() const {
    if (!inspected_ || !inspected_->rigid || inspected_->body >= world_->rigid_body_count()) return std::nullopt;
    return inspect_rigid(*world_, inspected_->body);
}

}  // namespace softbody::app

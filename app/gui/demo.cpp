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

glm::vec3 to_glm(const Vec3& v) { return {v.x, v.y, v.z}; }

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

}  // namespace

Demo::Demo(const Params& params) : clock_(params.dt) {
    world_ = std::make_unique<World>(params, load_mesh(params.mesh), WorldOptions{hardware_threads(), false});
    after_load(params);
}

bool Demo::load(const Params& params) {
    try {
        auto world = std::make_unique<World>(params, load_mesh(params.mesh), WorldOptions{hardware_threads(), false});
        world_ = std::move(world);
        after_load(params);
        error_.clear();
        return true;
    } catch (const std::exception& e) {
        error_ = e.what();
        return false;
    }
}

void Demo::after_load(const Params& params) {
    built_with_ = params;
    clock_ = FixedClock(params.dt, max_ticks_per_frame);
    energy_.clear();
    match_ground(params, appearance);
    frame_body();
    sample_energy();
}

bool Demo::load_scene_file(const std::string& path) {
    try {
        const Params params = load_scene(path);
        if (!load(params)) return false;
        source_ = path;
        return true;
    } catch (const std::exception& e) {
        error_ = e.what();
        return false;
    }
}

bool Demo::load_mesh_file(const std::string& path) {
    Params params = world_->params();
    params.mesh = path;
    params.pinned.clear();  // vertex numbers of another mesh mean nothing here
    if (!load(params)) return false;
    source_ = path;
    return true;
}

bool Demo::save_preset(const std::string& path, bool overwrite) {
    try {
        save_scene(path, world_->params(), overwrite ? Overwrite::Yes : Overwrite::No);
        return true;
    } catch (const std::exception& e) {
        error_ = e.what();
        return false;
    }
}

void Demo::reset() {
    world_->reset();
    built_with_ = world_->params();
    clock_.reset();
    energy_.clear();
    sample_energy();
}

void Demo::edit(const Params& params) {
    try {
        world_->set_params(params);
        clock_.set_dt(params.dt);
        match_ground(params, appearance);
    } catch (const std::exception& e) {
        error_ = e.what();
    }
}

bool Demo::reset_pending() const {
    const Params& now = world_->params();
    return now.scale != built_with_.scale || now.init_height != built_with_.init_height ||
           !(now.rotation == built_with_.rotation) ||
           !(now.initial_velocity == built_with_.initial_velocity) || now.pinned != built_with_.pinned;
}

void Demo::advance(double wall_seconds) {
    ticks_last_frame_ = 0;
    clock_.set_max_ticks_per_frame(max_ticks_per_frame);
    if (paused || world_->status() != Status::Ok) return;
    const int ticks = clock_.advance(wall_seconds * time_scale);
    if (ticks == 0) return;
    const auto start = std::chrono::steady_clock::now();
    for (int t = 0; t < ticks && world_->status() == Status::Ok; ++t) {
        world_->tick();
        ++ticks_last_frame_;
    }
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    physics_ms_per_tick_ = ms / std::max(1, ticks_last_frame_);
    if (world_->status() != Status::Ok) error_ = world_->divergence();
    if (follow) {
        const Vec3 com = world_->center_of_mass();
        camera.target.x = com.x;
        camera.target.y = com.y;
    }
    sample_energy();
}

void Demo::single_tick() {
    if (world_->status() != Status::Ok) return;
    world_->tick();
    ticks_last_frame_ = 1;
    if (world_->status() != Status::Ok) error_ = world_->divergence();
    sample_energy();
}

void Demo::sample_energy() {
    const Energy e = world_->energy();
    energy_.push_back({world_->time(), e.kinetic, e.gravity, e.elastic, e.total()});
    while (energy_.size() > kEnergySamples) energy_.pop_front();
}

void Demo::frame_body() {
    const float aspect = view_aspect_, shift = view_shift_;
    // Frame the body and the ground below it, so the whole fall is in view.
    const Vec3 com = world_->center_of_mass();
    float radius = 0.0f;
    const auto& x = world_->positions();
    for (std::size_t i = 0; i < world_->particle_count(); ++i) radius = std::max(radius, length(x[i] - com));
    radius = std::max(radius, 0.25f);
    const float ground = params().ground_height;
    const float bottom = params().ground ? std::min(ground, com.z - radius) : com.z - radius;
    const float top = com.z + radius;
    const glm::vec3 centre{com.x, com.y, 0.5f * (top + bottom)};
    camera.frame(centre, std::max(0.5f * (top - bottom), radius) * 1.15f, aspect * (1.0f - 2.0f * shift));
    const float view_width = 2.0f * camera.distance * std::tan(0.5f * camera.fov_y) * aspect;
    camera.pan(-shift * view_width, 0.0f);
}

render::Frame Demo::make_frame() const {
    render::Frame frame;
    const World& w = *world_;
    frame.body = body_view(w, paused || w.status() != Status::Ok ? 1.0f : static_cast<float>(clock_.alpha()));
    frame.camera = camera;
    frame.overlays = overlays;
    frame.appearance = appearance;
    if (const auto& grab = w.grab()) {
        frame.overlays.grab = true;
        frame.overlays.grab_particle = grab->particle;
        frame.overlays.grab_target = to_glm(grab->target);
    }
    return frame;
}

std::optional<std::uint32_t> Demo::pick(float x, float y, float width, float height, float radius) const {
    const glm::mat4 clip = camera.projection(width / height) * camera.view();
    const auto& p = world_->positions();
    std::optional<std::uint32_t> best;
    float best_depth = 0.0f;
    for (std::size_t i = 0; i < world_->particle_count(); ++i) {
        const glm::vec4 c = clip * glm::vec4(to_glm(p[i]), 1.0f);
        if (c.w <= 0.0f) continue;
        const float sx = (c.x / c.w * 0.5f + 0.5f) * width, sy = (0.5f - c.y / c.w * 0.5f) * height;
        const float d2 = (sx - x) * (sx - x) + (sy - y) * (sy - y);
        if (d2 > radius * radius) continue;
        // Within reach: the nearest to the eye wins (it is the one drawn in front).
        if (!best || c.w < best_depth) {
            best = static_cast<std::uint32_t>(i);
            best_depth = c.w;
        }
    }
    return best;
}

void Demo::begin_grab(std::uint32_t particle, float x, float y, float width, float height) {
    const glm::vec3 at = to_glm(world_->positions()[particle]);
    grab_depth_ = glm::dot(at - camera.eye(), camera.forward());
    world_->set_grab(Grab{particle, world_->positions()[particle], 0.0f, 0});
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
    world_->set_grab(grab);
}

void Demo::end_grab() { world_->set_grab(std::nullopt); }

void Demo::toggle_pin(std::uint32_t particle) {
    // Pins are kept as vertex numbers in the params, so they survive a reset and a saved preset.
    const bool pin = !world_->is_pinned(particle);
    Params params = world_->params();
    const auto& map = world_->mesh().vertex_to_particle;
    std::erase_if(params.pinned, [&](std::uint32_t v) { return map[v] == particle; });
    if (pin) {
        const auto vertex = std::find(map.begin(), map.end(), particle) - map.begin();
        params.pinned.push_back(static_cast<std::uint32_t>(vertex));
    }
    world_->set_params(params);
    built_with_.pinned = params.pinned;
    world_->set_pinned(particle, pin);
}

}  // namespace softbody::app

// The run's summary (app_shell.h): what a session ended with, as one JSON object for scripts
// and tests.
#include <cinttypes>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "gui/app_shell.h"
#include "gui/tools/lesson.h"
#include "physics/scene_io.h"
#include "world_json.h"

namespace softbody::app {

void AppShell::summarise() {
    // A recording still going when the app closes is finished, not lost.
    recorder.finish();
    if (std::string failure = recorder.take_error(); !failure.empty()) session->set_error(failure);

    // A summary for scripts and tests: what the session ended with.
    const World& world = session->world();
    const Vec3 com = world.center_of_mass();
    char hash[17];
    std::snprintf(hash, sizeof hash, "%016" PRIx64, world.state_hash());
    std::size_t particles = 0, pinned = 0;
    for (std::size_t b = 0; b < world.soft_body_count(); ++b) {
        particles += world.soft_body(b).particle_count();
        pinned += world.soft_body(b).def.pinned.size();
    }
    nlohmann::ordered_json out = {
        {"particles", particles}, {"ticks", world.ticks()},
        {"sim_time", world.time()},   {"com", {com.x, com.y, com.z}},       {"status", world.status() == Status::Ok ? "ok" : "diverged"},
        {"pinned", pinned}, {"error", session->error()}, {"state_hash", hash},
        {"soft_bodies", soft_bodies_json(world)},
        {"rigid_bodies", rigid_bodies_json(world)},
        {"scene", nlohmann::json::parse(scene_to_json(session->scene()))},
    };
    // The integrator comparison: each world's integrator, substeps and total energy now.
    if (session->comparing()) {
        const auto entry = [](World& w) {
            char h[17];
            std::snprintf(h, sizeof h, "%016" PRIx64, w.state_hash());
            return nlohmann::ordered_json{{"integrator", std::string(to_string(w.settings().integrator))}, {"substeps", w.substeps_in_use()},
                                          {"ticks", w.ticks()}, {"status", w.status() == Status::Ok ? "ok" : "diverged"},
                                          {"total_energy", w.energy().total()}, {"state_hash", h}};
        };
        nlohmann::ordered_json worlds = nlohmann::ordered_json::array();
        worlds.push_back(entry(session->world()));
        for (const ComparedWorld& c : session->compared()) worlds.push_back(entry(*c.world));
        out["compared"] = worlds;
    }
    // The view: whether the camera follows the bodies, and where it looks now.
    constexpr double kDegrees = 180.0 / 3.14159265358979323846;
    out["camera"] = {{"follow", view.follow},
                     {"target", {view.camera.target.x, view.camera.target.y, view.camera.target.z}},
                     {"yaw", view.camera.yaw * kDegrees},
                     {"pitch", view.camera.pitch * kDegrees}};
    out["tools"] = panels.tool_reports();
    // The timeline: what the record holds.
    const History& history = session->history();
    out["history"] = {{"oldest_tick", history.oldest_tick()}, {"newest_tick", history.newest_tick()},
                      {"keyframes", history.keyframe_count()}, {"bytes", history.bytes()}, {"in_past", session->in_past()}};
    // The inspector's read-out, as the panel shows it.
    if (const auto in = session->particle_inspection()) {
        nlohmann::ordered_json terms = nlohmann::ordered_json::array();
        for (const ForceTerm& t : in->terms) {
            terms.push_back({{"name", t.name}, {"equation", t.equation}, {"force", {t.force.x, t.force.y, t.force.z}},
                             {"detail", t.detail}});
        }
        out["inspection"] = {{"particle", in->particle}, {"x", {in->x.x, in->x.y, in->x.z}}, {"v", {in->v.x, in->v.y, in->v.z}},
                             {"terms", terms}, {"net", {in->net.x, in->net.y, in->net.z}}, {"on_ground", in->on_ground}};
    }
    if (LessonTool* tool = panels.lesson()) {
        if (auto lesson = tool->summary(*session); !lesson.is_null()) out["lesson"] = std::move(lesson);
    }
    if (const auto& recording = recorder.last()) {
        out["recording"] = {{"path", recording->path}, {"video", recording->video}, {"frames", recording->frames},
                            {"message", recording->message}};
    }
    // Resident now and at its peak, after the warm-up and at the end: flat means the ends agree.
    const ResidentMemory end = resident_memory();
    out["memory_kib"] = {{"after_warmup", after_warmup.now_kib}, {"peak_after_warmup", after_warmup.peak_kib},
                         {"end", end.now_kib},                   {"peak", end.peak_kib}};
    // A file name need not be UTF-8: its odd bytes are replaced in the summary, not fatal.
    std::cout << out.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) << std::endl;
}

}  // namespace softbody::app

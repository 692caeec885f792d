#include "gui/panels.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "cli.h"
#include "gui/bindings.h"
#include "gui/demo.h"
#include "gui/key_widgets.h"
#include "gui/recorder.h"
#include "physics/pair_forces.h"
#include "physics/rigid_body.h"
#include "physics/scene_io.h"

namespace softbody::app {

namespace {

namespace fs = std::filesystem;

std::vector<std::string> list_files(const std::string& folder, std::initializer_list<const char*> extensions) {
    std::vector<std::string> files;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(folder, ec)) {
        const std::string ext = entry.path().extension().string();
        for (const char* wanted : extensions) {
            if (ext == wanted) files.push_back(entry.path().string());
        }
    }
    std::sort(files.begin(), files.end());
    return files;
}

std::string presets_folder() {
    const char* data = std::getenv("XDG_DATA_HOME");
    const char* home = std::getenv("HOME");
    if (data && *data) return std::string(data) + "/softbody/presets";
    if (home && *home) return std::string(home) + "/.local/share/softbody/presets";
    return "presets";
}

std::string memory_text(std::size_t n) {
    // State: x, x_prev, v, rest, forces, four stage accelerations and scratch: about 30 floats a
    // particle; and what the fast kernel keeps (its packed state and per-tile partial forces).
    const double bytes = double(n) * 30.0 * 4.0 + double(PairForceKernel::memory_bytes(n));
    char text[64];
    std::snprintf(text, sizeof text, "%.1f MB", bytes / 1e6);
    return text;
}

}  // namespace

Panels::Panels(float ui_scale) : scale_(ui_scale) {
    scenes_ = list_files(assets_dir() + "/scenes", {".json"});
    meshes_ = list_files(assets_dir() + "/meshes", {".obj", ".off"});
    std::snprintf(preset_path_, sizeof preset_path_, "%s/my_scene.json", presets_folder().c_str());
}

void Panels::draw(Demo& demo, float fps) {
    error_banner(demo);
    if (show_help) help();
    if (!show_panels) return;
    const ImGuiViewport* viewport = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(viewport->WorkPos.x + 8 * scale_, viewport->WorkPos.y + 8 * scale_), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(360 * scale_, viewport->WorkSize.y - 16 * scale_), ImGuiCond_Always);
    ImGui::Begin("softbody", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    ImGui::PushItemWidth(-150 * scale_);
    lesson.draw(demo, scale_);
    if (ImGui::CollapsingHeader("Simulation", ImGuiTreeNodeFlags_DefaultOpen)) simulation(demo, fps);
    if (demo.particle_inspection() || demo.rigid_inspection()) {
        if (ImGui::CollapsingHeader("Inspector", ImGuiTreeNodeFlags_DefaultOpen)) inspector(demo);
    }
    if (ImGui::CollapsingHeader("Stability", ImGuiTreeNodeFlags_DefaultOpen)) stability(demo);
    if (ImGui::CollapsingHeader("Energy", ImGuiTreeNodeFlags_DefaultOpen)) energy(demo);
    if (ImGui::CollapsingHeader("Compare integrators", demo.comparing() ? ImGuiTreeNodeFlags_DefaultOpen : 0)) compare(demo);
    if (demo.world().rigid_body_count() > 0 && ImGui::CollapsingHeader("Last collision", ImGuiTreeNodeFlags_DefaultOpen)) {
        last_collision(demo);
    }
    if (ImGui::CollapsingHeader("Add")) add(demo);
    if (ImGui::CollapsingHeader("Parameters")) parameters(demo);
    if (demo.world().rigid_body_count() > 0 && ImGui::CollapsingHeader("Rigid bodies", ImGuiTreeNodeFlags_DefaultOpen)) {
        rigid_bodies(demo);
    }
    if (ImGui::CollapsingHeader("Mesh")) mesh(demo);
    if (ImGui::CollapsingHeader("Display")) display(demo);
    if (ImGui::CollapsingHeader("Presets")) presets(demo);
    ImGui::PopItemWidth();
    ImGui::Separator();
    ImGui::TextDisabled("H: help   Space: pause   R: reset   Tab: hide panels");
    ImGui::End();
}

void Panels::simulation(Demo& demo, float fps) {
    const World& world = demo.world();
    const ImVec2 button(78 * scale_, 0);
    if (ImGui::Button(demo.paused ? "Play" : "Pause", button)) demo.paused = !demo.paused;
    ImGui::SameLine();
    if (ImGui::Button("< Back", button)) demo.step_back();
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("One tick back (key ,): the world as it was, bit for bit.");
    ImGui::SameLine();
    if (ImGui::Button("Step >", button)) {
        demo.paused = true;
        demo.single_tick();
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("One tick on (key . or N).");
    ImGui::SameLine();
    if (ImGui::Button("Reset", button)) demo.reset();
    timeline(demo);
    float time_scale = static_cast<float>(demo.time_scale);
    if (ImGui::SliderFloat("time scale", &time_scale, 0.05f, 2.0f, "%.2fx", ImGuiSliderFlags_Logarithmic)) {
        demo.time_scale = time_scale;
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Slow motion below 1: fewer ticks per second of wall time; dt stays fixed.");
    ImGui::SliderInt("max ticks/frame", &demo.max_ticks_per_frame, 1, 32);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("A slow frame runs at most this many ticks; the rest of its time is dropped.");
    ImGui::Text("tick %llu   t = %.2f s", static_cast<unsigned long long>(world.ticks()), world.time());
    ImGui::Text("ticks this frame %d   physics %.2f ms/tick", demo.ticks_last_frame(), demo.physics_ms_per_tick());
    ImGui::Text("render %.0f FPS   %d threads", fps, world.threads());
    if (world.status() != Status::Ok) ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.3f, 1.0f), "diverged: reset to go on");
    else if (demo.paused) ImGui::TextDisabled("paused");
    if (recorder) recorder_controls(*recorder, demo.paused || world.status() != Status::Ok, scale_);
}

// The recorded past (physics/history.h): drag to any tick of it; play goes on from there.
void Panels::timeline(Demo& demo) {
    const World& world = demo.world();
    const History& history = demo.history();
    const double dt = world.settings().dt;
    int oldest = static_cast<int>(history.oldest_tick()), newest = static_cast<int>(history.newest_tick());
    int tick = static_cast<int>(world.ticks());
    ImGui::BeginDisabled(newest == oldest);
    char label[64];
    std::snprintf(label, sizeof label, "t = %.2f s", tick * dt);
    if (ImGui::SliderInt("timeline", &tick, oldest, std::max(newest, oldest + 1), label)) {
        demo.go_to_tick(static_cast<std::uint64_t>(std::clamp(tick, oldest, newest)));
    }
    ImGui::EndDisabled();
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
        ImGui::SetTooltip("The last %.0f s are kept (%.1f MB now). Drag back to any tick and play on: the\n"
                          "same future, bit for bit, unless you change something; then a new one.",
                          double(history.capacity_ticks()) * dt, double(history.bytes()) / 1e6);
    }
    if (demo.in_past()) {
        ImGui::TextColored(ImVec4(0.95f, 0.75f, 0.30f, 1.0f), "in the past: %.2f s behind", (newest - tick) * dt);
        ImGui::SameLine();
        if (ImGui::SmallButton("Back to now")) demo.go_to_tick(history.newest_tick());
    }
}

void Panels::stability(Demo& demo) {
    const Stability s = demo.world().stability();
    const float fraction = static_cast<float>(s.h_omega / s.limit);
    const ImVec4 colour = !s.stable ? ImVec4(0.90f, 0.25f, 0.20f, 1.0f)
                          : fraction > 0.9f ? ImVec4(0.95f, 0.70f, 0.20f, 1.0f)
                                            : ImVec4(0.30f, 0.75f, 0.40f, 1.0f);
    char label[64];
    std::snprintf(label, sizeof label, "h*omega %.2f of %.2f", s.h_omega, s.limit);
    ImGui::PushStyleColor(ImGuiCol_PlotHistogram, colour);
    ImGui::ProgressBar(std::min(fraction, 1.0f), ImVec2(-1, 0), label);
    ImGui::PopStyleColor();
    if (ImGui::IsItemHovered()) {
        ImGui::SetTooltip("The fastest mode of the spring network (omega = %.1f rad/s) against the step h = %.4f s.\n"
                          "Verlet is stable while sqrt(h^2 omega^2 + 2 h gamma) < 2, i.e. N (k h^2 + 2 c h) < 4 m.",
                          s.omega_max, s.h);
    }
    ImGui::Text("substeps %d (needed %d)   growth %.3f", s.substeps, s.substeps_needed, s.growth);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("growth: how much the fastest-growing mode is amplified per step (above 1 it explodes)");
    if (!s.stable) {
        ImGui::TextColored(colour, "Unstable: this will explode.");
    } else if (fraction > 0.9f) {
        ImGui::TextColored(colour, "Close to the limit.");
    }
    WorldSettings settings = demo.world().settings();
    if (ImGui::Checkbox("automatic substeps", &settings.auto_substeps)) demo.edit_settings(settings);
    if (!s.stable && s.substeps_needed > 0) {
        ImGui::SameLine();
        char fix[48];
        std::snprintf(fix, sizeof fix, "Use %d substeps", s.substeps_needed);
        if (ImGui::SmallButton(fix)) {
            settings.substeps = s.substeps_needed;
            demo.edit_settings(settings);
        }
    }
}

void Panels::energy(Demo& demo) {
    const auto& history = demo.energy_history();
    if (history.size() < 2) {
        ImGui::TextDisabled("no samples yet");
        return;
    }
    // The rigid bodies' rotational energy is drawn when there are rigid bodies.
    const bool rotation = demo.world().rigid_body_count() > 0;
    const int series_count = rotation ? 6 : 4;
    const auto value_of = [](const EnergySample& s, int series) {
        return series == 0   ? s.kinetic
               : series == 1 ? s.gravity
               : series == 2 ? s.elastic
               : series == 3 ? s.total
               : series == 4 ? s.rotational
                             : s.contacts;
    };
    double lo = 1e300, hi = -1e300;
    for (const auto& s : history) {
        for (int series = 0; series < series_count; ++series) {
            lo = std::min(lo, value_of(s, series));
            hi = std::max(hi, value_of(s, series));
        }
    }
    if (hi - lo < 1e-9) hi = lo + 1.0;
    const ImVec2 size(ImGui::GetContentRegionAvail().x, 120 * scale_);
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    ImDrawList* draw = ImGui::GetWindowDrawList();
    draw->AddRectFilled(origin, ImVec2(origin.x + size.x, origin.y + size.y), IM_COL32(20, 24, 30, 255), 4.0f);
    const double t0 = history.front().time, t1 = std::max(history.back().time, t0 + 1e-6);
    const ImU32 colours[6] = {IM_COL32(90, 170, 255, 255), IM_COL32(120, 220, 120, 255), IM_COL32(255, 170, 60, 255),
                              IM_COL32(240, 240, 240, 255), IM_COL32(250, 200, 30, 255), IM_COL32(240, 90, 90, 255)};
    for (int series = 0; series < series_count; ++series) {
        std::vector<ImVec2> points;
        points.reserve(history.size());
        for (const auto& s : history) {
            const double v = value_of(s, series);
            points.emplace_back(origin.x + float((s.time - t0) / (t1 - t0)) * size.x,
                                origin.y + size.y - float((v - lo) / (hi - lo)) * size.y);
        }
        draw->AddPolyline(points.data(), static_cast<int>(points.size()), colours[series], 0, series == 3 ? 2.0f : 1.5f);
    }
    ImGui::Dummy(size);
    const char* names[5] = {"kinetic", "gravity", "elastic", "total", "rotational"};
    const auto& last = history.back();
    for (int series = 0; series < std::min(series_count, 5); ++series) {
        if (series % 2) ImGui::SameLine(180 * scale_);
        ImGui::TextColored(ImColor(colours[series]), "%s %.3g J", names[series], value_of(last, series));
    }
    if (rotation) {
        ImGui::SameLine(180 * scale_);
        ImGui::Text("|L| %.3g kg m^2/s", last.angular_momentum);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("Total angular momentum about the origin, every body: conserved without torques.");
        ImGui::TextColored(ImColor(colours[5]), "contacts: %+.3g J this second", last.contacts);
        if (ImGui::IsItemHovered()) {
            ImGui::SetTooltip("What the rigid contacts' impulses (Eq. 38) did to the energy over the last second: never more\n"
                              "than zero. A bounce with e < 1 and friction take energy; a body resting on another, none.");
        }
    }
    ImGui::TextDisabled("last %.0f s, from %.1f to %.1f J", t1 - t0, lo, hi);
    if (demo.comparing()) energy_by_integrator(demo);
}

// Total energy of each compared world, in its integrator's colour, on one scale.
void Panels::energy_by_integrator(Demo& demo) {
    const auto& history = demo.energy_history();
    const auto& compared = demo.compared();
    const std::size_t worlds = compared.size() + 1;
    const auto total = [](const EnergySample& s, std::size_t k) { return k == 0 ? s.total : s.compared[k - 1]; };
    double lo = 1e300, hi = -1e300;
    for (const auto& s : history) {
        if (s.compared.size() + 1 != worlds) continue;
        for (std::size_t k = 0; k < worlds; ++k) {
            if (!std::isfinite(total(s, k))) continue;
            lo = std::min(lo, total(s, k));
            hi = std::max(hi, total(s, k));
        }
    }
    if (lo > hi) return;
    if (hi - lo < 1e-9) hi = lo + 1.0;
    ImGui::TextUnformatted("total energy by integrator");
    const ImVec2 size(ImGui::GetContentRegionAvail().x, 90 * scale_);
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    ImDrawList* draw = ImGui::GetWindowDrawList();
    draw->AddRectFilled(origin, ImVec2(origin.x + size.x, origin.y + size.y), IM_COL32(20, 24, 30, 255), 4.0f);
    const double t0 = history.front().time, t1 = std::max(history.back().time, t0 + 1e-6);
    for (std::size_t k = 0; k < worlds; ++k) {
        const Integrator integrator = k == 0 ? demo.world().settings().integrator : compared[k - 1].setup.integrator;
        const glm::vec3 c = integrator_color(integrator);
        std::vector<ImVec2> points;
        for (const auto& s : history) {
            if (s.compared.size() + 1 != worlds || !std::isfinite(total(s, k))) continue;
            points.emplace_back(origin.x + float((s.time - t0) / (t1 - t0)) * size.x,
                                origin.y + size.y - float((total(s, k) - lo) / (hi - lo)) * size.y);
        }
        draw->AddPolyline(points.data(), static_cast<int>(points.size()), ImColor(c.r, c.g, c.b), 0, 2.0f);
    }
    ImGui::Dummy(size);
    ImGui::TextDisabled("from %.1f to %.1f J", lo, hi);
}

// Up to four integrators on the same scene at once: which ones, each one's substeps, and
// what each is doing now.
void Panels::compare(Demo& demo) {
    constexpr Integrator kAll[4] = {Integrator::Verlet, Integrator::SymplecticEuler, Integrator::ExplicitEuler, Integrator::RK4};
    const Integrator main = demo.world().settings().integrator;
    const auto swatch = [](Integrator integrator) {
        const glm::vec3 c = integrator_color(integrator);
        ImGui::ColorButton("##colour", ImVec4(c.r, c.g, c.b, 1.0f), ImGuiColorEditFlags_NoTooltip, ImVec2(12, 12));
        ImGui::SameLine();
    };
    if (!demo.comparing()) {
        ImGui::TextWrapped("The scene again from t = 0, beside copies of itself stepped by other integrators.");
        swatch(main);
        ImGui::Text("%s (this world's; Parameters)", std::string(to_string(main)).c_str());
        std::vector<CompareSetup> others;
        for (int k = 0; k < 4; ++k) {
            if (kAll[k] == main) continue;
            ImGui::PushID(k);
            swatch(kAll[k]);
            ImGui::Checkbox(std::string(to_string(kAll[k])).c_str(), &compare_pick_[k]);
            ImGui::SameLine(200 * scale_);
            ImGui::SetNextItemWidth(90 * scale_);
            ImGui::SliderInt("##substeps", &compare_substeps_[k], 0, 16, compare_substeps_[k] == 0 ? "auto" : "%d substeps");
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("Its substeps a tick: 0 is automatic (what stability needs).");
            ImGui::PopID();
            if (compare_pick_[k]) others.push_back({kAll[k], compare_substeps_[k] == 0, std::max(1, compare_substeps_[k])});
        }
        ImGui::BeginDisabled(others.empty());
        if (ImGui::Button("Compare")) demo.compare(others);
        ImGui::EndDisabled();
        return;
    }
    // Running: a row each, with its energy now against the plot's first sample.
    const auto& history = demo.energy_history();
    if (!history.empty() && ImGui::BeginTable("compared", 4, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit)) {
        ImGui::TableSetupColumn("integrator");
        ImGui::TableSetupColumn("substeps");
        ImGui::TableSetupColumn("E, J");
        ImGui::TableSetupColumn("change");
        ImGui::TableHeadersRow();
        const auto row = [&](Integrator integrator, const World& world, double start, double now) {
            ImGui::TableNextRow();
            ImGui::TableSetColumnIndex(0);
            swatch(integrator);
            ImGui::TextUnformatted(std::string(to_string(integrator)).c_str());
            ImGui::TableSetColumnIndex(1);
            ImGui::Text("%d", world.substeps_in_use());
            ImGui::TableSetColumnIndex(2);
            ImGui::Text("%.4g", now);
            ImGui::TableSetColumnIndex(3);
            if (world.status() != Status::Ok) ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.3f, 1.0f), "diverged");
            else ImGui::Text("%+.2f%%", start != 0.0 ? 100.0 * (now - start) / std::abs(start) : 0.0);
        };
        const EnergySample& first = history.front();
        const EnergySample& last = history.back();
        row(main, demo.world(), first.total, last.total);
        for (std::size_t k = 0; k < demo.compared().size() && k < last.compared.size() && k < first.compared.size(); ++k) {
            const ComparedWorld& c = demo.compared()[k];
            row(c.setup.integrator, *c.world, first.compared[k], last.compared[k]);
        }
        ImGui::EndTable();
    }
    if (ImGui::Checkbox("overlaid", &demo.compare_overlaid)) demo.frame_body();
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Draw the copies over this world instead of beside it.");
    ImGui::SameLine();
    if (ImGui::Button("Stop comparing")) demo.compare({});
    ImGui::TextWrapped("The mouse grabs the first world only; keys, pins, Reset and the timeline act on all.");
}

// Every key with a widget, from the table (keys.h): the world's, the selected soft body's, and
// each named spring's. A widget hands its typed value to the definition's setter, checked once.
void Panels::parameters(Demo& demo) {
    const World& world = demo.world();
    ImGui::TextDisabled("World");
    WorldSettings settings = world.settings();
    for (const KeyInfo* info : keys_of(KeyOwner::World)) {
        if (!has_widget(*info)) continue;
        KeyValue value = get_key(settings, *info);
        if (key_widget(*info, value)) {
            set_key(settings, *info, value);
            demo.edit_settings(settings);
        }
    }
    if (world.soft_body_count() > 0) {
        // Several soft bodies: the keys are the selected body's (click a body to select it).
        const std::size_t selected = demo.selected_body();
        ImGui::Separator();
        if (world.soft_body_count() > 1) {
            if (ImGui::BeginCombo("soft body", world.soft_body(selected).name().c_str())) {
                for (std::size_t b = 0; b < world.soft_body_count(); ++b) {
                    if (ImGui::Selectable(world.soft_body(b).name().c_str(), b == selected)) demo.select_body(b);
                }
                ImGui::EndCombo();
            }
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("Whose keys are below (or click a soft body in the view).");
        } else {
            ImGui::TextDisabled("Soft body '%s'", world.soft_body(selected).name().c_str());
        }
        SoftBodyDef def = world.soft_body(selected).def;
        for (const KeyInfo* info : keys_of(KeyOwner::SoftBody)) {
            if (!has_widget(*info)) continue;
            KeyValue value = get_key(def, *info);
            if (key_widget(*info, value)) {
                set_key(def, *info, value);
                demo.edit_body(selected, def);
            }
        }
        ImGui::Text("pinned: %zu vertices", def.pinned.size());
        ImGui::SameLine();
        if (ImGui::SmallButton("free all")) {
            def.pinned.clear();
            demo.edit_body(selected, def);
        }
    }
    for (std::size_t k = 0; k < world.spring_count(); ++k) {
        SpringDef def = world.def(world.spring_id(k));
        if (def.name.empty()) continue;
        ImGui::Separator();
        ImGui::TextDisabled("Spring '%s'", def.name.c_str());
        ImGui::PushID(int(k));
        for (const KeyInfo* info : keys_of(KeyOwner::Spring)) {
            KeyValue value = get_key(def, *info);
            if (key_widget(*info, value)) {
                set_key(def, *info, value);
                demo.set_key(def.name + "." + std::string(info->name), key_text(*info, value));
            }
        }
        ImGui::PopID();
    }
    ImGui::TextDisabled("* applies on reset");
    if (demo.reset_pending()) {
        ImGui::SameLine();
        if (ImGui::SmallButton("reset now")) demo.reset();
    }
    if (ImGui::Button("World to defaults")) demo.edit_settings(WorldSettings{});
    ImGui::SameLine();
    ImGui::TextDisabled("(Listing 8's values)");
}

void Panels::add(Demo& demo) {
    ImGui::TextWrapped("Drops a body above the scene where the camera looks; the others go on as they were.");
    const ImVec2 button(ImGui::GetContentRegionAvail().x * 0.48f, 0.0f);
    if (ImGui::Button("Soft ball", button)) demo.add_body(Demo::AddKind::SoftBall);
    ImGui::SameLine();
    if (ImGui::Button("Soft cube", button)) demo.add_body(Demo::AddKind::SoftCube);
    if (ImGui::Button("Rigid box", button)) demo.add_body(Demo::AddKind::RigidBox);
    ImGui::SameLine();
    if (ImGui::Button("Rigid ball", button)) demo.add_body(Demo::AddKind::RigidBall);
    if (!meshes_.empty()) {
        add_mesh_ = std::min(add_mesh_, int(meshes_.size()) - 1);
        const std::string current = fs::path(meshes_[std::size_t(add_mesh_)]).filename().string();
        if (ImGui::BeginCombo("##addmesh", current.c_str())) {
            for (std::size_t k = 0; k < meshes_.size(); ++k) {
                if (ImGui::Selectable(fs::path(meshes_[k]).filename().string().c_str(), int(k) == add_mesh_)) add_mesh_ = int(k);
            }
            ImGui::EndCombo();
        }
        ImGui::SameLine();
        if (ImGui::Button("Add mesh")) demo.add_body(Demo::AddKind::MeshFile, meshes_[std::size_t(add_mesh_)]);
    }
}

void Panels::mesh(Demo& demo) {
    const World& world = demo.world();
    const bool soft = world.soft_body_count() > 0;
    if (soft) {
        const SoftBody& body = world.soft_body(demo.selected_body());
        const Mesh& mesh = body.mesh;
        ImGui::TextWrapped("%s", fs::path(mesh.source).filename().string().c_str());
        if (body.reduced) {
            ImGui::Text("%zu vertices, simulated on %zu particles", mesh.vertex_to_particle.size(), body.particle_count());
            if (ImGui::IsItemHovered()) {
                // max_particles all (0) is capped too: no body runs on more than kMaxParticles.
                const bool all = body.def.max_particles == 0;
                ImGui::SetTooltip("Above %s (%zu): the %zu distinct positions follow %zu particles chosen over\n"
                                  "the body (skinning); each weighs %.3g particles' mass, k and c as much again.",
                                  all ? "the cap on max_particles=all" : "max_particles",
                                  all ? kMaxParticles : std::size_t(body.def.max_particles), mesh.particle_count(), body.particle_count(),
                                  double(mesh.particle_count()) / double(body.particle_count()));
            }
        } else {
            ImGui::Text("%zu vertices -> %zu particles", mesh.vertex_to_particle.size(), body.particle_count());
        }
        ImGui::Text("scale %.4g%s, +%s up", double(body.scale_used), body.def.scale == 0.0f ? " (auto: 1 m, centred)" : "",
                    body.def.up_axis.c_str());
        if (ImGui::IsItemHovered()) {
            ImGui::SetTooltip("A mesh opened or dropped without a scene is sized so its largest side is 1 m and stood\n"
                              "up (+y up, as most exporters write). Parameters: scale, up_axis (both on reset).");
        }
        ImGui::Text("%zu triangles, %zu springs + dampers", mesh.triangle_count(), body.spring_count());
        ImGui::Text("memory %s", memory_text(body.particle_count()).c_str());
    } else {
        ImGui::TextWrapped("No soft body in this scene: open a mesh to add one.");
    }
    if (ImGui::BeginCombo("scene", fs::path(demo.source()).filename().string().c_str())) {
        for (const auto& scene : scenes_) {
            if (ImGui::Selectable(fs::path(scene).stem().string().c_str())) demo.load_scene_file(scene);
        }
        ImGui::EndCombo();
    }
    if (ImGui::BeginCombo("mesh", soft ? fs::path(world.soft_body(demo.selected_body()).mesh.source).filename().string().c_str() : "(none)")) {
        for (const auto& file : meshes_) {
            if (ImGui::Selectable(fs::path(file).filename().string().c_str())) demo.load_mesh_file(file);
        }
        ImGui::EndCombo();
    }
    ImGui::InputTextWithHint("##open", "path to an .obj or .off", open_path_, sizeof open_path_);
    ImGui::SameLine();
    if (ImGui::Button("Open") && open_path_[0]) demo.load_mesh_file(open_path_);
    ImGui::TextDisabled("or drop a file on the window");
}

// One particle's forces, one line each, named by equation, as Listing 8's CalcForce adds them;
// or a rigid body's, each with its torque about the centre of mass.
void Panels::inspector(Demo& demo) {
    const auto vec = [](const char* label, const Vec3& v, const char* unit) {
        ImGui::Text("%-8s %8.3f %8.3f %8.3f %s", label, double(v.x), double(v.y), double(v.z), unit);
    };
    if (const auto in = demo.particle_inspection()) {
        ImGui::Text("particle %u of '%s'%s", in->particle, demo.world().soft_body(in->body).name().c_str(),
                    in->mass == 0.0f ? " (pinned)" : "");
        vec("x", in->x, "m");
        vec("v", in->v, "m/s");
        vec("a", in->a, "m/s^2");
        ImGui::TextDisabled("force      from          |F|, N");
        for (const ForceTerm& t : in->terms) {
            ImGui::Text("%-10s %-10s %9.4g", t.name.substr(0, 10).c_str(), t.equation.c_str(), double(length(t.force)));
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s: %s\n%s", t.name.c_str(), t.equation.c_str(), t.detail.c_str());
            ImGui::TextDisabled("  (%.3f, %.3f, %.3f)", double(t.force.x), double(t.force.y), double(t.force.z));
            if (t.name == "friction") ImGui::TextWrapped("  %s", t.detail.c_str());
        }
        ImGui::Separator();
        ImGui::Text("%-21s %9.4g", "net = m a", double(length(in->net)));
        ImGui::TextDisabled("  (%.3f, %.3f, %.3f)", double(in->net.x), double(in->net.y), double(in->net.z));
        if (!in->strongest.empty()) {
            ImGui::TextDisabled("strongest pairs (Eq. 21 + 22):");
            for (const PairTerm& p : in->strongest) {
                ImGui::Text("  %-5u l %.3f/%.3f m %.3g N", p.other, double(p.length), double(p.rest_length),
                            double(length(p.spring + p.damper)));
            }
        }
        ImGui::TextDisabled("ctrl-click elsewhere to stop");
        return;
    }
    const auto in = demo.rigid_inspection();
    if (!in) return;
    const RigidBody& body = demo.world().rigid_body(in->body);
    ImGui::Text("rigid body '%s'%s", body.name.c_str(), body.fixed ? " (fixed)" : "");
    if (!body.fixed) {
        const World& world = demo.world();
        if (world.rigid_asleep(in->body)) {
            ImGui::TextColored(ImVec4(0.55f, 0.75f, 1.0f, 1.0f), "asleep: at rest, not integrated");
            if (ImGui::IsItemHovered()) {
                ImGui::SetTooltip("Its island's bodies were all slower than 5 cm/s at every point for 0.5 s: it costs nothing\n"
                                  "until an awake body or a soft body touches it, it is grabbed, or a key changes.");
            }
        } else if (world.rigid_rest_time(in->body) > 0.0) {
            ImGui::TextDisabled("awake, at rest for %.2f s", world.rigid_rest_time(in->body));
        } else {
            ImGui::TextDisabled("awake, moving");
        }
    }
    ImGui::TextDisabled("force          |F| N   |tau| N m");
    for (const WrenchTerm& t : in->terms) {
        ImGui::Text("%-14s %-8s %8.4g %8.4g", t.name.substr(0, 14).c_str(), t.equation.c_str(), length(t.force), length(t.torque));
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s (%s)\n%s", t.name.c_str(), t.equation.c_str(), t.detail.c_str());
    }
    ImGui::Separator();
    ImGui::Text("sum: F %.4g N, tau %.4g N m", length(in->force), length(in->torque));
    ImGui::TextDisabled("P, L, omega, q, J_world: the Rigid bodies panel");
}

// Eq. 38 with the numbers of the latest hit, so that a student can follow the formula through.
void Panels::last_collision(Demo& demo) {
    const auto& hit = demo.last_collision();
    if (!hit) {
        ImGui::TextDisabled("no collision yet");
        return;
    }
    const ImpulseTerms& t = hit->terms;
    ImGui::Text("t = %.2f s: %s on %s", hit->time, hit->body_1.c_str(), hit->body_2.c_str());
    if (hit->points > 1) ImGui::TextDisabled("the point with the largest impulse of %zu", hit->points);
    ImGui::TextDisabled("lambda = -(1 + e) v_rel.n");
    ImGui::TextDisabled("         / (1/m1 + 1/m2 + rot1 + rot2)");
    if (ImGui::IsItemHovered()) {
        ImGui::SetTooltip("Eq. 38. rot_i = n . ((J_i^-1 (r_i x n)) x r_i): how much of the impulse turns body i\n"
                          "instead of moving it. Body 1 gets +lambda n at r1, body 2 -lambda n at r2 (Eq. 37).");
    }
    ImGui::Text("n       %7.3f %7.3f %7.3f", t.n.x, t.n.y, t.n.z);
    ImGui::Text("v_rel.n %9.4f m/s    e %.2f", t.v_rel_n, t.e);
    ImGui::Text("r1 x n  %7.3f %7.3f %7.3f m", t.r1_x_n.x, t.r1_x_n.y, t.r1_x_n.z);
    ImGui::Text("r2 x n  %7.3f %7.3f %7.3f m", t.r2_x_n.x, t.r2_x_n.y, t.r2_x_n.z);
    ImGui::Text("1/m1 %.4g  1/m2 %.4g 1/kg", t.inv_mass_1, t.inv_mass_2);
    ImGui::Text("rot1 %.4g  rot2 %.4g 1/kg", t.rotation_1, t.rotation_2);
    ImGui::Text("denominator %.4g 1/kg", t.denominator);
    ImGui::Text("lambda %.4g N s (Eq. 38 alone)", t.lambda);
    ImGui::Text("solver %.4g N s", t.solver_lambda);
    if (ImGui::IsItemHovered()) {
        ImGui::SetTooltip("What the solver applied at this point: all the contacts of the step solved together,\n"
                          "with friction. For one point of two bodies without friction it equals Eq. 38's lambda;\n"
                          "where several points share a hit, they split it.");
    }
}

void Panels::rigid_bodies(Demo& demo) {
    const World& world = demo.world();
    const int count = static_cast<int>(world.rigid_body_count());
    rigid_selected_ = std::clamp(rigid_selected_, 0, count - 1);
    if (ImGui::BeginCombo("body##rigid", world.rigid_body(std::size_t(rigid_selected_)).name.c_str())) {
        for (int b = 0; b < count; ++b) {
            if (ImGui::Selectable(world.rigid_body(std::size_t(b)).name.c_str(), b == rigid_selected_)) rigid_selected_ = b;
        }
        ImGui::EndCombo();
    }
    const std::size_t i = std::size_t(rigid_selected_);
    const RigidBody& body = world.rigid_body(i);
    RigidBodyDef def = world.def(world.rigid_body_id(i));
    ImGui::TextDisabled("%s, volume %.4g m^3%s", std::string(to_string(body.shape)).c_str(), body.volume,
                        body.hull_mass_properties ? " (its hull's: the mesh is open)" : "");

    // Keys: restitution and friction act at once; mass and fixed at reset.
    bool edited = false;
    float mass = float(body.mass);
    if (ImGui::SliderFloat("mass *", &mass, 0.01f, 1000.0f, "%.3g kg", ImGuiSliderFlags_Logarithmic)) {
        def.mass = double(std::max(mass, 1e-3f));
        def.density.reset();
        edited = true;
    }
    if (ImGui::Checkbox("fixed *", &def.fixed)) edited = true;
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Infinite mass: scenery such as a fulcrum or a ramp.");
    float e = def.restitution.value_or(world.settings().restitution);
    if (ImGui::SliderFloat("restitution e", &e, 0.0f, 1.0f, "%.2f")) {
        def.restitution = e;
        edited = true;
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Eq. 38: an impact's normal velocity leaves at -e times the speed it came in with.");
    float mu = def.friction.value_or(world.settings().dynamic_friction);
    if (ImGui::SliderFloat("friction mu", &mu, 0.0f, 2.0f, "%.2f")) {
        def.friction = mu;
        edited = true;
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Coulomb friction in impulse form: |tangential impulse| <= mu x normal impulse.");
    if (edited) demo.edit_rigid_body(i, def);
    if (demo.reset_pending()) {
        ImGui::TextDisabled("* applies on reset");
        ImGui::SameLine();
        if (ImGui::SmallButton("reset now##rigid")) demo.reset();
    }

    // State: Listing 10's thirteen numbers and what follows from them (Eq. 28, 32, 36).
    const RigidMotion m = world.rigid_motion(i);
    ImGui::Text("x     %8.3f %8.3f %8.3f m", m.x.x, m.x.y, m.x.z);
    ImGui::Text("P     %8.3f %8.3f %8.3f kg m/s", m.P.x, m.P.y, m.P.z);
    ImGui::Text("L     %8.3f %8.3f %8.3f kg m^2/s", m.L.x, m.L.y, m.L.z);
    ImGui::Text("q     %7.4f %7.4f %7.4f %7.4f", m.q.w, m.q.x, m.q.y, m.q.z);
    const double norm = m.q.norm();
    ImGui::TextColored(std::abs(norm - 1.0) > 1e-3 ? ImVec4(1.0f, 0.55f, 0.3f, 1.0f) : ImVec4(0.7f, 0.7f, 0.7f, 1.0f),
                       "|q| = %.9f", norm);
    if (ImGui::IsItemHovered()) {
        ImGui::SetTooltip("A unit quaternion has |q| = 1; rounding and explicit Euler make it drift, and a drifted q\n"
                          "no longer rotates: it scales and shears. Listing 9 renormalises every few steps\n"
                          "(renormalize_every; 0 lets you watch it drift).");
    }
    ImGui::Text("v     %8.3f %8.3f %8.3f m/s", m.v.x, m.v.y, m.v.z);
    ImGui::Text("omega %8.3f %8.3f %8.3f rad/s", m.omega.x, m.omega.y, m.omega.z);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Eq. 36: omega = R J_body^-1 R^T L, after each step.");
    const Mat3 J = m.R * body.J_body * m.R.transposed();
    ImGui::TextDisabled("J_world = R J_body R^T (Eq. 32), kg m^2:");
    for (int r = 0; r < 3; ++r) ImGui::Text("      %9.4f %9.4f %9.4f", J.m[r][0], J.m[r][1], J.m[r][2]);
    if (!body.fixed) {
        ImGui::Text("kinetic %.4g J = %.4g translation + %.4g rotation", 0.5 * dot(m.P, m.v) + 0.5 * dot(m.L, m.omega),
                    0.5 * dot(m.P, m.v), 0.5 * dot(m.L, m.omega));
    }
}

void Panels::display(Demo& demo) {
    auto& o = demo.overlays;
    auto& a = demo.appearance;
    ImGui::Checkbox("particles (P)", &o.particles);
    ImGui::SameLine(180 * scale_);
    ImGui::Checkbox("springs (S)", &o.springs);
    ImGui::Checkbox("pins", &o.pins);
    ImGui::SameLine(180 * scale_);
    ImGui::Checkbox("centre of mass (C)", &o.center_of_mass);
    ImGui::Checkbox("velocities (V)", &o.velocities);
    ImGui::SameLine(180 * scale_);
    ImGui::Checkbox("forces", &o.forces);
    ImGui::Checkbox("normals", &o.normals);
    ImGui::SameLine(180 * scale_);
    ImGui::Checkbox("shadows", &a.shadows);
    ImGui::Checkbox("omega and L (W)", &o.angular);
    if (ImGui::IsItemHovered()) {
        ImGui::SetTooltip("Each rigid body's angular velocity (yellow) and angular momentum (violet) at its centre of mass:\n"
                          "L = J omega (Eq. 28); they point the same way only about a principal axis.");
    }
    ImGui::SameLine(180 * scale_);
    ImGui::Checkbox("contacts", &o.contacts);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Contact points of the last step, each normal as long as its impulse (Eq. 38).");
    ImGui::Checkbox("springs between bodies", &o.links);
    ImGui::SameLine(180 * scale_);
    ImGui::Checkbox("sleeping dimmer", &demo.dim_sleeping);
    if (ImGui::IsItemHovered()) {
        ImGui::SetTooltip("Rigid bodies that sleep drawn greyer: an island of bodies at rest for half a second sleeps (it is\n"
                          "not integrated and its contacts are not solved) until something touches it, you grab it or a\n"
                          "key changes. The sleeping key (Parameters) turns sleeping off.");
    }
    ImGui::Checkbox("ground and grid", &a.ground);
    ImGui::SameLine(180 * scale_);
    ImGui::Checkbox("follow the bodies (T)", &demo.follow);
    if (ImGui::IsItemHovered()) {
        ImGui::SetTooltip("The camera moves with the bodies' centre, smoothed and level, keeping them where they are in\n"
                          "the view (pan to move them; it holds still while you pull a body). On for a scene with one body.");
    }
    int style = static_cast<int>(a.body);
    if (ImGui::Combo("body", &style, "solid\0ghost (see-through)\0wireframe\0hidden\0")) a.body = static_cast<render::BodyStyle>(style);
    ImGui::ColorEdit3("colour", &a.body_color.x, ImGuiColorEditFlags_NoInputs);
    int samples_index = a.samples >= 4 ? 2 : a.samples >= 2 ? 1 : 0;
    if (ImGui::Combo("anti-aliasing", &samples_index, "off\0" "2x\0" "4x\0")) a.samples = samples_index == 0 ? 1 : samples_index == 1 ? 2 : 4;
    ImGui::Checkbox("pattern on the body", &a.pattern);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Soft checks fixed in the body's material, so rolling and squash show.");
    int springs = static_cast<int>(a.max_springs);
    if (ImGui::SliderInt("inner springs drawn", &springs, 0, 2000, "%d", ImGuiSliderFlags_Logarithmic)) a.max_springs = static_cast<std::size_t>(springs);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Springs along the surface are drawn, plus this many more from a fixed sample.");
}

void Panels::presets(Demo& demo) {
    ImGui::InputText("##preset", preset_path_, sizeof preset_path_);
    if (ImGui::Button("Save")) {
        std::error_code ec;
        const fs::path path(preset_path_);
        if (path.has_parent_path()) fs::create_directories(path.parent_path(), ec);
        if (fs::exists(path, ec)) confirm_overwrite_ = preset_path_;
        else demo.save_preset(preset_path_, false);
    }
    ImGui::SameLine();
    if (ImGui::Button("Load")) demo.load_scene_file(preset_path_);
    ImGui::SameLine();
    ImGui::TextDisabled("JSON scene files");
    if (!confirm_overwrite_.empty()) ImGui::OpenPopup("Overwrite?");
    if (ImGui::BeginPopupModal("Overwrite?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::Text("%s already exists.\nReplace it with the current parameters?", confirm_overwrite_.c_str());
        if (ImGui::Button("Replace")) {
            demo.save_preset(confirm_overwrite_, true);
            confirm_overwrite_.clear();
            ImGui::CloseCurrentPopup();
        }
        ImGui::SameLine();
        if (ImGui::Button("Cancel")) {
            confirm_overwrite_.clear();
            ImGui::CloseCurrentPopup();
        }
        ImGui::EndPopup();
    }
}

void Panels::help() {
    const ImGuiViewport* viewport = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(viewport->WorkPos.x + viewport->WorkSize.x * 0.5f, viewport->WorkPos.y + viewport->WorkSize.y * 0.5f),
                            ImGuiCond_Always, ImVec2(0.5f, 0.5f));
    ImGui::Begin("Controls", &show_help, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse);
    // The mouse and every key, from the one list the controls use (gui/bindings.cpp).
    if (ImGui::BeginTable("controls", 2, ImGuiTableFlags_RowBg)) {
        const auto row = [](const char* left, const char* right) {
            ImGui::TableNextRow();
            ImGui::TableSetColumnIndex(0);
            ImGui::TextUnformatted(left);
            ImGui::TableSetColumnIndex(1);
            ImGui::TextUnformatted(right);
        };
        for (const MouseBinding& m : mouse_bindings()) row(m.gesture, m.what);
        for (const KeyBinding& k : key_bindings()) row(k.label, k.what);
        ImGui::EndTable();
    }
    ImGui::End();
}

void Panels::error_banner(Demo& demo) {
    if (demo.error().empty()) return;
    const ImGuiViewport* viewport = ImGui::GetMainViewport();
    const float width = std::min(760 * scale_, viewport->WorkSize.x - 400 * scale_);
    ImGui::SetNextWindowPos(ImVec2(viewport->WorkPos.x + viewport->WorkSize.x - width - 12 * scale_, viewport->WorkPos.y + 12 * scale_));
    ImGui::SetNextWindowSize(ImVec2(width, 0));
    ImGui::PushStyleColor(ImGuiCol_WindowBg, ImVec4(0.45f, 0.08f, 0.08f, 0.94f));
    ImGui::Begin("##error", nullptr, ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_AlwaysAutoResize);
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextUnformatted(demo.error().c_str());
    ImGui::PopTextWrapPos();
    if (ImGui::SmallButton("Dismiss")) demo.clear_error();
    if (demo.world().status() != Status::Ok) {
        ImGui::SameLine();
        if (ImGui::SmallButton("Reset")) {
            demo.reset();
            demo.clear_error();
        }
    }
    ImGui::End();
    ImGui::PopStyleColor();
}

}  // namespace softbody::app

// The Measure tool: what a class measures with, in the view and in simulated time.
//   - a stopwatch on the simulation's clock (start, stop, lap, reset): slow motion and pauses
//     do not change what it reads;
//   - a reference line across the view at a height, and a height scale beside the bodies;
//   - a ruler: two ends dragged in the view (or typed), the distance and its level and upright parts;
//   - a probe: one body's centre, velocity, speed, acceleration and kinetic energy, live, from the
//     run's series (the numbers Export CSV writes).
#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "gui/plot.h"
#include "gui/session.h"
#include "gui/tool.h"
#include "gui/view.h"

namespace softbody::app {

namespace {

// Where a point of the world is drawn in the window (ImGui's coordinates); false when it is
// behind the eye.
bool to_window(const render::Camera& camera, const glm::vec3& p, ImVec2& out) {
    const ImVec2 size = ImGui::GetIO().DisplaySize;
    if (size.x <= 0.0f || size.y <= 0.0f) return false;
    const glm::vec4 clip = camera.projection(size.x / size.y) * camera.view() * glm::vec4(p, 1.0f);
    if (clip.w <= camera.near_plane) return false;
    out = ImVec2((clip.x / clip.w * 0.5f + 0.5f) * size.x, (0.5f - clip.y / clip.w * 0.5f) * size.y);
    return true;
}

void line_3d(ImDrawList* draw, const render::Camera& camera, const glm::vec3& a, const glm::vec3& b, ImU32 color, float width) {
    ImVec2 pa, pb;
    if (to_window(camera, a, pa) && to_window(camera, b, pb)) draw->AddLine(pa, pb, color, width);
}

// Text with a dark outline, readable on the light ground and the sky.
void label(ImDrawList* draw, ImVec2 at, ImU32 color, const char* text) {
    for (const ImVec2 d : {ImVec2(-1, 0), ImVec2(1, 0), ImVec2(0, -1), ImVec2(0, 1)}) {
        draw->AddText(ImVec2(at.x + d.x, at.y + d.y), IM_COL32(0, 0, 0, 255), text);
    }
    draw->AddText(at, color, text);
}

class MeasureTool : public Tool {
public:
    const char* title() const override { return "Measure"; }
    void draw(ToolContext& c) override {
        stopwatch(c.session);
        ImGui::Separator();
        ImGui::Checkbox("Reference line", &line_on_);
        if (line_on_) {
            ImGui::SetNextItemWidth(-FLT_MIN);
            ImGui::DragFloat("##line", &line_height_, 0.01f, -100.0f, 1000.0f, "at height %.2f m");
        }
        ImGui::Checkbox("Height scale", &scale_on_);
        ImGui::Separator();
        ruler_panel(c);
        ImGui::Separator();
        probe_panel(c.session);
    }

    nlohmann::ordered_json report() const override {
        nlohmann::ordered_json out = {{"height_scale", scale_on_}, {"ruler", ruler_on_}};
        out["reference_line"] = line_on_ ? nlohmann::ordered_json(line_height_) : nlohmann::ordered_json(nullptr);
        return out;
    }

    void draw_view(ToolContext& c) override {
        follow_scene(c.session);
        ImDrawList* draw = ImGui::GetBackgroundDrawList();
        const render::Camera& camera = c.view.camera;
        // Across the view, level, at the chosen height, centred where the camera looks.
        const glm::vec3 across = camera.right() * (4.0f * camera.distance);
        const glm::vec3 centre(camera.target.x, camera.target.y, 0.0f);
        if (line_on_) {
            const glm::vec3 mid = centre + glm::vec3(0.0f, 0.0f, line_height_);
            line_3d(draw, camera, mid - across, mid + across, plot_color(5), 2.0f);
            ImVec2 at;
            if (to_window(camera, mid, at)) {
                char text[48];
                std::snprintf(text, sizeof text, "%.2f m", line_height_);
                label(draw, ImVec2(at.x + 6.0f, at.y - ImGui::GetFontSize() - 2.0f), plot_color(5), text);
            }
        }
        if (scale_on_) height_scale(draw, c);
        if (ruler_on_) ruler_view(draw, c);
        probe_view(draw, c);
    }

private:
    // A scene that asks for aids (its "view") turns them on as it opens; what the panel
    // changes afterwards stays until another scene opens.
    void follow_scene(const Session& session) {
        if (session.source() == source_) return;
        source_ = session.source();
        const SceneView& aids = session.lesson().view;
        scale_on_ = aids.height_scale;
        line_on_ = aids.reference_line.has_value();
        if (aids.reference_line) line_height_ = float(*aids.reference_line);
    }

    // --- The stopwatch, on the world's clock ------------------------------------------------
    void stopwatch(Session& session) {
        const double now = session.world().time();
        if (running_ && now < start_) reset_watch();  // the world went back before the start
        const double shown = running_ ? held_ + (now - start_) : held_;
        ImGui::Text("Stopwatch  %.3f s", shown);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("Simulated time: slow motion and pauses do not change it.");
        if (ImGui::Button(running_ ? "Stop" : "Start")) {
            if (running_) held_ += now - start_;
            else start_ = now;
            running_ = !running_;
        }
        ImGui::SameLine();
        ImGui::BeginDisabled(!running_);
        if (ImGui::Button("Lap")) laps_.push_back(shown);
        ImGui::EndDisabled();
        ImGui::SameLine();
        if (ImGui::Button("Reset##watch")) reset_watch();
        for (std::size_t k = 0; k < laps_.size(); ++k) {
            ImGui::Text("lap %zu  %.3f s  (split %.3f s)", k + 1, laps_[k] - (k ? laps_[k - 1] : 0.0), laps_[k]);
        }
    }
    void reset_watch() {
        running_ = false;
        held_ = 0.0;
        laps_.clear();
    }

    // --- A height scale: a post beside the bodies, a tick every round step ---------------------
    void height_scale(ImDrawList* draw, ToolContext& c) {
        const render::Camera& camera = c.view.camera;
        const World& world = c.session.world();
        const float ground = world.settings().ground ? world.settings().ground_height : 0.0f;
        // To the right of where the camera looks (the panel covers the left of the view).
        const glm::vec3 base = glm::vec3(camera.target.x, camera.target.y, ground) + camera.right() * (0.3f * camera.distance);
        const float top = std::max(ground + 1.0f, float(camera.target.z) + 0.5f * camera.distance);
        const std::vector<double> ticks = plot_ticks(ground, top, 8);
        const ImU32 color = plot_color(7);
        line_3d(draw, camera, base, glm::vec3(base.x, base.y, top), color, 2.0f);
        for (double t : ticks) {
            const glm::vec3 at(base.x, base.y, float(t));
            line_3d(draw, camera, at, at + camera.right() * (0.03f * camera.distance), color, 2.0f);
            ImVec2 p;
            if (!to_window(camera, at, p)) continue;
            char text[32];
            std::snprintf(text, sizeof text, "%g m", t);
            label(draw, ImVec2(p.x + 10.0f, p.y - 0.5f * ImGui::GetFontSize()), color, text);
        }
    }

    // --- The ruler ----------------------------------------------------------------------------
    void ruler_panel(ToolContext& c) {
        if (ImGui::Checkbox("Ruler", &ruler_on_) && ruler_on_ && !placed_) {
            // First shown: across the middle of the view, a metre long.
            const render::Camera& camera = c.view.camera;
            ends_[0] = camera.target - camera.right() * 0.5f;
            ends_[1] = camera.target + camera.right() * 0.5f;
            placed_ = true;
        }
        if (!ruler_on_) return;
        ImGui::TextDisabled("drag its ends in the view");
        for (int k = 0; k < 2; ++k) {
            ImGui::SetNextItemWidth(-FLT_MIN);
            ImGui::DragFloat3(k == 0 ? "##a" : "##b", &ends_[k].x, 0.01f, -1000.0f, 1000.0f, "%.2f");
        }
        const glm::vec3 d = ends_[1] - ends_[0];
        ImGui::Text("distance %.3f m", glm::length(d));
        ImGui::Text("level %.3f m   upright %.3f m", std::hypot(d.x, d.y), std::abs(d.z));
    }

    void ruler_view(ImDrawList* draw, ToolContext& c) {
        const render::Camera& camera = c.view.camera;
        const ImGuiIO& io = ImGui::GetIO();
        const ImU32 color = plot_color(3);
        ImVec2 p[2];
        const bool seen[2] = {to_window(camera, ends_[0], p[0]), to_window(camera, ends_[1], p[1])};
        if (seen[0] && seen[1]) {
            draw->AddLine(p[0], p[1], IM_COL32(0, 0, 0, 255), 4.0f);
            draw->AddLine(p[0], p[1], color, 2.0f);
            char text[32];
            std::snprintf(text, sizeof text, "%.3f m", glm::length(ends_[1] - ends_[0]));
            label(draw, ImVec2(0.5f * (p[0].x + p[1].x) + 6.0f, 0.5f * (p[0].y + p[1].y) + 4.0f), color, text);
        }
        // An end under the pointer takes the mouse from the view (the panel's way of saying it
        // wants it), and follows it in the plane through it that faces the camera.
        const float reach = 12.0f * c.scale;
        int hover = -1;
        for (int k = 0; k < 2; ++k) {
            if (!seen[k]) continue;
            draw->AddCircleFilled(p[k], 6.0f * c.scale, color);
            draw->AddCircle(p[k], 6.0f * c.scale, IM_COL32(0, 0, 0, 255), 16, 2.0f);
            const float dx = io.MousePos.x - p[k].x, dy = io.MousePos.y - p[k].y;
            if (dx * dx + dy * dy < reach * reach && !ImGui::IsWindowHovered(ImGuiHoveredFlags_AnyWindow)) hover = k;
        }
        if (dragging_ < 0 && hover >= 0 && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) dragging_ = hover;
        if (dragging_ >= 0 && !ImGui::IsMouseDown(ImGuiMouseButton_Left)) dragging_ = -1;
        if (hover >= 0 || dragging_ >= 0) ImGui::CaptureMouseFromApp(true);
        if (dragging_ < 0) return;
        glm::vec3 origin, direction;
        mouse_ray(camera, io.MousePos.x, io.MousePos.y, io.DisplaySize.x, io.DisplaySize.y, origin, direction);
        const glm::vec3 normal = camera.forward();
        const float along = glm::dot(direction, normal);
        if (std::abs(along) < 1e-6f) return;
        const float t = glm::dot(ends_[dragging_] - origin, normal) / along;
        if (t > 0.0f) ends_[dragging_] = origin + t * direction;
    }

    // --- The probe: one body's motion, live ---------------------------------------------------
    void probe_panel(Session& session) {
        const Series* series = session.series().series();
        std::vector<std::string> names;
        for (std::size_t k = Series::kFixedColumns; series && k + 5 < series->columns().size(); ++k) {
            const std::string& name = series->columns()[k].name;
            if (name.size() > 2 && name.compare(name.size() - 2, 2, " x") == 0) names.push_back(name.substr(0, name.size() - 2));
        }
        ImGui::Checkbox("Probe", &probe_on_);
        if (!probe_on_) return;
        if (names.empty()) {
            ImGui::TextDisabled("no moving body");
            return;
        }
        if (std::find(names.begin(), names.end(), probed_) == names.end()) probed_ = names.front();
        ImGui::SetNextItemWidth(-FLT_MIN);
        if (ImGui::BeginCombo("##probe", probed_.c_str())) {
            for (const std::string& name : names) {
                if (ImGui::Selectable(name.c_str(), name == probed_)) probed_ = name;
            }
            ImGui::EndCombo();
        }
        Reading r;
        if (!read(*series, session.world(), r)) return;
        ImGui::Text("centre   %.3f, %.3f, %.3f m", r.x.x, r.x.y, r.x.z);
        ImGui::Text("velocity %.3f, %.3f, %.3f m/s", r.v.x, r.v.y, r.v.z);
        ImGui::Text("speed    %.3f m/s", glm::length(r.v));
        ImGui::Text("acceleration %.3f, %.3f, %.3f m/s^2", r.a.x, r.a.y, r.a.z);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("The change of the velocity over the last tick, divided by the tick.");
        ImGui::Text("kinetic  %.4g J (1/2 m v^2 of the centre, m = %.4g kg)", 0.5 * r.mass * glm::dot(r.v, r.v), r.mass);
    }

    struct Reading {
        glm::dvec3 x{0.0}, v{0.0}, a{0.0};
        double mass = 0.0;
    };
    // The probed body's last row of the series (its centre and velocity), the velocity's change
    // over the last tick, and its mass from the world.
    bool read(const Series& series, const World& world, Reading& r) const {
        const auto column = [&](const std::string& name) {
            for (std::size_t k = 0; k < series.columns().size(); ++k) {
                if (series.columns()[k].name == name) return k;
            }
            return series.columns().size();
        };
        const std::size_t x = column(probed_ + " x");
        const std::size_t n = series.size();
        if (x + 5 >= series.columns().size() || n == 0) return false;
        const auto at = [&](std::size_t k, std::size_t row) { return series.column(k)[row]; };
        r.x = {at(x, n - 1), at(x + 1, n - 1), at(x + 2, n - 1)};
        r.v = {at(x + 3, n - 1), at(x + 4, n - 1), at(x + 5, n - 1)};
        if (n > 1) {
            const double dt = at(Series::kTime, n - 1) - at(Series::kTime, n - 2);
            if (dt > 0.0) r.a = (r.v - glm::dvec3(at(x + 3, n - 2), at(x + 4, n - 2), at(x + 5, n - 2))) / dt;
        }
        if (const auto id = world.find_rigid_body(probed_)) {
            r.mass = world.rigid_body(world.index(*id)).mass;
        } else if (const auto soft = world.find_soft_body(probed_)) {
            const SoftBody& body = world.soft_body(world.index(*soft));
            r.mass = double(body.mass) * double(body.particle_count());
        }
        return std::isfinite(r.x.x);
    }

    void probe_view(ImDrawList* draw, ToolContext& c) {
        if (!probe_on_ || probed_.empty()) return;
        const Series* series = c.session.series().series();
        Reading r;
        if (!series || !read(*series, c.session.world(), r)) return;
        ImVec2 p;
        if (!to_window(c.view.camera, glm::vec3(r.x), p)) return;
        const ImU32 color = plot_color(6);
        draw->AddCircle(p, 9.0f * c.scale, IM_COL32(0, 0, 0, 255), 20, 4.0f);
        draw->AddCircle(p, 9.0f * c.scale, color, 20, 2.0f);
        char text[64];
        std::snprintf(text, sizeof text, "%s  %.2f m/s", probed_.c_str(), glm::length(r.v));
        label(draw, ImVec2(p.x + 12.0f * c.scale, p.y - 0.5f * ImGui::GetFontSize()), color, text);
    }

    bool running_ = false;
    double start_ = 0.0, held_ = 0.0;  // s of world time: when it last started, and before that
    std::vector<double> laps_;
    std::string source_;  // the scene whose aids were last applied
    bool line_on_ = false, scale_on_ = false;
    float line_height_ = 1.0f;
    bool ruler_on_ = false, placed_ = false;
    glm::vec3 ends_[2]{};
    int dragging_ = -1;  // the end the mouse holds
    bool probe_on_ = false;
    std::string probed_;
};

const ToolRegistration kMeasureToolRegistered{57, [] { return std::unique_ptr<Tool>(new MeasureTool); }};

}  // namespace

}  // namespace softbody::app

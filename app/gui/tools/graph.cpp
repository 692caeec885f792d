// The Graph tool: any quantity of the run (gui/series_record.h: the energies, each moving body's
// centre and velocity, each named spring's length and force) against time or against another
// (a phase plot), over the last seconds; the energies as bars that add up (what dampers, drag,
// friction and contacts took is the dissipated bar); and Export CSV of every tick so far.
#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "gui/asset_files.h"
#include "gui/plot.h"
#include "gui/session.h"
#include "gui/tool.h"
#if defined(__EMSCRIPTEN__)
#include "web/browser.h"
#endif

namespace softbody::app {

namespace {

namespace fs = std::filesystem;

class GraphTool : public Tool {
public:
    const char* title() const override { return "Graph"; }
    bool open(const Session& session) const override { return !session.lesson().title.empty(); }
    void draw(ToolContext& c) override {
        const Series* series = c.session.series().series();
        if (!series || series->size() == 0) {
            ImGui::TextDisabled("no ticks yet");
            return;
        }
        if (c.session.loads() != loads_) {  // a new world: its first body's height again
            loads_ = c.session.loads();
            shown_.clear();
        }
        choose(*series);
        graph(c, *series);
        ImGui::Checkbox("Energy bars", &bars_);
        if (bars_) energy_bars(c, *series);
        export_button(c);
    }

private:
    static std::size_t find(const Series& series, const std::string& name) {
        for (std::size_t k = 0; k < series.columns().size(); ++k) {
            if (series.columns()[k].name == name) return k;
        }
        return series.columns().size();
    }

    // What is plotted (any columns but the time) and against what (the time or one column).
    void choose(const Series& series) {
        const auto& columns = series.columns();
        if (shown_.empty()) {
            // A body's height when there is a body, else the total energy.
            shown_.push_back(columns.size() > Series::kFixedColumns + 2 ? columns[Series::kFixedColumns + 2].name : "total");
        }
        std::string preview;
        for (const std::string& name : shown_) preview += (preview.empty() ? "" : ", ") + name;
        ImGui::TextUnformatted("Plot");
        ImGui::SetNextItemWidth(-FLT_MIN);
        if (ImGui::BeginCombo("##plot", preview.empty() ? "(nothing)" : preview.c_str())) {
            for (std::size_t k = 1; k < columns.size(); ++k) {
                const auto at = std::find(shown_.begin(), shown_.end(), columns[k].name);
                bool on = at != shown_.end();
                if (ImGui::Checkbox(columns[k].header().c_str(), &on)) {
                    if (on) shown_.push_back(columns[k].name);
                    else shown_.erase(at);
                }
            }
            ImGui::EndCombo();
        }
        ImGui::TextUnformatted("against");
        ImGui::SetNextItemWidth(-FLT_MIN);
        const std::size_t x = std::min(find(series, against_), columns.size() - 1);
        if (ImGui::BeginCombo("##against", columns[x].header().c_str())) {
            for (std::size_t k = 0; k < columns.size(); ++k) {
                if (ImGui::Selectable(columns[k].header().c_str(), k == x)) against_ = columns[k].name;
            }
            ImGui::EndCombo();
        }
        ImGui::TextUnformatted("over the last (s)");
        ImGui::SetNextItemWidth(-FLT_MIN);
        ImGui::SliderFloat("##window", &window_, 1.0f, 120.0f, "%.0f", ImGuiSliderFlags_Logarithmic);
    }

    void graph(ToolContext& c, const Series& series) {
        const auto& columns = series.columns();
        const std::size_t x = find(series, against_) < columns.size() ? find(series, against_) : Series::kTime;
        const std::vector<double>& time = series.column(Series::kTime);
        const double from = time.back() - double(window_);
        const std::size_t first = std::size_t(std::lower_bound(time.begin(), time.end(), from) - time.begin());
        std::vector<PlotLine> lines;
        std::string unit;
        bool one_unit = true;
        for (const std::string& name : shown_) {
            const std::size_t k = find(series, name);
            if (k >= columns.size()) continue;  // a thing no longer in the world
            // Each column keeps its colour and marker whatever else is shown.
            lines.push_back({name, &series.column(x), &series.column(k), first, k});
            if (lines.size() == 1) unit = columns[k].unit;
            one_unit = one_unit && columns[k].unit == unit;
        }
        const std::string y_title = lines.size() == 1 ? columns[find(series, lines[0].name)].header()
                                    : one_unit && !unit.empty() ? "(" + unit + ")"
                                                                : "(mixed units)";
        plot("graph", lines, columns[x].header(), y_title, 150.0f * c.scale);
    }

    // The energies now, as bars: kinetic + gravitational + elastic + dissipated = total, the
    // energy the world had at the start (and what a hand put in since).
    void energy_bars(ToolContext& c, const Series& series) {
        const std::size_t last = series.size() - 1;
        std::vector<PlotBar> bars;
        for (std::size_t k = Series::kKinetic; k <= Series::kTotal; ++k) {
            bars.push_back({series.columns()[k].name, series.column(k)[last], k});
        }
        char unit[48];
        std::snprintf(unit, sizeof unit, "J, at t = %.2f s", series.column(Series::kTime)[last]);
        bar_chart("bars", bars, unit, 130.0f * c.scale);
    }

    // Every tick so far to a new CSV file in the data folder (never over an existing one), or
    // in the page as a download.
    void export_button(ToolContext& c) {
        if (!ImGui::Button("Export CSV")) {
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("Every tick since the start, every column: a new file (a download in the page)");
            return;
        }
        std::string stem = fs::path(c.session.source()).stem().string();
        if (stem.empty()) stem = "run";
#if defined(__EMSCRIPTEN__)
        // The page: a download, which the browser puts where the person keeps downloads.
        const Series* series = c.session.series().series();
        browser::download(stem + ".csv", c.session.series().csv(), "text/csv");
        c.session.set_notice("Downloaded " + stem + ".csv (" + std::to_string(series ? series->size() : 0) + " rows, one a tick)");
#else
        std::error_code error;
        fs::create_directories(folder(), error);
        std::string path;
        for (int n = 1; n < 100000; ++n) {
            path = (fs::path(folder()) / (stem + "_" + std::to_string(n) + ".csv")).string();
            if (!fs::exists(path, error)) break;
        }
        c.session.export_series(path, false);
#endif
    }

    static std::string folder() { return (fs::path(presets_folder()).parent_path() / "data").string(); }

    std::vector<std::string> shown_;  // columns plotted, by name
    std::string against_ = "time";
    float window_ = 20.0f;
    bool bars_ = true;
    std::uint64_t loads_ = 0;  // the session's world the choice was made for
};

const ToolRegistration kGraphToolRegistered{55, [] { return std::unique_ptr<Tool>(new GraphTool); }};

}  // namespace

}  // namespace softbody::app

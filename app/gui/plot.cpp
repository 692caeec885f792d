#include "gui/plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace softbody::app {

namespace {

// Okabe and Ito's eight, black turned light grey for the panel's dark background.
constexpr ImU32 kPalette[] = {
    IM_COL32(230, 159, 0, 255),    // orange
    IM_COL32(86, 180, 233, 255),   // sky blue
    IM_COL32(0, 158, 115, 255),    // bluish green
    IM_COL32(240, 228, 66, 255),   // yellow
    IM_COL32(0, 114, 178, 255),    // blue
    IM_COL32(213, 94, 0, 255),     // vermillion
    IM_COL32(204, 121, 167, 255),  // reddish purple
    IM_COL32(225, 225, 225, 255),  // (black)
};
constexpr std::size_t kColors = sizeof kPalette / sizeof kPalette[0];
constexpr int kMarkers = 7;

std::string tick_text(double value, double step) {
    char text[32];
    if (std::abs(value) < step * 1e-6) value = 0.0;  // -0 and rounding dust read as 0
    std::snprintf(text, sizeof text, "%.4g", value);
    return text;
}

// The range of the finite values of the lines' drawn samples, through `pick` (x or y).
template <class Pick>
void range_of(const std::vector<PlotLine>& lines, Pick pick, double& lo, double& hi) {
    lo = std::numeric_limits<double>::infinity();
    hi = -lo;
    for (const PlotLine& line : lines) {
        const std::vector<double>& v = *pick(line);
        for (std::size_t i = line.first; i < v.size(); ++i) {
            if (!std::isfinite(v[i])) continue;
            lo = std::min(lo, v[i]);
            hi = std::max(hi, v[i]);
        }
    }
    if (!(lo <= hi)) lo = 0.0, hi = 1.0;
    if (hi - lo < 1e-12 * std::max(1.0, std::abs(hi))) {  // a flat line: a range around it
        const double pad = std::max(1e-3, std::abs(hi) * 0.1);
        lo -= pad;
        hi += pad;
    }
}

}  // namespace

ImU32 plot_color(std::size_t k) { return kPalette[k % kColors]; }

Marker plot_marker(std::size_t k) { return Marker(k % kMarkers); }

void draw_marker(ImDrawList* draw, ImVec2 at, Marker marker, ImU32 color, float size) {
    const float r = size * 0.5f;
    switch (marker) {
        case Marker::Circle: draw->AddCircleFilled(at, r, color, 12); break;
        case Marker::Square: draw->AddRectFilled(ImVec2(at.x - r, at.y - r), ImVec2(at.x + r, at.y + r), color); break;
        case Marker::TriangleUp:
            draw->AddTriangleFilled(ImVec2(at.x, at.y - r), ImVec2(at.x + r, at.y + r), ImVec2(at.x - r, at.y + r), color);
            break;
        case Marker::Diamond:
            draw->AddQuadFilled(ImVec2(at.x, at.y - r), ImVec2(at.x + r, at.y), ImVec2(at.x, at.y + r), ImVec2(at.x - r, at.y), color);
            break;
        case Marker::Cross:
            draw->AddLine(ImVec2(at.x - r, at.y - r), ImVec2(at.x + r, at.y + r), color, 2.0f);
            draw->AddLine(ImVec2(at.x - r, at.y + r), ImVec2(at.x + r, at.y - r), color, 2.0f);
            break;
        case Marker::TriangleDown:
            draw->AddTriangleFilled(ImVec2(at.x - r, at.y - r), ImVec2(at.x + r, at.y - r), ImVec2(at.x, at.y + r), color);
            break;
        case Marker::Plus:
            draw->AddLine(ImVec2(at.x - r, at.y), ImVec2(at.x + r, at.y), color, 2.0f);
            draw->AddLine(ImVec2(at.x, at.y - r), ImVec2(at.x, at.y + r), color, 2.0f);
            break;
    }
}

std::vector<double> plot_ticks(double lo, double hi, int count) {
    std::vector<double> ticks;
    if (!(hi > lo) || count < 1 || !std::isfinite(lo) || !std::isfinite(hi)) return ticks;
    const double rough = (hi - lo) / count;
    const double power = std::pow(10.0, std::floor(std::log10(rough)));
    const double fraction = rough / power;
    const double step = (fraction < 1.5 ? 1.0 : fraction < 3.5 ? 2.0 : fraction < 7.5 ? 5.0 : 10.0) * power;
    for (double t = std::ceil(lo / step) * step; t <= hi + step * 1e-9; t += step) ticks.push_back(t);
    return ticks;
}

void plot(const char* id, const std::vector<PlotLine>& lines, const std::string& x_title, const std::string& y_title,
          float height) {
    ImGui::PushID(id);
    const float font = ImGui::GetFontSize();
    ImGui::TextDisabled("%s", y_title.c_str());
    double x_lo, x_hi, y_lo, y_hi;
    range_of(lines, [](const PlotLine& l) { return l.x; }, x_lo, x_hi);
    range_of(lines, [](const PlotLine& l) { return l.y; }, y_lo, y_hi);
    const double y_pad = (y_hi - y_lo) * 0.05;
    y_lo -= y_pad;
    y_hi += y_pad;
    const std::vector<double> x_ticks = plot_ticks(x_lo, x_hi, 5), y_ticks = plot_ticks(y_lo, y_hi, 4);
    const double x_step = x_ticks.size() > 1 ? x_ticks[1] - x_ticks[0] : 1.0;
    const double y_step = y_ticks.size() > 1 ? y_ticks[1] - y_ticks[0] : 1.0;

    // The box, with room on the left for the y ticks' numbers and below for the x ticks'.
    float label_width = 0.0f;
    for (double t : y_ticks) label_width = std::max(label_width, ImGui::CalcTextSize(tick_text(t, y_step).c_str()).x);
    const ImVec2 start = ImGui::GetCursorScreenPos();
    const float width = ImGui::GetContentRegionAvail().x;
    const ImVec2 lo(start.x + label_width + 0.4f * font, start.y);
    const ImVec2 hi(start.x + width - 0.5f * font, start.y + height);
    ImDrawList* draw = ImGui::GetWindowDrawList();
    draw->AddRectFilled(lo, hi, IM_COL32(20, 24, 30, 255));
    const auto to_screen = [&](double x, double y) {
        return ImVec2(lo.x + float((x - x_lo) / (x_hi - x_lo)) * (hi.x - lo.x), hi.y - float((y - y_lo) / (y_hi - y_lo)) * (hi.y - lo.y));
    };
    const ImU32 grid = IM_COL32(70, 76, 86, 255), text = ImGui::GetColorU32(ImGuiCol_TextDisabled);
    for (double t : x_ticks) {
        const float x = to_screen(t, y_lo).x;
        draw->AddLine(ImVec2(x, lo.y), ImVec2(x, hi.y), grid);
        const std::string label = tick_text(t, x_step);
        draw->AddText(ImVec2(x - ImGui::CalcTextSize(label.c_str()).x * 0.5f, hi.y + 0.15f * font), text, label.c_str());
    }
    for (double t : y_ticks) {
        const float y = to_screen(x_lo, t).y;
        draw->AddLine(ImVec2(lo.x, y), ImVec2(hi.x, y), grid);
        const std::string label = tick_text(t, y_step);
        draw->AddText(ImVec2(lo.x - 0.3f * font - ImGui::CalcTextSize(label.c_str()).x, y - 0.5f * font), text, label.c_str());
    }
    draw->AddRect(lo, hi, IM_COL32(110, 116, 126, 255));

    // The lines: each run of finite samples, thinned to about two points a pixel; markers spaced
    // along it, each line's shifted so that lines on top of each other still show their shapes.
    draw->PushClipRect(lo, hi, true);
    const float marker_size = 0.45f * font;
    for (const PlotLine& line : lines) {
        const std::vector<double>& xs = *line.x;
        const std::vector<double>& ys = *line.y;
        const std::size_t n = std::min(xs.size(), ys.size());
        if (n <= line.first) continue;
        const std::size_t stride = std::max<std::size_t>(1, (n - line.first) / std::size_t(std::max(1.0f, 2.0f * (hi.x - lo.x))));
        const ImU32 color = plot_color(line.style);
        std::vector<ImVec2> run;
        const auto flush = [&] {
            if (run.size() > 1) draw->AddPolyline(run.data(), int(run.size()), color, 0, 2.0f);
            run.clear();
        };
        for (std::size_t i = line.first; i < n; i += stride) {
            if (!std::isfinite(xs[i]) || !std::isfinite(ys[i])) {
                flush();
                continue;
            }
            run.push_back(to_screen(xs[i], ys[i]));
        }
        if (run.size() == 1) draw_marker(draw, run[0], plot_marker(line.style), color, marker_size);  // a single point shows
        flush();
        const std::size_t every = std::max<std::size_t>(1, (n - line.first) / 6);
        for (std::size_t i = line.first + (every * (line.style % 3)) / 3; i < n; i += every) {
            if (std::isfinite(xs[i]) && std::isfinite(ys[i])) draw_marker(draw, to_screen(xs[i], ys[i]), plot_marker(line.style), color, marker_size);
        }
    }
    draw->PopClipRect();

    // Under the pointer: the nearest sample of any line, marked, with its values.
    ImGui::SetCursorScreenPos(start);
    ImGui::InvisibleButton("plot", ImVec2(width, height));
    if (ImGui::IsItemHovered()) {
        const ImVec2 mouse = ImGui::GetIO().MousePos;
        float best = 20.0f * 20.0f;
        const PlotLine* near_line = nullptr;
        std::size_t near_index = 0;
        for (const PlotLine& line : lines) {
            const std::size_t n = std::min(line.x->size(), line.y->size());
            for (std::size_t i = line.first; i < n; ++i) {
                if (!std::isfinite((*line.x)[i]) || !std::isfinite((*line.y)[i])) continue;
                const ImVec2 p = to_screen((*line.x)[i], (*line.y)[i]);
                const float d = (p.x - mouse.x) * (p.x - mouse.x) + (p.y - mouse.y) * (p.y - mouse.y);
                if (d < best) best = d, near_line = &line, near_index = i;
            }
        }
        if (near_line) {
            const ImVec2 p = to_screen((*near_line->x)[near_index], (*near_line->y)[near_index]);
            draw->AddCircle(p, marker_size, IM_COL32(255, 255, 255, 255), 12, 2.0f);
            ImGui::SetTooltip("%s\n%s = %.6g\n%s = %.6g", near_line->name.c_str(), x_title.c_str(), (*near_line->x)[near_index],
                              y_title.c_str(), (*near_line->y)[near_index]);
        }
    }
    ImGui::Dummy(ImVec2(width, 1.3f * font));  // the x ticks' numbers
    const float title_width = ImGui::CalcTextSize(x_title.c_str()).x;
    ImGui::SetCursorPosX(ImGui::GetCursorPosX() + std::max(0.0f, (width - title_width) * 0.5f));
    ImGui::TextDisabled("%s", x_title.c_str());

    // The legend: each line's shape and name, in its colour.
    for (std::size_t k = 0; k < lines.size(); ++k) {
        const std::string& name = lines[k].name;
        const float item = marker_size * 2.0f + ImGui::CalcTextSize(name.c_str()).x;
        if (k > 0) {
            const float next = ImGui::GetItemRectMax().x + ImGui::GetStyle().ItemSpacing.x * 2.0f + item;
            if (next < ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x) ImGui::SameLine(0.0f, ImGui::GetStyle().ItemSpacing.x * 2.0f);
        }
        const ImVec2 at = ImGui::GetCursorScreenPos();
        draw_marker(draw, ImVec2(at.x + marker_size * 0.6f, at.y + font * 0.5f), plot_marker(lines[k].style), plot_color(lines[k].style), marker_size);
        ImGui::Dummy(ImVec2(marker_size * 1.5f, font));
        ImGui::SameLine(0.0f, 0.0f);
        ImGui::TextColored(ImColor(plot_color(lines[k].style)), "%s", name.c_str());
    }
    ImGui::PopID();
}

void bar_chart(const char* id, const std::vector<PlotBar>& bars, const std::string& unit, float height) {
    if (bars.empty()) return;
    ImGui::PushID(id);
    const float font = ImGui::GetFontSize();
    double lo = 0.0, hi = 0.0;
    for (const PlotBar& bar : bars) {
        if (!std::isfinite(bar.value)) continue;
        lo = std::min(lo, bar.value);
        hi = std::max(hi, bar.value);
    }
    if (hi - lo < 1e-12) hi = lo + 1.0;
    const ImVec2 start = ImGui::GetCursorScreenPos();
    const float width = ImGui::GetContentRegionAvail().x;
    const float slot = width / float(bars.size());
    // The names under the bars, on two staggered rows when one row is too narrow for them.
    bool two_rows = false;
    for (const PlotBar& bar : bars) two_rows = two_rows || ImGui::CalcTextSize(bar.name.c_str()).x > slot * 0.95f;
    // Room above for the values and below for the names.
    const float top = start.y + 1.3f * font, bottom = start.y + height - (two_rows ? 2.5f : 1.3f) * font;
    ImDrawList* draw = ImGui::GetWindowDrawList();
    draw->AddRectFilled(ImVec2(start.x, top), ImVec2(start.x + width, bottom), IM_COL32(20, 24, 30, 255));
    const auto y_of = [&](double v) { return bottom - float((v - lo) / (hi - lo)) * (bottom - top); };
    const float zero = y_of(0.0);
    draw->AddLine(ImVec2(start.x, zero), ImVec2(start.x + width, zero), IM_COL32(150, 156, 166, 255));
    for (std::size_t k = 0; k < bars.size(); ++k) {
        const PlotBar& bar = bars[k];
        const float x0 = start.x + slot * float(k) + slot * 0.18f, x1 = start.x + slot * float(k + 1) - slot * 0.18f;
        const float y = std::isfinite(bar.value) ? y_of(bar.value) : zero;
        const ImU32 color = plot_color(bar.style);
        draw->AddRectFilled(ImVec2(x0, std::min(y, zero)), ImVec2(x1, std::max(y, zero)), color);
        char value[32];
        std::snprintf(value, sizeof value, "%.3g", bar.value);
        const float vw = ImGui::CalcTextSize(value).x;
        draw->AddText(ImVec2((x0 + x1 - vw) * 0.5f, std::min(y, zero) - 1.2f * font), ImGui::GetColorU32(ImGuiCol_Text), value);
        const float nw = ImGui::CalcTextSize(bar.name.c_str()).x;
        const float row = two_rows && k % 2 == 1 ? 1.2f * font : 0.0f;
        draw->AddText(ImVec2((x0 + x1 - nw) * 0.5f, bottom + 0.15f * font + row), ImGui::GetColorU32(ImGuiCol_Text), bar.name.c_str());
    }
    ImGui::Dummy(ImVec2(width, height));
    ImGui::TextDisabled("%s", unit.c_str());
    ImGui::PopID();
}

}  // namespace softbody::app

// A graph in the panel: lines of y against x with axes, ticks at round numbers, each axis named
// with its unit, a legend that names each line and marks it with its own shape (never by colour
// alone), and under the pointer the nearest point's values. Colours from the Okabe-Ito palette,
// which people with any of the common colour-vision deficiencies tell apart.
#pragma once

#include <imgui.h>

#include <cstddef>
#include <string>
#include <vector>

namespace softbody::app {

// Line k's colour (k wraps) and the shape that marks it.
ImU32 plot_color(std::size_t k);
enum class Marker { Circle, Square, TriangleUp, Diamond, Cross, TriangleDown, Plus };
Marker plot_marker(std::size_t k);
void draw_marker(ImDrawList* draw, ImVec2 at, Marker marker, ImU32 color, float size);

struct PlotLine {
    std::string name;                   // "kinetic", "bob z"
    const std::vector<double>* x = nullptr;
    const std::vector<double>* y = nullptr;
    std::size_t first = 0;              // the samples drawn: [first, size)
    std::size_t style = 0;              // its colour and marker (plot_color, plot_marker)
};

// Round tick positions covering [lo, hi], about `count` of them (steps of 1, 2 or 5 x 10^n).
std::vector<double> plot_ticks(double lo, double hi, int count);

// Draws the lines in a box the panel's width and `height` pixels high; x_title and y_title name
// the axes with their units ("time (s)"). Missing values (NaN) break a line.
void plot(const char* id, const std::vector<PlotLine>& lines, const std::string& x_title, const std::string& y_title,
          float height);

// Bars from zero, one per value, each named under it and its value above; colours by style.
struct PlotBar {
    std::string name;
    double value = 0.0;
    std::size_t style = 0;
};
void bar_chart(const char* id, const std::vector<PlotBar>& bars, const std::string& unit, float height);

}  // namespace softbody::app

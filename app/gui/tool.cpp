#include "gui/tool.h"

#include <algorithm>
#include <utility>

namespace softbody::app {

namespace {

// The registered tools; a function's static, so that it exists before any registration runs.
std::vector<std::pair<int, ToolMaker>>& registry() {
    static std::vector<std::pair<int, ToolMaker>> tools;
    return tools;
}

}  // namespace

ToolRegistration::ToolRegistration(int order, ToolMaker make) { registry().emplace_back(order, make); }

std::vector<std::unique_ptr<Tool>> make_tools() {
    std::vector<std::pair<int, ToolMaker>> ordered = registry();
    std::stable_sort(ordered.begin(), ordered.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<std::unique_ptr<Tool>> tools;
    for (const auto& [order, make] : ordered) tools.push_back(make());
    return tools;
}

}  // namespace softbody::app

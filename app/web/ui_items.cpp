// Where the panel's items are (browser.h, ui_items_json): Dear ImGui tells the functions below
// of every item it lays out and of its label, when it is built with IMGUI_ENABLE_TEST_ENGINE
// and the context asks for it (web/CMakeLists.txt builds the page's copy so). The browser tests
// tap a button by its label this way, as a person reads it, not at a position kept in the test.
#include <imgui.h>
#include <imgui_internal.h>

#include <cstdarg>
#include <cstdio>
#include <string>
#include <vector>

#include "web/browser.h"

namespace {

struct Item {
    ImGuiID id = 0;
    ImRect rect;
    std::string label;
    std::string window;
};

struct Items {
    int frame = -1;  // the frame they were laid out in
    std::vector<Item> items;
};

Items& items() {
    static Items all;
    return all;
}

void escape_into(std::string& out, const std::string& text) {
    for (const char ch : text) {
        if (ch == '"' || ch == '\\') {
            out += '\\';
            out += ch;
        } else if (static_cast<unsigned char>(ch) < 0x20) {
            char code[8];
            std::snprintf(code, sizeof code, "\\u%04x", ch);
            out += code;
        } else {
            out += ch;
        }
    }
}

}  // namespace

void ImGuiTestEngineHook_ItemAdd(ImGuiContext* context, const ImRect& rect, ImGuiID id) {
    Items& all = items();
    if (all.frame != context->FrameCount) {
        all.frame = context->FrameCount;
        all.items.clear();
    }
    Item item;
    item.id = id;
    item.rect = rect;
    if (ImGuiWindow* window = context->CurrentWindow) {
        item.window = window->Name;
        // A window's fold arrow has no label of its own: it is listed by its id's name.
        if (id == window->GetIDNoKeepAlive("#COLLAPSE")) item.label = "#COLLAPSE";
    }
    all.items.push_back(std::move(item));
}

void ImGuiTestEngineHook_ItemInfo(ImGuiContext* context, ImGuiID id, const char* label, ImGuiItemStatusFlags) {
    Items& all = items();
    if (all.frame != context->FrameCount || !label) return;
    for (auto it = all.items.rbegin(); it != all.items.rend(); ++it) {
        if (it->id == id) {
            it->label = label;
            // As a person reads it: without the part after "##" that only keeps the id apart. A
            // widget whose words stand above it (a key's slider, key_widgets.h) has only that
            // part: it is listed by it, the key's name.
            if (const auto hidden = it->label.find("##"); hidden == 0) it->label.erase(0, 2);
            else if (hidden != std::string::npos) it->label.erase(hidden);
            return;
        }
    }
}

void ImGuiTestEngineHook_Log(ImGuiContext*, const char*, ...) {}

const char* ImGuiTestEngine_FindItemDebugLabel(ImGuiContext*, ImGuiID id) {
    for (const Item& item : items().items) {
        if (item.id == id && !item.label.empty()) return item.label.c_str();
    }
    return nullptr;
}

namespace softbody::app::browser {

std::string ui_items_json() {
    ImGuiContext* context = ImGui::GetCurrentContext();
    if (!context) return "[]";
    context->TestEngineHookItems = true;  // from now on (the first question gets the next frame's)
    std::string out = "[";
    for (const Item& item : items().items) {
        if (item.label.empty()) continue;
        if (out.size() > 1) out += ',';
        out += "{\"label\":\"";
        escape_into(out, item.label);
        out += "\",\"window\":\"";
        escape_into(out, item.window);
        char numbers[128];
        std::snprintf(numbers, sizeof numbers, "\",\"x\":%.1f,\"y\":%.1f,\"w\":%.1f,\"h\":%.1f}", item.rect.Min.x, item.rect.Min.y,
                      item.rect.GetWidth(), item.rect.GetHeight());
        out += numbers;
    }
    return out + "]";
}

}  // namespace softbody::app::browser

#include "gui/script.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "gui/bindings.h"
#include "physics/error.h"

namespace softbody::app {

namespace {

// The keys a script can press, by the names gui/bindings.cpp gives them.
std::string key_names() {
    std::string names;
    for (const KeyBinding& binding : key_bindings()) {
        for (const char* name : binding.names) {
            if (name) names += (names.empty() ? "" : " ") + std::string(name);
        }
    }
    return names;
}

int button_number(const std::string& name) {
    if (name == "left") return 0;
    if (name == "right") return 1;
    if (name == "middle") return 2;
    return -1;
}

bool to_float(const std::string& text, float& out) {
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
    return ec == std::errc() && end == text.data() + text.size() && std::isfinite(out);
}

}  // namespace

std::optional<CompareSetup> parse_compare_setup(const std::string& text) {
    const auto colon = text.find(':');
    const auto integrator = integrator_from_string(text.substr(0, colon));
    if (!integrator) return std::nullopt;
    CompareSetup c{*integrator, true, 1};
    if (colon != std::string::npos) {
        const std::string n = text.substr(colon + 1);
        const auto [last, error] = std::from_chars(n.data(), n.data() + n.size(), c.substeps);
        if (error != std::errc() || last != n.data() + n.size() || c.substeps < 1 || c.substeps > 1000) return std::nullopt;
        c.auto_substeps = false;
    }
    return c;
}

std::vector<ScriptCommand> load_script(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw InputError(path + ": cannot open the script");
    std::vector<ScriptCommand> script;
    std::string text;
    std::size_t line_number = 0;
    while (std::getline(in, text)) {
        ++line_number;
        if (const auto hash = text.find('#'); hash != std::string::npos) text.resize(hash);
        std::istringstream line(text);
        std::vector<std::string> words;
        for (std::string word; line >> word;) words.push_back(word);
        if (words.empty()) continue;
        auto fail = [&](const std::string& what) -> void {
            throw InputError(path + ":" + std::to_string(line_number) + ": " + what);
        };
        ScriptCommand command;
        command.line = line_number;
        const auto [end, ec] = std::from_chars(words[0].data(), words[0].data() + words[0].size(), command.frame);
        if (ec != std::errc() || end != words[0].data() + words[0].size() || command.frame < 0) {
            fail("expected a frame number first, got '" + words[0] + "'");
        }
        if (words.size() < 2) fail("expected a command after the frame number");
        const std::string verb = words[1];
        command.args.assign(words.begin() + 2, words.end());
        const auto& args = command.args;
        InputEvent& e = command.input;
        if (verb == "move") {
            e.type = InputEvent::Type::Move;
            if (args.size() != 2 || !to_float(args[0], e.x) || !to_float(args[1], e.y)) fail("move needs X Y (fractions of the view)");
            command.verb = "input";
        } else if (verb == "press" || verb == "release") {
            e.type = verb == "press" ? InputEvent::Type::Press : InputEvent::Type::Release;
            if (args.empty() || (e.button = button_number(args[0])) < 0) fail(verb + " needs left, right or middle");
            for (std::size_t a = 1; a < args.size(); ++a) {
                if (args[a] == "shift") e.shift = true;
                else if (args[a] == "ctrl") e.ctrl = true;
                else fail("unknown modifier '" + args[a] + "' (shift or ctrl)");
            }
            command.verb = "input";
        } else if (verb == "scroll") {
            e.type = InputEvent::Type::Scroll;
            if (args.size() != 1 || !to_float(args[0], e.scroll)) fail("scroll needs one number");
            command.verb = "input";
        } else if (verb == "key") {
            e.type = InputEvent::Type::Key;
            if (args.size() != 1 || key_of_name(args[0]) == 0) fail("key needs one of " + key_names());
            e.key = key_of_name(args[0]);
            command.verb = "input";
        } else if (verb == "set") {
            if (args.size() != 2) fail("set needs KEY VALUE");
            command.verb = verb;
        } else if (verb == "load_scene" || verb == "load_mesh") {
            if (args.size() != 1) fail(verb + " needs a path");
            command.verb = verb;
        } else if (verb == "save_preset" || verb == "export_csv") {
            if (args.empty() || args.size() > 2 || (args.size() == 2 && args[1] != "overwrite")) {
                fail(verb + " needs a path, optionally followed by 'overwrite'");
            }
            command.verb = verb;
        } else if (verb == "inspect") {
            if (args.size() != 1) fail("inspect needs a particle number of the first soft body, or none");
            if (args[0] != "none") {
                std::uint32_t particle = 0;
                const auto [last, error] = std::from_chars(args[0].data(), args[0].data() + args[0].size(), particle);
                if (error != std::errc() || last != args[0].data() + args[0].size()) fail("inspect needs a particle number, or none");
            }
            command.verb = verb;
        } else if (verb == "compare") {
            // compare off | compare INTEGRATOR[:SUBSTEPS] ... (one to three)
            if (args.empty() || args.size() > 3) fail("compare needs one to three integrators (each NAME or NAME:SUBSTEPS), or off");
            if (!(args.size() == 1 && args[0] == "off")) {
                for (const std::string& a : args) {
                    if (!parse_compare_setup(a)) fail("compare: '" + a + "' is not an integrator (verlet, symplectic_euler, explicit_euler, rk4), optionally :SUBSTEPS");
                }
            }
            command.verb = verb;
        } else if (verb == "rewind") {
            float seconds = 0.0f;
            if (args.size() != 1 || !to_float(args[0], seconds) || seconds < 0.0f) fail("rewind needs a number of seconds, 0 or more");
            command.verb = verb;
        } else if (verb == "lesson") {
            if (args.size() != 1 || args[0].empty() || args[0].size() > 4 || args[0].find_first_not_of("0123456789") != std::string::npos) fail("lesson needs a number (softbody lessons)");
            command.verb = verb;
        } else if (verb == "record") {
            if (args.empty() || args.size() > 2 || (args[0] != "start" && args[0] != "stop") || (args[0] == "stop" && args.size() == 2)) {
                fail("record needs start [FILE.mp4] or stop");
            }
            command.verb = verb;
        } else if (verb == "add") {
            // add soft_ball | soft_cube | rigid_box | rigid_ball | mesh FILE: the Add menu
            const bool mesh = !args.empty() && args[0] == "mesh";
            if (args.empty() || (mesh ? args.size() != 2 : args.size() != 1) ||
                (!mesh && args[0] != "soft_ball" && args[0] != "soft_cube" && args[0] != "rigid_box" && args[0] != "rigid_ball")) {
                fail("add needs soft_ball, soft_cube, rigid_box, rigid_ball or mesh FILE");
            }
            command.verb = verb;
        } else if (verb == "reset" || verb == "step_back" || verb == "pause" || verb == "play" || verb == "loop") {
            if (!args.empty()) fail(verb + " takes no arguments");
            if (verb == "loop" && command.frame == 0) fail("loop needs a frame after 0");
            command.verb = verb;
        } else {
            fail("unknown command '" + verb + "'");
        }
        script.push_back(std::move(command));
    }
    std::stable_sort(script.begin(), script.end(), [](const auto& a, const auto& b) { return a.frame < b.frame; });
    return script;
}

}  // namespace softbody::app

// softbody lessons: the lessons in the addendum's order (physics/lesson.h), each with its
// number, title, scene file, the equations it is about and the first line of its text; with
// --json, one JSON object with all of that, the whole text and the closed form it compares.
#include <CLI/CLI.hpp>

#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli.h"
#include "commands.h"
#include "physics/lesson.h"
#include "physics/scene_io.h"

namespace softbody::app {

namespace {

std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

}  // namespace

int lessons_command(int argc, char** argv) {
    CLI::App app("Lists the lessons in the addendum's order: number, title, scene file, equations, and what each shows.\n"
                 "Open one with: softbody run --scene " + assets_dir() + "/scenes/FILE",
                 "softbody lessons");
    configure(app);
    bool as_json = false;
    app.add_flag("--json", as_json, "one JSON object instead of the text: every lesson's whole text and the closed form it compares");
    app.footer(exit_codes_help(false));
    if (!parse(app, argc, argv, 2)) return kOk;
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    std::size_t number = 0;
    for (const LessonInfo& lesson : lessons()) {
        ++number;
        const std::string path = assets_dir() + "/scenes/" + std::string(lesson.file);
        const Scene scene = load_scene(path);  // a lesson that does not load is bad input: exit 2
        if (as_json) {
            nlohmann::ordered_json entry = {{"number", number},          {"title", scene.title},
                                            {"scene", std::string(lesson.file)}, {"path", path},
                                            {"equation", std::string(lesson.equation)}, {"text", scene.text}};
            if (scene.expect) {
                const ClosedFormInfo* form = find_closed_form(scene.expect->kind);
                entry["expect"] = {{"kind", scene.expect->kind}, {"body", scene.expect->body},
                                   {"closed_form", form ? std::string(form->summary) : ""}};
            }
            list.push_back(entry);
        } else {
            std::cout << (number < 10 ? " " : "") << number << ". " << scene.title << "  (" << lesson.file << ", "
                      << lesson.equation << ")\n    " << first_line(scene.text) << "\n";
        }
    }
    if (as_json) std::cout << nlohmann::ordered_json{{"lessons", list}}.dump(2) << "\n";
    return kOk;
}

}  // namespace softbody::app

// The setup as a link's query or a command line (setup_link.h).
#include "gui/setup_link.h"

#include <algorithm>
#include <filesystem>

#include "cli.h"
#include "gui/session.h"
#include "physics/lesson.h"

namespace softbody::app {

namespace {

bool plain_for_query(char ch) {
    return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '-' || ch == '_' ||
           ch == '.' || ch == '~' || ch == '/' || ch == ':' || ch == ',' || ch == '=';
}

std::string query_escape(const std::string& text, bool is_name) {
    static const char* hex = "0123456789ABCDEF";
    std::string out;
    for (const char ch : text) {
        if (plain_for_query(ch) && !(is_name && ch == '=')) {
            out += ch;
        } else {
            const auto byte = static_cast<unsigned char>(ch);
            out += '%';
            out += hex[byte >> 4];
            out += hex[byte & 15];
        }
    }
    return out;
}

std::string shell_word(const std::string& word) {
    const bool plain = !word.empty() && std::all_of(word.begin(), word.end(), [](char ch) {
        return plain_for_query(ch) || ch == '+' || ch == '@' || ch == '%';
    });
    if (plain) return word;
    std::string out = "'";
    for (const char ch : word) out += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
    return out + "'";
}

}  // namespace

Setup current_setup(const Session& session, const SceneOptions& launch) {
    Setup setup;
    const ChangedKeys changed = session.changed_keys();
    const auto changed_later = [&](const std::string& assignment) {
        const std::string key = assignment.substr(0, assignment.find('='));
        return std::any_of(changed.keys.begin(), changed.keys.end(), [&](const auto& k) { return k.first == key; });
    };
    if (session.loads() <= 1) {
        // The first world: what the app was started with (its --set keys are the world's start).
        if (launch.lesson != 0) setup.args.emplace_back("lesson", std::to_string(launch.lesson));
        else if (!launch.scene.empty()) setup.args.emplace_back("scene", launch.scene);
        if (!launch.mesh.empty()) setup.args.emplace_back("mesh", launch.mesh);
        for (const std::string& assignment : launch.sets) {
            if (!changed_later(assignment)) setup.args.emplace_back("set", assignment);
        }
    } else if (const std::size_t lesson = lesson_number(session.source());
               lesson != 0 && std::filesystem::path(session.source()).lexically_normal() ==
                                  std::filesystem::path(lesson_path(std::int64_t(lesson))).lexically_normal()) {
        setup.args.emplace_back("lesson", std::to_string(lesson));
    } else if (const std::string bundled = bundled_name(session.source());
               !bundled.empty() && std::filesystem::path(bundled).extension() == ".json") {
        setup.args.emplace_back("scene", bundled);
    } else {
        setup.lost = "The world came from " + (session.source().empty() ? std::string("a file") : session.source()) +
                     ", which a link cannot carry: download the preset and send the file instead.";
    }
    for (const auto& [key, value] : changed.keys) setup.args.emplace_back("set", key + "=" + value);
    if (setup.lost.empty() && (changed.added != 0 || changed.removed != 0)) {
        setup.lost = "Bodies or springs were added or taken out, which a link cannot carry: download the preset "
                     "to keep them.";
    }
    return setup;
}

std::string setup_query(const Setup& setup) {
    std::string query;
    for (const auto& [name, value] : setup.args) {
        if (!query.empty()) query += '&';
        query += query_escape(name, true) + '=' + query_escape(value, false);
    }
    return query;
}

std::string setup_command(const Setup& setup) {
    std::string command = "softbody run";
    for (const auto& [name, value] : setup.args) command += " --" + name + ' ' + shell_word(value);
    return command;
}

}  // namespace softbody::app

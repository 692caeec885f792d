#include "physics/scene_io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "message_text.h"
#include "physics/error.h"
#include "physics/generated.h"
#include "physics/lesson.h"
#include "text_file.h"

namespace softbody {

namespace {

using nlohmann::json;
namespace fs = std::filesystem;

constexpr std::size_t kMaxSceneBytes = 1 << 20;  // a scene is a few hundred bytes
constexpr int kMaxDepth = 8;                      // a scene is one flat object

std::size_t line_of_offset(const std::string& text, std::size_t offset) {
    offset = std::min(offset, text.size());
    return 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + static_cast<long>(offset), '\n'));
}

// Line where "key" first appears, so an error can point at it.
std::string where(const std::string& origin, const std::string& text, const std::string& key) {
    const auto at = text.find("\"" + key + "\"");
    if (at == std::string::npos) return origin;
    return origin + ":" + std::to_string(line_of_offset(text, at));
}

std::string type_name(const json& value) {
    if (value.is_boolean()) return "true/false";
    if (value.is_number()) return "a number";
    return value.type_name();
}

// The command-line text for a JSON value of the key's type (set_param then checks the range).
std::string value_text(const ParamInfo& info, const json& value) {
    auto fail = [&](const char* expected) -> std::string {
        throw InputError("parameter '" + std::string(info.key) + "': expected " + expected +
                         (info.zero_word.empty() ? "" : " or \"" + std::string(info.zero_word) + "\"") + ", got " +
                         type_name(value));
    };
    if (!info.zero_word.empty() && value.is_string() && value.get<std::string>() == info.zero_word) return std::string(info.zero_word);
    auto number = [](const json& v) {
        std::ostringstream out;
        out.precision(9);
        out << v.get<double>();
        return out.str();
    };
    switch (info.type) {
        case ParamType::Float:
            if (!value.is_number()) return fail("a number");
            return number(value);
        case ParamType::Int:
            if (!value.is_number_integer()) return fail("a whole number");
            return value.dump();  // exact, even beyond the range of long long (set_param refuses it)
        case ParamType::Bool:
            if (!value.is_boolean()) return fail("true or false");
            return value.get<bool>() ? "true" : "false";
        case ParamType::Vec3:
        case ParamType::OptionalVec3:
            if (info.type == ParamType::OptionalVec3 && value.is_string() && value.get<std::string>() == "none") return "none";
            if (!value.is_array() || value.size() != 3 || !value[0].is_number() || !value[1].is_number() ||
                !value[2].is_number()) {
                return fail(info.type == ParamType::OptionalVec3 ? "an array of three numbers [x, y, z] or \"none\""
                                                                 : "an array of three numbers [x, y, z]");
            }
            return number(value[0]) + "," + number(value[1]) + "," + number(value[2]);
        case ParamType::String:
        case ParamType::Integrator:
        case ParamType::Axis:
            if (!value.is_string()) return fail("a string");
            return value.get<std::string>();
        case ParamType::IndexList: {
            if (!value.is_array()) return fail("an array of vertex indices");
            std::string out;
            for (const auto& item : value) {
                if (!item.is_number_integer()) return fail("an array of vertex indices (whole numbers)");
                if (!out.empty()) out += ',';
                out += item.dump();
            }
            return out;
        }
    }
    return {};
}

json value_json(const Params& params, const ParamInfo& info) {
    const std::string text = param_text(params, info.key);
    if (!info.zero_word.empty() && text == info.zero_word) return json(text);
    switch (info.type) {
        case ParamType::Float: return json(std::stod(text));
        case ParamType::Int: return json(std::stoll(text));
        case ParamType::Bool: return json(text == "true");
        case ParamType::Vec3:
        case ParamType::OptionalVec3: {
            json v = json::array();
            std::istringstream parts(text);
            for (std::string part; std::getline(parts, part, ',');) v.push_back(std::stod(part));
            return v;
        }
        case ParamType::String:
        case ParamType::Integrator:
        case ParamType::Axis: return json(text);
        case ParamType::IndexList: return json(params.pinned);
    }
    return {};
}

// A body's mesh without the keys that say how big it is and which way is up: fitted
// (fit_brought_mesh), each part only where the file says nothing of it.
void fit_unless_given(const json& keys, Params& params) {
    Params fitted = params;
    fit_brought_mesh(fitted);
    if (!keys.contains("scale")) params.scale = fitted.scale;
    if (!keys.contains("rotation") && !keys.contains("up_axis")) params.up_axis = fitted.up_axis;
}

[[noreturn]] void io_error(const std::string& path, const std::string& what) {
    throw InputError(path + ": " + what + " (" + std::strerror(errno) + ")");
}

std::string number_text(const json& v) {
    std::ostringstream out;
    out.precision(17);
    out << v.get<double>();
    return out.str();
}

// Where in the text a nested key is: the line of the first "key" after `from` (an offset), so
// an error inside the third rigid body points at that body's line, not the first body's.
std::string where_after(const std::string& origin, const std::string& text, std::size_t from, const std::string& key) {
    const auto at = text.find("\"" + key + "\"", std::min(from, text.size()));
    if (at == std::string::npos) return origin + ":" + std::to_string(line_of_offset(text, from));
    return origin + ":" + std::to_string(line_of_offset(text, at));
}

// The offset of the `index`-th object of the array under `array_key`, roughly: where its name
// (or, without one, the array) appears. For pointing errors at a line.
std::size_t element_offset(const std::string& text, const std::string& array_key, const json& element) {
    const auto array_at = text.find("\"" + array_key + "\"");
    std::size_t from = array_at == std::string::npos ? 0 : array_at;
    if (element.is_object() && element.contains("name") && element["name"].is_string()) {
        const auto named = text.find("\"" + element["name"].get<std::string>() + "\"", from);
        if (named != std::string::npos) from = named;
    }
    return from;
}

std::string relative_to(const std::string& origin, const std::string& path) {
    if (path.empty() || !fs::path(path).is_relative() || is_generated(path)) return path;
    const fs::path folder = fs::path(origin).parent_path();
    return folder.empty() ? path : (folder / path).lexically_normal().string();
}

// A JSON value as command-line text for a rigid body's key (set_rigid_key checks it).
std::string rigid_value_text(const RigidBodyDef& def, const RigidKeyInfo& info, const json& value) {
    auto fail = [&](const char* expected) -> std::string {
        throw InputError("rigid body '" + printable(def.name) + "', key '" + std::string(info.key) + "': expected " +
                         expected + ", got " + type_name(value));
    };
    auto numbers = [&](std::size_t count, const char* expected) {
        if (!value.is_array() || value.size() != count) return fail(expected);
        std::string out;
        for (const auto& item : value) {
            if (!item.is_number()) return fail(expected);
            out += (out.empty() ? "" : ",") + number_text(item);
        }
        return out;
    };
    switch (info.type) {
        case RigidKeyType::Number:
        case RigidKeyType::PositiveNumber:
            if (!value.is_number()) return fail("a number");
            return number_text(value);
        case RigidKeyType::Vec3: return numbers(3, "an array of three numbers [x, y, z]");
        case RigidKeyType::Quat: return numbers(4, "an array of four numbers [w, x, y, z]");
        case RigidKeyType::Bool:
            if (!value.is_boolean()) return fail("true or false");
            return value.get<bool>() ? "true" : "false";
        case RigidKeyType::Shape:
        case RigidKeyType::Text:
            if (!value.is_string()) return fail("a string");
            return value.get<std::string>();
    }
    return {};
}

// A rigid body's key as JSON, straight from its field (doubles written to full precision), or
// null when the key is not set.
json rigid_value_json(const RigidBodyDef& def, std::string_view key) {
    const auto vec = [](const Vec3d& v) { return json::array({v.x, v.y, v.z}); };
    if (key == "shape") return std::string(to_string(def.shape));
    if (key == "size") return def.size ? vec(*def.size) : json();
    if (key == "radius") return def.radius ? json(*def.radius) : json();
    if (key == "height") return def.height ? json(*def.height) : json();
    if (key == "mesh") return def.mesh.empty() ? json() : json(def.mesh);
    if (key == "scale") return def.shape == ShapeKind::Mesh || def.scale != 1.0 ? json(def.scale) : json();  // set on any shape: kept
    if (key == "mass") return def.mass ? json(*def.mass) : json();
    if (key == "density") return def.density ? json(*def.density) : json();
    if (key == "position") return def.position ? vec(*def.position) : json();
    if (key == "orientation") return json::array({def.orientation.w, def.orientation.x, def.orientation.y, def.orientation.z});
    if (key == "velocity") return vec(def.velocity);
    if (key == "angular_velocity") return vec(def.angular_velocity);
    if (key == "fixed") return def.fixed;
    if (key == "restitution") return def.restitution ? json(*def.restitution) : json();
    if (key == "friction") return def.friction ? json(*def.friction) : json();
    if (key == "drag_coefficient") return def.drag_coefficient;
    if (key == "rolling_resistance") return def.rolling_resistance;
    if (key == "color") return def.color ? vec(*def.color) : json();
    return json();  // "rotation": kept as the orientation
}

RigidBodyDef parse_rigid_body(const json& element, const std::string& origin, const std::string& text,
                              std::size_t at) {
    if (!element.is_object()) throw InputError(origin + ":" + std::to_string(line_of_offset(text, at)) + ": each of \"rigid_bodies\" must be an object {\"name\": ..., \"shape\": ...}");
    RigidBodyDef def;
    if (!element.contains("name") || !element["name"].is_string() || element["name"].get<std::string>().empty()) {
        throw InputError(origin + ":" + std::to_string(line_of_offset(text, at)) + ": a rigid body needs a \"name\" (a string)");
    }
    def.name = element["name"].get<std::string>();
    // The shape first: the keys that follow are checked against it.
    if (element.contains("shape")) {
        try {
            set_rigid_key(def, "shape", rigid_value_text(def, *find_rigid_key("shape"), element["shape"]));
        } catch (const InputError& e) {
            throw InputError(where_after(origin, text, at, "shape") + ": " + e.what());
        }
    }
    if (element.contains("orientation") && element.contains("rotation")) {
        throw InputError(where_after(origin, text, at, "rotation") + ": rigid body '" + printable(def.name) +
                         "': give 'orientation' or 'rotation', not both");
    }
    for (const auto& [key, value] : element.items()) {
        if (key == "name" || key == "shape") continue;
        const RigidKeyInfo* info = find_rigid_key(key);
        try {
            if (!info) set_rigid_key(def, key, "");  // refused, with the list of keys
            set_rigid_key(def, key, rigid_value_text(def, *info, value));
        } catch (const InputError& e) {
            throw InputError(where_after(origin, text, at, key) + ": " + e.what());
        }
    }
    def.mesh = relative_to(origin, def.mesh);
    return def;
}

SpringEndDef parse_spring_end(const json& value, const std::string& where, const char* name) {
    const std::string what = where + ": spring end '" + name + "'";
    if (!value.is_object()) throw InputError(what + " must be an object {\"body\": NAME, \"point\": [x, y, z]} or {\"body\": NAME, \"vertex\": K}");
    SpringEndDef end;
    for (const auto& [key, item] : value.items()) {
        if (key == "body") {
            if (!item.is_string() || item.get<std::string>().empty()) throw InputError(what + ": \"body\" must be a body's name");
            end.body = item.get<std::string>();
        } else if (key == "point") {
            if (!item.is_array() || item.size() != 3 || !item[0].is_number() || !item[1].is_number() || !item[2].is_number()) {
                throw InputError(what + ": \"point\" must be an array of three numbers [x, y, z]");
            }
            const Vec3d p{item[0].get<double>(), item[1].get<double>(), item[2].get<double>()};
            if (!is_finite(p) || length(p) > 1e6) throw InputError(what + ": \"point\" must be finite and within 1e6 m");
            end.point = p;
        } else if (key == "vertex") {
            if (!item.is_number_integer() || item.get<std::int64_t>() < 0) {
                throw InputError(what + ": \"vertex\" must be a vertex index (a whole number from 0)");
            }
            end.vertex = item.get<std::int64_t>();
        } else {
            throw InputError(what + ": unknown key '" + printable(key) + "' (body, point, vertex)");
        }
    }
    if (end.point && end.vertex) throw InputError(what + ": give a \"point\" or a \"vertex\", not both");
    return end;
}

SpringDef parse_spring(const json& element, const std::string& where) {
    if (!element.is_object()) throw InputError(where + ": each of \"springs\" must be an object {\"a\": ..., \"b\": ..., \"stiffness\": k}");
    SpringDef def;
    const auto number = [&](const std::string& key, const json& v, double max) {
        if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < 0.0 || v.get<double>() > max) {
            throw InputError(where + ": spring key '" + key + "' must be a number from 0 to " + number_text(json(max)));
        }
        return v.get<double>();
    };
    for (const auto& [key, value] : element.items()) {
        if (key == "a") def.a = parse_spring_end(value, where, "a");
        else if (key == "b") def.b = parse_spring_end(value, where, "b");
        else if (key == "stiffness") def.stiffness = number(key, value, 1e7);
        else if (key == "damping") def.damping = number(key, value, 1e6);
        else if (key == "rest_length") def.rest_length = number(key, value, 1e6);
        else throw InputError(where + ": unknown spring key '" + printable(key) + "' (a, b, stiffness, damping, rest_length)");
    }
    if (!element.contains("a") || !element.contains("b")) throw InputError(where + ": a spring needs both ends, \"a\" and \"b\"");
    if (!def.stiffness) throw InputError(where + ": a spring needs \"stiffness\" (N/m)");
    return def;
}

// "expect": { "kind": ..., "body": ..., "slope": ... }, a lesson's closed form (lesson.h). The
// names are checked against the scene's bodies once they are read (check_expect_names).
LessonExpect parse_expect(const json& value, const std::string& where) {
    const std::string what = where + ": key 'expect'";
    std::string kinds;
    for (const ClosedFormInfo& form : closed_forms()) kinds += (kinds.empty() ? "" : ", ") + std::string(form.kind);
    if (!value.is_object()) {
        throw InputError(what + ": expected an object {\"kind\": ..., \"body\": NAME}, got " + type_name(value));
    }
    LessonExpect expect;
    for (const auto& [key, item] : value.items()) {
        std::string* field = key == "kind" ? &expect.kind : key == "body" ? &expect.body : key == "slope" ? &expect.slope : nullptr;
        if (!field) throw InputError(what + ": unknown key '" + printable(key) + "' (kind, body, slope)");
        if (!item.is_string() || item.get<std::string>().empty()) {
            throw InputError(what + ": \"" + key + "\" must be a non-empty string, got " + type_name(item));
        }
        *field = item.get<std::string>();
    }
    const ClosedFormInfo* form = find_closed_form(expect.kind);
    if (expect.kind.empty()) throw InputError(what + ": needs a \"kind\" (" + kinds + ")");
    if (!form) throw InputError(what + ": unknown kind '" + printable(expect.kind) + "' (" + kinds + ")");
    if (expect.body.empty()) throw InputError(what + ": kind '" + expect.kind + "' needs a \"body\" (" + std::string(form->body) + ")");
    if (!form->takes_slope && !expect.slope.empty()) throw InputError(what + ": kind '" + expect.kind + "' takes no \"slope\"");
    return expect;
}

// The bodies "expect" names exist, of the kind its closed form reads.
void check_expect_names(const Scene& scene, const std::string& where) {
    const LessonExpect& expect = *scene.expect;
    const ClosedFormInfo& form = *find_closed_form(expect.kind);
    const auto rigid = [&](const std::string& name) {
        return std::any_of(scene.rigid_bodies.begin(), scene.rigid_bodies.end(), [&](const RigidBodyDef& b) { return b.name == name; });
    };
    const std::vector<std::string> names = body_names(scene);
    const bool exists = std::find(names.begin(), names.end(), expect.body) != names.end();
    const std::string what = where + ": key 'expect': ";
    if (!exists) throw InputError(what + "there is no body named '" + printable(expect.body) + "'");
    if (form.rigid_body && !rigid(expect.body)) throw InputError(what + "'" + printable(expect.body) + "' must be a rigid body for '" + expect.kind + "'");
    if (!form.rigid_body && rigid(expect.body)) throw InputError(what + "'" + printable(expect.body) + "' must be a soft body for '" + expect.kind + "'");
    if (!expect.slope.empty() && !rigid(expect.slope)) throw InputError(what + "there is no rigid body named '" + printable(expect.slope) + "' (the slope)");
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& origin, const Scene& base) {
    if (text.size() > kMaxSceneBytes) {
        throw InputError(origin + ": too large for a scene file (" + std::to_string(text.size()) + " bytes)");
    }
    json root;
    try {
        root = json::parse(text, [](int depth, json::parse_event_t, json&) {
            if (depth > kMaxDepth) throw InputError("nested too deeply for a scene file");
            return true;
        });
    } catch (const json::parse_error& e) {
        std::string message = e.what();
        if (const auto at = message.find("; "); at != std::string::npos) message = message.substr(at + 2);
        throw InputError(origin + ":" + std::to_string(line_of_offset(text, e.byte ? e.byte - 1 : 0)) +
                         ": malformed JSON: " + printable(message, 200));
    } catch (const json::out_of_range& e) {
        // A number beyond double ("1e400"): reported without a position, so the line is the
        // one where its text first appears.
        std::string message = e.what();
        if (const auto at = message.find("] "); at != std::string::npos) message = message.substr(at + 2);
        std::string where_it_is = origin;
        if (const auto open = message.find('\''), close = message.rfind('\'');
            open != std::string::npos && close > open) {
            if (const auto at = text.find(message.substr(open + 1, close - open - 1)); at != std::string::npos) {
                where_it_is += ":" + std::to_string(line_of_offset(text, at));
            }
        }
        throw InputError(where_it_is + ": malformed JSON: " + printable(message, 120));
    } catch (const json::exception& e) {
        throw InputError(origin + ": malformed JSON: " + printable(e.what(), 120));
    } catch (const InputError& e) {
        throw InputError(origin + ": " + e.what());
    }
    if (!root.is_object()) throw InputError(origin + ": a scene file must be a JSON object {\"key\": value, ...}");

    Scene scene = base;
    Params& params = scene.params;
    for (const auto& [key, value] : root.items()) {
        if (key == "rigid_bodies" || key == "soft_bodies" || key == "springs") {
            if (!value.is_array()) throw InputError(where(origin, text, key) + ": \"" + key + "\" must be an array");
            continue;
        }
        // A lesson's words and its closed form: for the reader and the lesson meter, not the physics.
        if (key == "title" || key == "text") {
            if (!value.is_string()) throw InputError(where(origin, text, key) + ": key '" + key + "': expected a string, got " + type_name(value));
            (key == "title" ? scene.title : scene.text) = value.get<std::string>();
            continue;
        }
        if (key == "expect") {
            scene.expect = parse_expect(value, where(origin, text, key));
            continue;
        }
        const ParamInfo* info = find_param(key);
        if (!info) {
            std::string message = where(origin, text, key) + ": unknown key '" + printable(key) + "'";
            if (auto hint = closest_key(key); !hint.empty()) message += " (did you mean '" + std::string(hint) + "'?)";
            else message += " (besides the keys of params: soft_bodies, rigid_bodies, springs, title, text, expect)";
            throw InputError(message);
        }
        try {
            set_param(params, key, value_text(*info, value));
        } catch (const InputError& e) {
            throw InputError(where(origin, text, key) + ": " + e.what());
        }
    }
    if (root.contains("position") && root.contains("init_height")) {
        throw InputError(where(origin, text, "position") + ": soft body 'body': give 'position' or 'init_height', not both");
    }
    if (root.contains("mesh")) {
        params.mesh = relative_to(origin, params.mesh);
        fit_unless_given(root, params);
    }

    if (root.contains("soft_bodies")) {
        scene.soft_bodies.clear();
        for (const json& element : root["soft_bodies"]) {
            const std::size_t at = element_offset(text, "soft_bodies", element);
            const std::string line = origin + ":" + std::to_string(line_of_offset(text, at));
            if (!element.is_object() || !element.contains("name") || !element["name"].is_string() ||
                element["name"].get<std::string>().empty()) {
                throw InputError(line + ": each of \"soft_bodies\" must be an object with a \"name\" and a \"mesh\"");
            }
            SoftBodyScene body;
            body.name = element["name"].get<std::string>();
            for (const auto& [key, value] : element.items()) {
                if (key == "name") continue;
                const ParamInfo* info = find_param(key);
                if (!info || info->scope != ParamScope::Body) {
                    throw InputError(where_after(origin, text, at, key) + ": soft body '" + printable(body.name) + "': '" +
                                     printable(key) + "' is " + (info ? "a world key: set it at the top level" : "not a key of a soft body"));
                }
                try {
                    set_param(body.params, key, value_text(*info, value));
                } catch (const InputError& e) {
                    throw InputError(where_after(origin, text, at, key) + ": soft body '" + printable(body.name) + "': " + e.what());
                }
            }
            if (body.params.mesh.empty()) throw InputError(line + ": soft body '" + printable(body.name) + "' needs a \"mesh\"");
            if (element.contains("position") && element.contains("init_height")) {
                throw InputError(where_after(origin, text, at, "position") + ": soft body '" + printable(body.name) +
                                 "': give 'position' or 'init_height', not both");
            }
            body.params.mesh = relative_to(origin, body.params.mesh);
            fit_unless_given(element, body.params);
            scene.soft_bodies.push_back(std::move(body));
        }
    }
    if (root.contains("rigid_bodies")) {
        scene.rigid_bodies.clear();
        for (const json& element : root["rigid_bodies"]) {
            scene.rigid_bodies.push_back(parse_rigid_body(element, origin, text, element_offset(text, "rigid_bodies", element)));
        }
    }
    if (root.contains("springs")) {
        scene.springs.clear();
        std::size_t from = text.find("\"springs\"");
        for (const json& element : root["springs"]) {
            const std::size_t at = text.find("{", from == std::string::npos ? 0 : from + 1);
            from = at == std::string::npos ? from : at;
            scene.springs.push_back(parse_spring(element, origin + ":" + std::to_string(line_of_offset(text, from))));
            // Past this spring's ends ("a": {...}, "b": {...}) to the next spring's brace.
            for (int skip = 0; skip < 2 && from != std::string::npos; ++skip) from = text.find("}", from + 1);
        }
    }

    // Names: every body has one, and no two share it.
    std::vector<std::string> names = body_names(scene);
    std::sort(names.begin(), names.end());
    if (const auto twin = std::adjacent_find(names.begin(), names.end()); twin != names.end()) {
        throw InputError(where(origin, text, *twin) + ": two bodies are named '" + printable(*twin) +
                         "' (the soft body of the flat keys is 'body'); names must be unique");
    }
    if (scene.expect) check_expect_names(scene, where(origin, text, "expect"));
    return scene;
}

void fit_brought_mesh(Params& params) {
    params.scale = 0.0f;  // "auto"
    params.up_axis = "y";
    params.rotation = {};
}

Scene load_scene(const std::string& path, const Scene& base) {
    if (is_generated(path)) return generated_scene(path, base);  // "pile:100", "cloud:2500": made, not read
    return parse_scene(read_text_file(path, kMaxSceneBytes, "scene file"), path, base);
}

std::vector<std::string> body_names(const Scene& scene) {
    std::vector<std::string> names;
    if (!scene.params.mesh.empty()) names.push_back("body");
    for (const auto& body : scene.soft_bodies) names.push_back(body.name);
    for (const auto& body : scene.rigid_bodies) names.push_back(body.name);
    return names;
}

void set_scene_key(Scene& scene, std::string_view key, std::string_view text) {
    const auto dot = key.find('.');
    if (dot == std::string_view::npos) {
        set_param(scene.params, key, text);
        return;
    }
    const std::string name(key.substr(0, dot));
    const std::string_view sub = key.substr(dot + 1);
    const auto body_key = [&](Params& params) {
        const ParamInfo* info = find_param(sub);
        if (info && info->scope == ParamScope::World) {
            throw InputError("'" + std::string(sub) + "' is a world key: set it as --set " + std::string(sub) + "=VALUE");
        }
        set_param(params, sub, text);
    };
    if (name == "body" && !scene.params.mesh.empty()) return body_key(scene.params);
    for (SoftBodyScene& body : scene.soft_bodies) {
        if (body.name == name) return body_key(body.params);
    }
    for (RigidBodyDef& body : scene.rigid_bodies) {
        if (body.name == name) return set_rigid_key(body, sub, text);
    }
    std::string known;
    for (const std::string& n : body_names(scene)) known += (known.empty() ? "" : ", ") + n;
    throw InputError("'" + printable(key) + "': there is no body named '" + printable(name) + "'" +
                     (known.empty() ? std::string(" (the scene has no bodies)") : " (bodies: " + known + ")"));
}

WorldDef make_world_def(const Scene& scene) {
    WorldDef def;
    def.params = scene.params;
    if (!scene.params.mesh.empty()) def.soft_bodies.push_back(SoftBodyDef{"body", scene.params, open_mesh(scene.params.mesh)});
    for (const SoftBodyScene& body : scene.soft_bodies) {
        Mesh mesh;
        try {
            mesh = open_mesh(body.params.mesh);
        } catch (const InputError& e) {
            throw InputError("soft body '" + body.name + "': " + e.what());
        }
        def.soft_bodies.push_back(SoftBodyDef{body.name, body.params, std::move(mesh)});
    }
    for (const RigidBodyDef& body : scene.rigid_bodies) def.rigid_bodies.push_back(make_rigid_body(body));
    def.springs = scene.springs;
    return def;
}

std::string scene_to_json(const Scene& scene) {
    const auto flat = [](const Params& params, bool body_only) {
        json object = json::object();
        for (const auto& info : param_table()) {
            if (body_only && info.scope != ParamScope::Body) continue;
            if (info.type == ParamType::String && param_text(params, info.key).empty()) continue;
            if (info.type == ParamType::OptionalVec3 && param_text(params, info.key) == "none") continue;
            if (info.key == "init_height" && params.position) continue;  // the position places the body
            object[std::string(info.key)] = value_json(params, info);
        }
        return object;
    };
    json root = flat(scene.params, false);
    if (!scene.soft_bodies.empty()) {
        json list = json::array();
        for (const SoftBodyScene& body : scene.soft_bodies) {
            json object = flat(body.params, true);
            object["name"] = body.name;
            list.push_back(object);
        }
        root["soft_bodies"] = list;
    }
    if (!scene.rigid_bodies.empty()) {
        json list = json::array();
        for (const RigidBodyDef& body : scene.rigid_bodies) {
            json object = json::object();
            object["name"] = body.name;
            for (const RigidKeyInfo& info : rigid_key_table()) {
                json value = rigid_value_json(body, info.key);
                if (!value.is_null()) object[std::string(info.key)] = std::move(value);
            }
            list.push_back(object);
        }
        root["rigid_bodies"] = list;
    }
    if (!scene.springs.empty()) {
        json list = json::array();
        const auto end_json = [](const SpringEndDef& end) {
            json object = json::object();
            if (!end.body.empty()) object["body"] = end.body;
            if (end.point) object["point"] = {end.point->x, end.point->y, end.point->z};
            if (end.vertex) object["vertex"] = *end.vertex;
            return object;
        };
        for (const SpringDef& spring : scene.springs) {
            json object = {{"a", end_json(spring.a)}, {"b", end_json(spring.b)}, {"damping", spring.damping}};
            if (spring.stiffness) object["stiffness"] = *spring.stiffness;
            if (spring.rest_length) object["rest_length"] = *spring.rest_length;
            list.push_back(object);
        }
        root["springs"] = list;
    }
    if (!scene.title.empty()) root["title"] = scene.title;
    if (!scene.text.empty()) root["text"] = scene.text;
    if (scene.expect) {
        json expect = {{"kind", scene.expect->kind}, {"body", scene.expect->body}};
        if (!scene.expect->slope.empty()) expect["slope"] = scene.expect->slope;
        root["expect"] = expect;
    }
    // nlohmann's objects keep keys sorted, which keeps saved files stable and diffable.
    try {
        return root.dump(2) + "\n";
    } catch (const json::type_error&) {
        // JSON text is UTF-8; a path or name in another encoding cannot be written into it faithfully.
        throw InputError("parameter 'mesh': a path or name in the scene is not valid UTF-8, which a scene file cannot "
                         "hold; rename the file or the body");
    }
}

void save_scene(const std::string& path, const Scene& scene, Overwrite overwrite) {
    const fs::path target(path);
    fs::path folder = target.parent_path();
    if (folder.empty()) folder = ".";
    std::error_code ec;
    if (fs::is_directory(target, ec)) throw InputError(path + ": is a folder; choose a file name");
    if (overwrite == Overwrite::No && fs::exists(fs::symlink_status(target, ec))) {
        throw InputError(path + ": already exists; not overwriting it");
    }

    // Store mesh paths relative to the scene's folder, so a folder of presets can move.
    Scene saved = scene;
    const auto relative = [&](std::string& mesh) {
        if (mesh.empty() || is_generated(mesh)) return;
        std::error_code error;
        const fs::path to = fs::proximate(fs::absolute(mesh, error), fs::absolute(folder, error), error);
        if (!error && !to.empty()) mesh = to.string();
    };
    relative(saved.params.mesh);
    for (SoftBodyScene& body : saved.soft_bodies) relative(body.params.mesh);
    for (RigidBodyDef& body : saved.rigid_bodies) relative(body.mesh);
    const std::string text = scene_to_json(saved);  // before anything touches the disk

    // A replaced file keeps its permissions; a new one is readable by all, writable by its owner.
    mode_t mode = 0644;
    if (struct stat old {}; ::stat(path.c_str(), &old) == 0 && S_ISREG(old.st_mode)) mode = old.st_mode & 07777;

    // The temporary file sits beside the target (a rename cannot cross file systems), hidden,
    // named after it (cut short, so that a long name still leaves room for the suffix).
    std::string temp_name(".");
    temp_name.append(target.filename().string().substr(0, 200)).append(".XXXXXX");
    std::string temp = (folder / temp_name).string();
    const int fd = ::mkstemp(temp.data());
    if (fd < 0) io_error(path, "cannot create a temporary file beside it");
    auto fail = [&](const char* what) {
        const int saved_errno = errno;
        ::close(fd);
        ::unlink(temp.c_str());
        errno = saved_errno;
        io_error(path, what);
    };
    // A short write (a full disk, a file size limit) ends in an error, never in a shorter file.
    std::size_t written = 0;
    while (written < text.size()) {
        const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
        if (n < 0) {
            if (errno == EINTR) continue;
            fail("cannot write");
        }
        written += static_cast<std::size_t>(n);
    }
    if (::fchmod(fd, mode) != 0) fail("cannot set permissions");
    if (::fsync(fd) != 0) fail("cannot flush to disk");
    if (::close(fd) != 0) {
        const int saved_errno = errno;
        ::unlink(temp.c_str());
        errno = saved_errno;
        io_error(path, "cannot close");
    }
    if (overwrite == Overwrite::No) {
        // link() refuses to replace an existing name: no window for a race to clobber a file.
        if (::link(temp.c_str(), path.c_str()) != 0) {
            const int saved_errno = errno;
            ::unlink(temp.c_str());
            errno = saved_errno;
            if (errno == EEXIST) throw InputError(path + ": already exists; not overwriting it");
            io_error(path, "cannot save");
        }
        ::unlink(temp.c_str());
    } else if (::rename(temp.c_str(), path.c_str()) != 0) {
        const int saved_errno = errno;
        ::unlink(temp.c_str());
        errno = saved_errno;
        io_error(path, "cannot save");
    }
    // Make the new name itself durable (best effort: the file is in place either way).
    if (const int dir = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); dir >= 0) {
        ::fsync(dir);
        ::close(dir);
    }
}

}  // namespace softbody

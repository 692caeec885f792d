#include "physics/scene_io.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "message_text.h"
#include "physics/error.h"
#include "physics/generated.h"
#include "physics/keys.h"
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

// A JSON value as a key's value, checked (check_key): numbers as numbers, vectors as arrays,
// words and paths as strings, the unset word ("none", "auto") or the zero word ("auto", "all")
// as a string. Throws InputError "key 'NAME': expected ..., got ...".
KeyValue key_value(const KeyInfo& info, const json& value) {
    const auto fail = [&](const std::string& expected) -> KeyValue {
        std::string words;
        if (info.optional) words += " or \"" + std::string(info.unset_word) + "\"";
        if (!info.zero_word.empty()) words += " or \"" + std::string(info.zero_word) + "\"";
        throw InputError("key '" + std::string(info.name) + "': expected " + expected + words + ", got " + type_name(value));
    };
    if (value.is_string()) {
        const std::string word = value.get<std::string>();
        if (info.optional && word == info.unset_word) return std::monostate{};
        if (!info.zero_word.empty() && word == info.zero_word) return 0.0;
    }
    const auto number = [&](const json& v) { return info.single ? double(float(v.get<double>())) : v.get<double>(); };
    const auto numbers = [&](std::size_t count) {
        return value.is_array() && value.size() == count &&
               std::all_of(value.begin(), value.end(), [](const json& v) { return v.is_number(); });
    };
    KeyValue out;
    switch (info.type) {
        case KeyType::Number:
            if (!value.is_number()) return fail("a number");
            out = number(value);
            break;
        case KeyType::Whole:
            if (!value.is_number_integer()) return fail("a whole number");
            if (value.is_number_unsigned() ? value.get<std::uint64_t>() > 1e15 : std::abs(double(value.get<std::int64_t>())) > 1e15) {
                // Far out of any range, said with the number as written.
                throw InputError("key '" + std::string(info.name) + "': must be " + key_range_text(info) + ", got " + value.dump());
            } else {
                out = double(value.get<std::int64_t>());
            }
            break;
        case KeyType::Bool:
            if (!value.is_boolean()) return fail("true or false");
            out = value.get<bool>();
            break;
        case KeyType::Vec3:
            if (!numbers(3)) return fail("an array of three numbers [x, y, z]");
            out = Vec3d{number(value[0]), number(value[1]), number(value[2])};
            break;
        case KeyType::Quat:
            if (!numbers(4)) return fail("an array of four numbers [w, x, y, z]");
            out = Quat{value[0].get<double>(), value[1].get<double>(), value[2].get<double>(), value[3].get<double>()};
            break;
        case KeyType::Word:
        case KeyType::Path:
            if (!value.is_string()) return fail("a string");
            if (info.type == KeyType::Path && value.get<std::string>().empty()) return fail("a file path");
            out = value.get<std::string>();
            break;
        case KeyType::IndexList: {
            if (!value.is_array()) return fail("an array of vertex indices");
            std::vector<std::uint32_t> list;
            for (const json& item : value) {
                if (!item.is_number_integer() || (item.is_number_unsigned() ? item.get<std::uint64_t>() > 0xFFFFFFFEull
                                                                             : item.get<std::int64_t>() < 0 || item.get<std::int64_t>() > 0xFFFFFFFEll)) {
                    return fail("an array of vertex indices (whole numbers from 0)");
                }
                list.push_back(std::uint32_t(item.get<std::int64_t>()));
            }
            out = std::move(list);
            break;
        }
    }
    check_key(info, out);
    return out;
}

// A key's value as JSON, or null for an unset one (left out of the file). A float's number is
// written as the 9 digits that read back to it, not as the double it widens to.
json key_json(const KeyInfo& info, const KeyValue& value) {
    if (std::holds_alternative<std::monostate>(value)) return json();
    const auto number = [&](double x) { return info.single ? std::stod(key_text(info, x)) : x; };
    if (const double* x = std::get_if<double>(&value)) {
        if (*x == 0.0 && !info.zero_word.empty()) return json(info.zero_word);
        if (info.type == KeyType::Whole) return json(std::llround(*x));
        return json(number(*x));
    }
    if (const bool* b = std::get_if<bool>(&value)) return json(*b);
    if (const Vec3d* v = std::get_if<Vec3d>(&value)) return json::array({number(v->x), number(v->y), number(v->z)});
    if (const Quat* q = std::get_if<Quat>(&value)) return json::array({q->w, q->x, q->y, q->z});
    if (const std::string* text = std::get_if<std::string>(&value)) return json(*text);
    return json(std::get<std::vector<std::uint32_t>>(value));
}

// A body's mesh without the keys that say how big it is and which way is up: fitted
// (fit_brought_mesh), each part only where the file says nothing of it.
void fit_unless_given(const json& keys, SoftBodyDef& def) {
    SoftBodyDef fitted = def;
    fit_brought_mesh(fitted);
    if (!keys.contains("scale")) def.scale = fitted.scale;
    if (!keys.contains("rotation") && !keys.contains("up_axis")) def.up_axis = fitted.up_axis;
}


// Where in the text a nested key is: the line of the first "key" after `from` (an offset), so
// an error inside the third rigid body points at that body's line, not the first body's.
std::string where_after(const std::string& origin, const std::string& text, std::size_t from, const std::string& key) {
    const auto at = text.find("\"" + key + "\"", std::min(from, text.size()));
    if (at == std::string::npos) return origin + ":" + std::to_string(line_of_offset(text, from));
    return origin + ":" + std::to_string(line_of_offset(text, at));
}

// Where an object of an array appears in the text, roughly, for pointing errors at a line: its
// name, looked for from `from` (the array's key for the first object, the object before it for
// the others, so a file of many is read in one pass), or without a name `from` itself.
std::size_t element_offset(const std::string& text, std::size_t from, const json& element) {
    if (element.is_object() && element.contains("name") && element["name"].is_string()) {
        const auto named = text.find("\"" + element["name"].get<std::string>() + "\"", from);
        if (named != std::string::npos) return named;
    }
    return from;
}

// Where the array under `array_key` begins (0 when its key is not found).
std::size_t array_offset(const std::string& text, const std::string& array_key) {
    const auto at = text.find("\"" + array_key + "\"");
    return at == std::string::npos ? 0 : at;
}

std::string relative_to(const std::string& origin, const std::string& path) {
    if (path.empty() || !fs::path(path).is_relative() || is_generated(path)) return path;
    const fs::path folder = fs::path(origin).parent_path();
    return folder.empty() ? path : (folder / path).lexically_normal().string();
}

// The keys of one object of a list ("soft_bodies", "rigid_bodies", "springs"), each read into
// `def` (set_key checks it); an error names the file and line, the thing and the key. The line
// is counted only for an error: counted for every key, from the file's start each time, it made
// a file of thousands of bodies load in quadratic time.
template <class D>
void read_keys(const json& element, KeyOwner owner, D& def, const std::string& what, const std::string& origin,
               const std::string& text, std::size_t at, std::initializer_list<std::string_view> skip) {
    for (const auto& [key, value] : element.items()) {
        if (std::find(skip.begin(), skip.end(), key) != skip.end()) continue;
        const KeyInfo* info = find_key(owner, key);
        KeyValue read;
        try {
            if (!info) {
                std::string message = "unknown key '" + printable(key) + "'";
                if (auto hint = closest_key(owner, key); !hint.empty()) message += " (did you mean '" + std::string(hint) + "'?)";
                else if (owner == KeyOwner::SoftBody && find_key(KeyOwner::World, key)) message = "'" + printable(key) + "' is a world key: set it in \"world\"";
                throw InputError(message);
            }
            read = key_value(*info, value);
        } catch (const InputError& e) {
            throw InputError(where_after(origin, text, at, key) + ": " + what + ": " + e.what());
        }
        try {
            set_key(def, *info, read);  // says whose key it is itself
        } catch (const InputError& e) {
            throw InputError(where_after(origin, text, at, key) + ": " + e.what());
        }
    }
}

RigidBodyDef parse_rigid_body(const json& element, const std::string& origin, const std::string& text, std::size_t at) {
    const auto line = [&] { return origin + ":" + std::to_string(line_of_offset(text, at)); };  // for an error
    if (!element.is_object()) throw InputError(line() + ": each of \"rigid_bodies\" must be an object {\"name\": ..., \"shape\": ...}");
    RigidBodyDef def;
    if (!element.contains("name") || !element["name"].is_string() || element["name"].get<std::string>().empty()) {
        throw InputError(line() + ": a rigid body needs a \"name\" (a string)");
    }
    def.name = element["name"].get<std::string>();
    const std::string what = "rigid body '" + printable(def.name) + "'";
    if (element.contains("orientation") && element.contains("rotation")) {
        throw InputError(where_after(origin, text, at, "rotation") + ": " + what + ": give 'orientation' or 'rotation', not both");
    }
    read_keys(element, KeyOwner::RigidBody, def, what, origin, text, at, {"name"});
    def.mesh = relative_to(origin, def.mesh);
    return def;
}

SoftBodyDef parse_soft_body(const json& element, const std::string& origin, const std::string& text, std::size_t at) {
    const auto line = [&] { return origin + ":" + std::to_string(line_of_offset(text, at)); };  // for an error
    if (!element.is_object() || !element.contains("name") || !element["name"].is_string() || element["name"].get<std::string>().empty()) {
        throw InputError(line() + ": each of \"soft_bodies\" must be an object with a \"name\" and a \"mesh\"");
    }
    SoftBodyDef def;
    def.name = element["name"].get<std::string>();
    const std::string what = "soft body '" + printable(def.name) + "'";
    read_keys(element, KeyOwner::SoftBody, def, what, origin, text, at, {"name"});
    if (def.mesh.empty()) throw InputError(line() + ": " + what + " needs a \"mesh\"");
    if (element.contains("position") && element.contains("init_height")) {
        throw InputError(where_after(origin, text, at, "position") + ": " + what + ": give 'position' or 'init_height', not both");
    }
    def.mesh = relative_to(origin, def.mesh);
    fit_unless_given(element, def);
    return def;
}

// An error names the end; the caller puts the spring's line before it.
SpringEndDef parse_spring_end(const json& value, const char* name) {
    const std::string what = std::string("spring end '") + name + "'";
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

SpringDef parse_spring(const json& element, const std::string& origin, const std::string& text, std::size_t at) {
    const auto where = [&] { return origin + ":" + std::to_string(line_of_offset(text, at)); };  // for an error
    if (!element.is_object()) throw InputError(where() + ": each of \"springs\" must be an object {\"a\": ..., \"b\": ..., \"stiffness\": k}");
    SpringDef def;
    if (element.contains("name")) {
        if (!element["name"].is_string() || element["name"].get<std::string>().empty()) {
            throw InputError(where() + ": a spring's \"name\" must be a non-empty string");
        }
        def.name = element["name"].get<std::string>();
    }
    const std::string what = def.name.empty() ? std::string("spring") : "spring '" + printable(def.name) + "'";
    try {
        if (element.contains("a")) def.a = parse_spring_end(element["a"], "a");
        if (element.contains("b")) def.b = parse_spring_end(element["b"], "b");
    } catch (const InputError& e) {
        throw InputError(where() + ": " + e.what());
    }
    read_keys(element, KeyOwner::Spring, def, what, origin, text, at, {"name", "a", "b"});
    if (!element.contains("a") || !element.contains("b")) throw InputError(where() + ": a spring needs both ends, \"a\" and \"b\"");
    if (!element.contains("stiffness")) throw InputError(where() + ": a spring needs \"stiffness\" (N/m)");
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

// "view": the first look at the scene; each part optional.
SceneView parse_view(const json& value, const std::string& at) {
    if (!value.is_object()) throw InputError(at + ": key 'view': expected an object, got " + type_name(value));
    SceneView view;
    const auto number = [&](const std::string& key, const json& item, double low, double high, const char* what) {
        if (!item.is_number() || !std::isfinite(item.get<double>()) || item.get<double>() < low || item.get<double>() > high) {
            throw InputError(at + ": key 'view': \"" + key + "\" expected " + what + ", got " + printable(item.dump()));
        }
        return item.get<double>();
    };
    for (const auto& [key, item] : value.items()) {
        if (key == "yaw") {
            view.yaw = number(key, item, -360.0, 360.0, "degrees from -360 to 360");
        } else if (key == "pitch") {
            view.pitch = number(key, item, -89.0, 89.0, "degrees from -89 to 89");
        } else if (key == "height_scale") {
            if (!item.is_boolean()) throw InputError(at + ": key 'view': \"height_scale\" expected true or false, got " + type_name(item));
            view.height_scale = item.get<bool>();
        } else if (key == "reference_line") {
            view.reference_line = number(key, item, -1e6, 1e6, "a height in metres");
        } else {
            throw InputError(at + ": key 'view': unknown part '" + printable(key) + "' (yaw, pitch, height_scale, reference_line)");
        }
    }
    return view;
}

// "controls": each a key the scene has (as --set names it), with a range inside the key's.
std::vector<LessonControl> parse_controls(const json& list, const Scene& scene, const std::string& where) {
    std::vector<LessonControl> out;
    const ThingNames names = thing_names(scene);
    for (const json& item : list) {
        const std::string what = where + ": key 'controls'";
        if (!item.is_object() || !item.contains("key") || !item["key"].is_string()) {
            throw InputError(what + ": each control must be an object with a \"key\" (as --set names it)");
        }
        LessonControl control;
        control.key = item["key"].get<std::string>();
        const KeyInfo* info = nullptr;
        try {
            info = resolve_key(control.key, names).front().info;
        } catch (const InputError& e) {
            throw InputError(what + ": " + e.what());
        }
        for (const auto& [field, value] : item.items()) {
            if (field == "key") continue;
            if (field == "label" || field == "unit") {
                if (!value.is_string()) throw InputError(what + ": '" + control.key + "': \"" + field + "\" must be a string");
                (field == "label" ? control.label : control.unit) = value.get<std::string>();
            } else if (field == "min" || field == "max" || field == "step") {
                if (!value.is_number()) throw InputError(what + ": '" + control.key + "': \"" + field + "\" must be a number");
                (field == "min" ? control.min : field == "max" ? control.max : control.step) = value.get<double>();
            } else {
                throw InputError(what + ": '" + control.key + "': unknown field '" + printable(field) + "' (key, label, unit, min, max, step)");
            }
        }
        if (info->type != KeyType::Number && info->type != KeyType::Whole && info->type != KeyType::Vec3 && info->type != KeyType::Bool &&
            info->type != KeyType::Word) {
            throw InputError(what + ": '" + control.key + "' has no slider (a number, a vector, true/false or a word)");
        }
        const auto inside = [&](const std::optional<double>& x) {
            return !x || (*x <= info->max && (info->above ? *x > info->min : *x >= info->min));
        };
        if (!inside(control.min) || !inside(control.max) || (control.min && control.max && !(*control.min < *control.max)) ||
            (control.step && !(*control.step > 0.0))) {
            throw InputError(what + ": '" + control.key + "': min < max, both " + key_range_text(*info) + ", and a step above 0");
        }
        if (control.label.empty()) control.label = info->label.empty() ? control.key : std::string(info->label);
        if (control.unit.empty()) control.unit = std::string(info->unit);
        out.push_back(std::move(control));
    }
    return out;
}

// The bodies "expect" names exist, of the kind its closed form reads.
void check_expect_names(const Scene& scene, const std::string& where) {
    const LessonExpect& expect = *scene.expect;
    const ClosedFormInfo& form = *find_closed_form(expect.kind);
    const auto rigid = [&](const std::string& name) {
        return std::any_of(scene.rigid_bodies.begin(), scene.rigid_bodies.end(), [&](const RigidBodyDef& b) { return b.name == name; });
    };
    const bool exists = std::any_of(scene.soft_bodies.begin(), scene.soft_bodies.end(), [&](const SoftBodyDef& b) { return b.name == expect.body; }) ||
                        rigid(expect.body);
    const std::string what = where + ": key 'expect': ";
    if (!exists) throw InputError(what + "there is no body named '" + printable(expect.body) + "'");
    if (form.rigid_body && !rigid(expect.body)) throw InputError(what + "'" + printable(expect.body) + "' must be a rigid body for '" + expect.kind + "'");
    if (!form.rigid_body && rigid(expect.body)) throw InputError(what + "'" + printable(expect.body) + "' must be a soft body for '" + expect.kind + "'");
    if (!expect.slope.empty() && !rigid(expect.slope)) throw InputError(what + "there is no rigid body named '" + printable(expect.slope) + "' (the slope)");
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& origin) {
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

    Scene scene;
    // The old flat form: the world's keys at the top level, and with a "mesh" the keys of the
    // soft body "body" too (scene_io.h).
    SoftBodyDef flat;
    flat.name = "body";
    bool flat_world = false;
    for (const auto& [key, value] : root.items()) {
        if (key == "rigid_bodies" || key == "soft_bodies" || key == "springs") {
            if (!value.is_array()) throw InputError(where(origin, text, key) + ": \"" + key + "\" must be an array");
            continue;
        }
        // A lesson's words and its closed form: for the reader and the lesson meter, not the physics.
        if (key == "title" || key == "text" || key == "notes") {
            if (!value.is_string()) throw InputError(where(origin, text, key) + ": key '" + key + "': expected a string, got " + type_name(value));
            (key == "title" ? scene.title : key == "text" ? scene.text : scene.notes) = value.get<std::string>();
            continue;
        }
        if (key == "controls") {
            if (!value.is_array()) throw InputError(where(origin, text, key) + ": key 'controls': expected an array, got " + type_name(value));
            continue;  // read once the things they name are known
        }
        if (key == "expect") {
            scene.expect = parse_expect(value, where(origin, text, key));
            continue;
        }
        if (key == "view") {
            scene.view = parse_view(value, where(origin, text, key));
            continue;
        }
        if (key == "world") {
            if (!value.is_object()) throw InputError(where(origin, text, key) + ": \"world\" must be an object {\"key\": value, ...}");
            const std::size_t at = text.find("\"world\"");
            read_keys(value, KeyOwner::World, scene.settings, "world", origin, text, at == std::string::npos ? 0 : at, {});
            continue;
        }
        const KeyInfo* world_key = find_key(KeyOwner::World, key);
        const KeyInfo* body_key = find_key(KeyOwner::SoftBody, key);
        if (!world_key && !body_key) {
            std::string message = where(origin, text, key) + ": unknown key '" + printable(key) + "'";
            std::string_view hint = closest_key(KeyOwner::World, key);
            if (hint.empty()) hint = closest_key(KeyOwner::SoftBody, key);
            if (!hint.empty()) message += " (did you mean '" + std::string(hint) + "'?)";
            else message += " (a scene holds world, soft_bodies, rigid_bodies, springs, title, text and expect)";
            throw InputError(message);
        }
        try {
            if (world_key) {
                flat_world = true;
                set_key(scene.settings, *world_key, key_value(*world_key, value));
            } else {
                set_key(flat, *body_key, key_value(*body_key, value));
            }
        } catch (const InputError& e) {
            throw InputError(where(origin, text, key) + ": " + e.what());
        }
    }
    if (flat_world && root.contains("world")) {
        throw InputError(where(origin, text, "world") + ": the world's keys go in \"world\" or at the top level (the old form), not both");
    }
    if (root.contains("mesh")) {
        if (root.contains("position") && root.contains("init_height")) {
            throw InputError(where(origin, text, "position") + ": soft body 'body': give 'position' or 'init_height', not both");
        }
        flat.mesh = relative_to(origin, flat.mesh);
        fit_unless_given(root, flat);
        scene.soft_bodies.push_back(std::move(flat));
    }
    if (root.contains("soft_bodies")) {
        std::size_t at = array_offset(text, "soft_bodies");
        for (const json& element : root["soft_bodies"]) {
            at = element_offset(text, at, element);
            scene.soft_bodies.push_back(parse_soft_body(element, origin, text, at));
        }
    }
    if (root.contains("rigid_bodies")) {
        std::size_t at = array_offset(text, "rigid_bodies");
        for (const json& element : root["rigid_bodies"]) {
            at = element_offset(text, at, element);
            scene.rigid_bodies.push_back(parse_rigid_body(element, origin, text, at));
        }
    }
    if (root.contains("springs")) {
        std::size_t from = text.find("\"springs\"");
        for (const json& element : root["springs"]) {
            const std::size_t at = text.find("{", from == std::string::npos ? 0 : from + 1);
            from = at == std::string::npos ? from : at;
            scene.springs.push_back(parse_spring(element, origin, text, from == std::string::npos ? 0 : from));
            // Past this spring's ends ("a": {...}, "b": {...}) to the next spring's brace.
            for (int skip = 0; skip < 2 && from != std::string::npos; ++skip) from = text.find("}", from + 1);
        }
    }

    // Names: every body has one, a spring may, and no two share one.
    std::vector<std::string> all = names(scene);
    std::sort(all.begin(), all.end());
    if (const auto twin = std::adjacent_find(all.begin(), all.end()); twin != all.end()) {
        throw InputError(where(origin, text, *twin) + ": two things are named '" + printable(*twin) +
                         "' (the soft body of the old flat keys is 'body'); names must be unique");
    }
    if (scene.expect) check_expect_names(scene, where(origin, text, "expect"));
    if (root.contains("controls")) scene.controls = parse_controls(root["controls"], scene, where(origin, text, "controls"));
    return scene;
}

void fit_brought_mesh(SoftBodyDef& def) {
    def.scale = 0.0f;  // "auto"
    def.up_axis = "y";
    def.rotation = {};
}

Scene load_scene(const std::string& path) {
    if (is_generated(path)) return generated_scene(path);  // "pile:100", "cloud:2500": made, not read
    return parse_scene(read_text_file(path, kMaxSceneBytes, "scene file"), path);
}

void set_scene_key(Scene& scene, std::string_view key, std::string_view text) {
    // A mesh for a scene without a soft body: the body of the old flat keys, named "body".
    if (key == "mesh" && scene.soft_bodies.empty()) {
        SoftBodyDef body;
        body.name = "body";
        set_key(body, *find_key(KeyOwner::SoftBody, "mesh"), parse_key_text(*find_key(KeyOwner::SoftBody, "mesh"), text));
        for (const std::string& name : names(scene)) {
            if (name == body.name) throw InputError("mesh: the new soft body would be named 'body', which is taken");
        }
        scene.soft_bodies.push_back(std::move(body));
        return;
    }
    const ThingNames names = thing_names(scene);
    const std::vector<KeyTarget> targets = resolve_key(key, names);
    const KeyValue value = parse_key_text(targets.front(), names, text);
    for (const KeyTarget& t : targets) set_key(scene, t, value);
}

ChangedKeys changed_keys(const Scene& loaded, const WorldDef& now) {
    ChangedKeys out;
    const auto compare = [&](const auto& before, const auto& after, KeyOwner owner, const std::string& prefix) {
        for (const KeyInfo* info : keys_of(owner)) {
            if (info->alias) continue;
            const KeyValue a = get_key(before, *info), b = get_key(after, *info);
            if (!(a == b)) out.keys.emplace_back(prefix + std::string(info->name), key_text(*info, b));
        }
    };
    compare(loaded.settings, now.settings, KeyOwner::World, "");
    const auto match = [&](const auto& was, const auto& is, KeyOwner owner) {
        for (const auto& thing : is) {
            const auto it = std::find_if(was.begin(), was.end(), [&](const auto& t) { return t.name == thing.name; });
            if (it == was.end() || thing.name.empty()) {
                ++out.added;
                continue;
            }
            compare(*it, thing, owner, thing.name + ".");
        }
        for (const auto& thing : was) {
            if (std::none_of(is.begin(), is.end(), [&](const auto& t) { return t.name == thing.name; })) ++out.removed;
        }
    };
    match(loaded.soft_bodies, now.soft_bodies, KeyOwner::SoftBody);
    match(loaded.rigid_bodies, now.rigid_bodies, KeyOwner::RigidBody);
    match(loaded.springs, now.springs, KeyOwner::Spring);
    return out;
}

std::string scene_to_json(const Scene& scene) {
    // Each key a definition holds that is set (unset optional ones are left out), by the table.
    const auto keys = [](const auto& def, KeyOwner owner) {
        json object = json::object();
        for (const KeyInfo* info : keys_of(owner)) {
            if (info->alias) continue;
            json value = key_json(*info, get_key(def, *info));
            if (value.is_null() || (info->type == KeyType::Path && value.get<std::string>().empty())) continue;
            object[std::string(info->name)] = std::move(value);
        }
        return object;
    };
    json root = json::object();
    root["world"] = keys(scene.settings, KeyOwner::World);
    if (!scene.soft_bodies.empty()) {
        json list = json::array();
        for (const SoftBodyDef& body : scene.soft_bodies) {
            json object = keys(body, KeyOwner::SoftBody);
            if (body.position) object.erase("init_height");  // the position places the body
            object["name"] = body.name;
            list.push_back(object);
        }
        root["soft_bodies"] = list;
    }
    if (!scene.rigid_bodies.empty()) {
        json list = json::array();
        for (const RigidBodyDef& body : scene.rigid_bodies) {
            json object = keys(body, KeyOwner::RigidBody);
            if (body.shape != ShapeKind::Mesh && body.scale == 1.0) object.erase("scale");  // a mesh's key
            object["name"] = body.name;
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
            json object = keys(spring, KeyOwner::Spring);
            object["a"] = end_json(spring.a);
            object["b"] = end_json(spring.b);
            if (!spring.name.empty()) object["name"] = spring.name;
            list.push_back(object);
        }
        root["springs"] = list;
    }
    if (!scene.title.empty()) root["title"] = scene.title;
    if (!scene.notes.empty()) root["notes"] = scene.notes;
    if (!scene.controls.empty()) {
        json list = json::array();
        for (const LessonControl& c : scene.controls) {
            json item = {{"key", c.key}, {"label", c.label}, {"unit", c.unit}};
            if (c.min) item["min"] = *c.min;
            if (c.max) item["max"] = *c.max;
            if (c.step) item["step"] = *c.step;
            list.push_back(item);
        }
        root["controls"] = list;
    }
    if (!scene.text.empty()) root["text"] = scene.text;
    if (scene.view != SceneView{}) {
        json view = json::object();
        if (scene.view.yaw) view["yaw"] = *scene.view.yaw;
        if (scene.view.pitch) view["pitch"] = *scene.view.pitch;
        if (scene.view.height_scale) view["height_scale"] = true;
        if (scene.view.reference_line) view["reference_line"] = *scene.view.reference_line;
        root["view"] = view;
    }
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
        throw InputError("key 'mesh': a path or name in the scene is not valid UTF-8, which a scene file cannot "
                         "hold; rename the file or the body");
    }
}

void save_scene(const std::string& path, const Scene& scene, Overwrite overwrite) {
    const fs::path target(path);
    fs::path folder = target.parent_path();
    if (folder.empty()) folder = ".";
    // Store mesh paths relative to the scene's folder, so a folder of presets can move.
    Scene saved = scene;
    const auto relative = [&](std::string& mesh) {
        if (mesh.empty() || is_generated(mesh)) return;
        std::error_code error;
        const fs::path to = fs::proximate(fs::absolute(mesh, error), fs::absolute(folder, error), error);
        if (!error && !to.empty()) mesh = to.string();
    };
    for (SoftBodyDef& body : saved.soft_bodies) relative(body.mesh);
    for (RigidBodyDef& body : saved.rigid_bodies) relative(body.mesh);
    const std::string text = scene_to_json(saved);  // before anything touches the disk

    write_text_file(path, text, overwrite);
}

}  // namespace softbody

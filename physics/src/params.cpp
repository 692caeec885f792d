#include "physics/params.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

#include "message_text.h"
#include "physics/error.h"

namespace softbody {

namespace {

// Ranges are what the physics can honour, not what looks good on a slider: a value outside
// them is rejected. Where the book gives a value (Listing 8), it is the default.
constexpr ParamInfo kTable[] = {
    {"mesh", ParamType::String, "", "", "Mesh file, OBJ or OFF: one particle per distinct vertex position", 0, 0, false, false, ParamScope::Body},
    {"scale", ParamType::Float, "", "", "Uniform scale from mesh units to metres; auto: the largest side 1 m, centred", 0, 1e4, true, false, ParamScope::Body, "auto"},
    {"up_axis", ParamType::Axis, "", "", "The file's up axis (x, y, z, -x, -y, -z), turned to point up (+z)", 0, 0, false, false, ParamScope::Body},
    {"rotation", ParamType::Vec3, "deg", "", "Turns the mesh about x, then y, then z, after up_axis", -360, 360, false, false, ParamScope::Body},
    {"init_height", ParamType::Float, "m", "", "Height added to every vertex's z at the start (Listing 8)", -1e4, 1e4, false, false, ParamScope::Body},
    {"initial_velocity", ParamType::Vec3, "m/s", "", "Velocity of every particle at the start", -1e3, 1e3, false, false, ParamScope::Body},
    {"position", ParamType::OptionalVec3, "m", "", "Where the body's centre of mass goes at the start (none: the mesh's place, lifted by init_height)", -1e4, 1e4, false, false, ParamScope::Body},
    {"angular_velocity", ParamType::Vec3, "rad/s", "", "Spin about the centre of mass at the start, world axes (added to initial_velocity)", -1e3, 1e3, false, false, ParamScope::Body},
    {"color", ParamType::OptionalVec3, "", "", "The body's colour r, g, b from 0 to 1 (none: the palette's)", 0, 1, false, true, ParamScope::Body},
    {"self_collision", ParamType::Bool, "", "", "The body's particles collide with its own triangles (not those they belong to)", 0, 0, false, true, ParamScope::Body},
    {"particle_mass", ParamType::Float, "kg", "", "Mass m of each particle (Listing 8: 1)", 0, 1e6, true, true, ParamScope::Body},
    {"stiffness", ParamType::Float, "N/m", "Eq. 21", "Spring constant k between every pair (Listing 8: 10)", 0, 1e7, false, true, ParamScope::Body},
    {"damping", ParamType::Float, "kg/s", "Eq. 22", "Damper coefficient c between every pair (Listing 8: 0.1)", 0, 1e6, false, true, ParamScope::Body},
    {"gravity", ParamType::Vec3, "m/s^2", "", "Gravitational acceleration g, z up (Listing 8: 0,0,-9.81)", -1e3, 1e3, false, true},
    {"dt", ParamType::Float, "s", "", "Fixed physics tick (Listing 8: 0.02)", 0, 1, true, true},
    {"substeps", ParamType::Int, "", "", "Integration steps of dt/substeps within one tick", 1, 1000, false, true},
    {"auto_substeps", ParamType::Bool, "", "", "Use the fewest substeps the stability estimate allows (at least `substeps`)", 0, 0, false, true},
    {"integrator", ParamType::Integrator, "", "", "verlet (default), symplectic_euler, explicit_euler or rk4", 0, 0, false, true},
    {"drag_coefficient", ParamType::Float, "", "Eq. 23", "Drag coefficient C_D (0.1 to 0.4 for blunt bodies); 0 turns drag off", 0, 10, false, true, ParamScope::Body},
    {"air_density", ParamType::Float, "kg/m^3", "Eq. 23", "Fluid density rho (air: 1.2)", 0, 1e4, false, true},
    {"ground", ParamType::Bool, "", "", "Whether the ground plane z = ground_height exists", 0, 0, false, true},
    {"ground_height", ParamType::Float, "m", "", "Height of the ground plane", -1e4, 1e4, false, true},
    {"restitution", ParamType::Float, "", "", "Coefficient of restitution e at the ground: v_n' = -e v_n", 0, 1, false, true},
    {"static_friction", ParamType::Float, "", "Eq. 24", "Static friction coefficient mu_s at the ground", 0, 2, false, true},
    {"dynamic_friction", ParamType::Float, "", "Eq. 25", "Dynamic friction coefficient mu_d at the ground", 0, 2, false, true},
    {"pinned", ParamType::IndexList, "", "", "Vertex indices (0-based, as in the file) held fixed in place", 0, 0, false, false, ParamScope::Body},
    {"max_particles", ParamType::Int, "", "", "Particle budget: a mesh with more is simulated on this many, drawn in full; all: one per vertex", 4, 20000, false, false, ParamScope::Body, "all"},
    {"renormalize_every", ParamType::Int, "ticks", "Listing 9", "Renormalise each rigid body's quaternion every this many ticks (Listing 9: 5); 0: never, and watch |q| drift", 0, 1e6, false, true},
    {"sleeping", ParamType::Bool, "", "", "Rigid bodies at rest (slower than 5 cm/s) for half a second sleep, costing nothing, until touched, grabbed or a key changes", 0, 0, false, true},
};

struct FieldRef {
    float* f = nullptr;
    int* i = nullptr;
    bool* b = nullptr;
    Vec3* v = nullptr;
    std::string* s = nullptr;
    Integrator* e = nullptr;
    std::vector<std::uint32_t>* list = nullptr;
    std::optional<Vec3>* ov = nullptr;
};

FieldRef field(Params& p, std::string_view key) {
    if (key == "mesh") return {.s = &p.mesh};
    if (key == "scale") return {.f = &p.scale};
    if (key == "up_axis") return {.s = &p.up_axis};
    if (key == "rotation") return {.v = &p.rotation};
    if (key == "init_height") return {.f = &p.init_height};
    if (key == "initial_velocity") return {.v = &p.initial_velocity};
    if (key == "position") return {.ov = &p.position};
    if (key == "angular_velocity") return {.v = &p.angular_velocity};
    if (key == "color") return {.ov = &p.color};
    if (key == "self_collision") return {.b = &p.self_collision};
    if (key == "particle_mass") return {.f = &p.particle_mass};
    if (key == "stiffness") return {.f = &p.stiffness};
    if (key == "damping") return {.f = &p.damping};
    if (key == "gravity") return {.v = &p.gravity};
    if (key == "dt") return {.f = &p.dt};
    if (key == "substeps") return {.i = &p.substeps};
    if (key == "auto_substeps") return {.b = &p.auto_substeps};
    if (key == "integrator") return {.e = &p.integrator};
    if (key == "drag_coefficient") return {.f = &p.drag_coefficient};
    if (key == "air_density") return {.f = &p.air_density};
    if (key == "ground") return {.b = &p.ground};
    if (key == "ground_height") return {.f = &p.ground_height};
    if (key == "restitution") return {.f = &p.restitution};
    if (key == "static_friction") return {.f = &p.static_friction};
    if (key == "dynamic_friction") return {.f = &p.dynamic_friction};
    if (key == "pinned") return {.list = &p.pinned};
    if (key == "max_particles") return {.i = &p.max_particles};
    if (key == "renormalize_every") return {.i = &p.renormalize_every};
    if (key == "sleeping") return {.b = &p.sleeping};
    return {};
}

std::string format_number(double x) {
    std::ostringstream out;
    out.precision(9);
    out << x;
    return out.str();
}

[[noreturn]] void bad_value(std::string_view key, std::string_view what, std::string_view text) {
    throw InputError("parameter '" + std::string(key) + "': " + std::string(what) + ", got '" + printable(text) + "'");
}

std::string_view trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
    return s;
}

std::vector<std::string_view> split(std::string_view s, char sep) {
    std::vector<std::string_view> parts;
    for (;;) {
        const auto at = s.find(sep);
        parts.push_back(trim(s.substr(0, at)));
        if (at == std::string_view::npos) return parts;
        s.remove_prefix(at + 1);
    }
}

bool parse_float(std::string_view s, float& out) {
    s = trim(s);
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    double value = 0.0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    if (s.empty() || ec != std::errc() || end != s.data() + s.size()) return false;
    out = static_cast<float>(value);
    return std::isfinite(value) && std::isfinite(out);
}

bool parse_int(std::string_view s, long long& out) {
    s = trim(s);
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    return !s.empty() && ec == std::errc() && end == s.data() + s.size();
}

void check_range(const ParamInfo& info, double value, std::string_view what = {}) {
    if (value == 0.0 && !info.zero_word.empty()) return;  // the word's value ("auto", "all")
    const bool low = info.min_exclusive ? !(value > info.min) : !(value >= info.min);
    if (std::isfinite(value) && !low && value <= info.max) return;
    std::string unit;
    if (!info.unit.empty()) unit.append(" ").append(info.unit);
    std::string range = info.min_exclusive
                            ? "above " + format_number(info.min) + " and at most " + format_number(info.max)
                            : "between " + format_number(info.min) + " and " + format_number(info.max);
    if (!info.zero_word.empty()) range += ", or " + std::string(info.zero_word);
    throw InputError("parameter '" + std::string(info.key) + "'" + std::string(what) + ": must be " +
                     range + unit + ", got " + format_number(value));
}

}  // namespace

std::string_view to_string(Integrator integrator) {
    switch (integrator) {
        case Integrator::Verlet: return "verlet";
        case Integrator::SymplecticEuler: return "symplectic_euler";
        case Integrator::ExplicitEuler: return "explicit_euler";
        case Integrator::RK4: return "rk4";
    }
    return "verlet";
}

std::optional<Integrator> integrator_from_string(std::string_view name) {
    for (auto candidate : {Integrator::Verlet, Integrator::SymplecticEuler, Integrator::ExplicitEuler,
                           Integrator::RK4}) {
        if (to_string(candidate) == name) return candidate;
    }
    return std::nullopt;
}

std::span<const ParamInfo> param_table() { return kTable; }

const ParamInfo* find_param(std::string_view key) {
    for (const auto& info : kTable) {
        if (info.key == key) return &info;
    }
    return nullptr;
}

std::string_view closest_key(std::string_view key) {
    // Levenshtein distance; a key within a third of its length counts as a likely typo.
    std::string_view best;
    std::size_t best_distance = key.size() / 3 + 1;
    for (const auto& info : kTable) {
        const std::string_view other = info.key;
        // The distance is at least the difference in length: no need to compute it then
        // (which also keeps a megabyte-long key from costing seconds).
        const std::size_t longer = std::max(key.size(), other.size()), shorter = std::min(key.size(), other.size());
        if (longer - shorter >= best_distance) continue;
        std::vector<std::size_t> row(other.size() + 1);
        for (std::size_t j = 0; j <= other.size(); ++j) row[j] = j;
        for (std::size_t i = 1; i <= key.size(); ++i) {
            std::size_t diagonal = row[0];
            row[0] = i;
            for (std::size_t j = 1; j <= other.size(); ++j) {
                const std::size_t above = row[j];
                row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (key[i - 1] != other[j - 1])});
                diagonal = above;
            }
        }
        if (row[other.size()] < best_distance) {
            best_distance = row[other.size()];
            best = other;
        }
    }
    return best;
}

void validate(const Params& params) {
    Params& p = const_cast<Params&>(params);  // field() hands out pointers; nothing is written
    for (const auto& info : kTable) {
        const FieldRef ref = field(p, info.key);
        if (ref.f) check_range(info, *ref.f);
        if (ref.i) check_range(info, *ref.i);
        const Vec3* v = ref.v ? ref.v : ref.ov && *ref.ov ? &**ref.ov : nullptr;
        if (v) {
            check_range(info, v->x, " (x)");
            check_range(info, v->y, " (y)");
            check_range(info, v->z, " (z)");
        }
    }
}

void set_param(Params& params, std::string_view key, std::string_view text) {
    const ParamInfo* info = find_param(key);
    if (!info) {
        std::string message = "unknown parameter '" + printable(key) + "'";
        if (auto hint = closest_key(key); !hint.empty()) message += " (did you mean '" + std::string(hint) + "'?)";
        throw InputError(message);
    }
    const FieldRef ref = field(params, key);
    if (!info->zero_word.empty() && trim(text) == info->zero_word) {  // "auto", "all": stands for 0
        if (ref.f) *ref.f = 0.0f;
        if (ref.i) *ref.i = 0;
        return;
    }
    const auto expected = [&](std::string what) {
        return info->zero_word.empty() ? what : what + " or " + std::string(info->zero_word);
    };
    switch (info->type) {
        case ParamType::Float: {
            float value = 0.0f;
            if (!parse_float(text, value)) bad_value(key, expected("expected a finite number"), text);
            check_range(*info, value);
            *ref.f = value;
            break;
        }
        case ParamType::Int: {
            long long value = 0;
            if (!parse_int(text, value)) bad_value(key, expected("expected a whole number"), text);
            check_range(*info, static_cast<double>(value));
            *ref.i = static_cast<int>(value);
            break;
        }
        case ParamType::Bool: {
            const std::string_view t = trim(text);
            if (t == "true" || t == "1" || t == "on" || t == "yes") *ref.b = true;
            else if (t == "false" || t == "0" || t == "off" || t == "no") *ref.b = false;
            else bad_value(key, "expected true or false", text);
            break;
        }
        case ParamType::Vec3:
        case ParamType::OptionalVec3: {
            const bool optional = info->type == ParamType::OptionalVec3;
            if (optional && trim(text) == "none") {
                *ref.ov = std::nullopt;
                break;
            }
            const auto parts = split(text, ',');
            Vec3 v;
            if (parts.size() != 3 || !parse_float(parts[0], v.x) || !parse_float(parts[1], v.y) ||
                !parse_float(parts[2], v.z)) {
                bad_value(key, optional ? "expected three finite numbers x,y,z or none" : "expected three finite numbers x,y,z", text);
            }
            check_range(*info, v.x, " (x)");
            check_range(*info, v.y, " (y)");
            check_range(*info, v.z, " (z)");
            if (optional) *ref.ov = v;
            else *ref.v = v;
            break;
        }
        case ParamType::String:
            if (trim(text).empty()) bad_value(key, "expected a file path", text);
            *ref.s = std::string(trim(text));
            break;
        case ParamType::Axis: {
            const std::string_view t = trim(text);
            if (t != "x" && t != "y" && t != "z" && t != "-x" && t != "-y" && t != "-z") {
                bad_value(key, "expected x, y, z, -x, -y or -z", text);
            }
            *ref.s = std::string(t);
            break;
        }
        case ParamType::Integrator: {
            auto value = integrator_from_string(trim(text));
            if (!value) bad_value(key, "expected verlet, symplectic_euler, explicit_euler or rk4", text);
            *ref.e = *value;
            break;
        }
        case ParamType::IndexList: {
            std::vector<std::uint32_t> list;
            if (!trim(text).empty()) {
                for (auto part : split(text, ',')) {
                    long long value = 0;
                    if (!parse_int(part, value) || value < 0 || value > 0xFFFFFFFEll) {
                        bad_value(key, "expected vertex indices (whole numbers from 0) separated by commas", text);
                    }
                    list.push_back(static_cast<std::uint32_t>(value));
                }
            }
            *ref.list = std::move(list);
            break;
        }
    }
}

std::string param_text(const Params& params, std::string_view key) {
    const FieldRef ref = field(const_cast<Params&>(params), key);
    if (const ParamInfo* info = find_param(key); info && !info->zero_word.empty()) {
        if ((ref.f && *ref.f == 0.0f) || (ref.i && *ref.i == 0)) return std::string(info->zero_word);
    }
    if (ref.f) return format_number(*ref.f);
    if (ref.i) return std::to_string(*ref.i);
    if (ref.b) return *ref.b ? "true" : "false";
    if (ref.v) return format_number(ref.v->x) + "," + format_number(ref.v->y) + "," + format_number(ref.v->z);
    if (ref.ov) {
        if (!*ref.ov) return "none";
        const Vec3& v = **ref.ov;
        return format_number(v.x) + "," + format_number(v.y) + "," + format_number(v.z);
    }
    if (ref.s) return *ref.s;
    if (ref.e) return std::string(to_string(*ref.e));
    if (ref.list) {
        std::string out;
        for (std::size_t n = 0; n < ref.list->size(); ++n) {
            if (n) out += ',';
            out += std::to_string((*ref.list)[n]);
        }
        return out;
    }
    throw InputError("unknown parameter '" + printable(key) + "'");
}

}  // namespace softbody

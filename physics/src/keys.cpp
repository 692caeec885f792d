// The table of keys (keys.h) and what reads and writes them: text, ranges, the typed fields.
#include "physics/keys.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>
#include <type_traits>

#include "message_text.h"
#include "physics/error.h"

namespace softbody {

namespace {

// --- Binding a key to its field ---------------------------------------------------------------
// What a field holds, as a KeyValue, and back. The field's C++ type says the key's type.

template <class T> struct is_optional : std::false_type {};
template <class T> struct is_optional<std::optional<T>> : std::true_type { using type = T; };

template <class T>
KeyValue to_value(const T& field) {
    if constexpr (is_optional<T>::value) {
        if (!field) return std::monostate{};
        return to_value(*field);
    } else if constexpr (std::is_same_v<T, bool>) {
        return field;
    } else if constexpr (std::is_arithmetic_v<T>) {
        return double(field);
    } else if constexpr (std::is_same_v<T, Vec3>) {
        return Vec3d(field);
    } else if constexpr (std::is_same_v<T, Integrator> || std::is_same_v<T, ShapeKind>) {
        return std::string(to_string(field));
    } else {
        return field;  // Vec3d, Quat, std::string, the index list
    }
}

template <class T>
void from_value(const KeyValue& value, T& field) {
    if constexpr (is_optional<T>::value) {
        if (std::holds_alternative<std::monostate>(value)) {
            field.reset();
        } else {
            typename is_optional<T>::type inner{};
            from_value(value, inner);
            field = inner;
        }
    } else if constexpr (std::is_same_v<T, bool>) {
        field = std::get<bool>(value);
    } else if constexpr (std::is_arithmetic_v<T>) {
        field = static_cast<T>(std::get<double>(value));
    } else if constexpr (std::is_same_v<T, Vec3>) {
        field = to_float(std::get<Vec3d>(value));
    } else if constexpr (std::is_same_v<T, Integrator>) {
        field = *integrator_from_string(std::get<std::string>(value));
    } else if constexpr (std::is_same_v<T, ShapeKind>) {
        field = *shape_from_string(std::get<std::string>(value));
    } else {
        field = std::get<T>(value);
    }
}

template <class> struct member_of;
template <class O, class T> struct member_of<T O::*> {
    using owner = O;
    using field = T;
};

template <auto M>
KeyValue get_field(const void* def) {
    using O = typename member_of<decltype(M)>::owner;
    return to_value(static_cast<const O*>(def)->*M);
}

template <auto M>
void set_field(void* def, const KeyValue& value) {
    using O = typename member_of<decltype(M)>::owner;
    from_value(value, static_cast<O*>(def)->*M);
}

template <class T> constexpr KeyType type_of(bool word) {
    if constexpr (is_optional<T>::value) {
        return type_of<typename is_optional<T>::type>(word);
    } else if constexpr (std::is_same_v<T, bool>) {
        return KeyType::Bool;
    } else if constexpr (std::is_integral_v<T>) {
        return KeyType::Whole;
    } else if constexpr (std::is_floating_point_v<T>) {
        return KeyType::Number;
    } else if constexpr (std::is_same_v<T, Vec3> || std::is_same_v<T, Vec3d>) {
        return KeyType::Vec3;
    } else if constexpr (std::is_same_v<T, Quat>) {
        return KeyType::Quat;
    } else if constexpr (std::is_same_v<T, Integrator> || std::is_same_v<T, ShapeKind>) {
        return KeyType::Word;
    } else if constexpr (std::is_same_v<T, std::string>) {
        return word ? KeyType::Word : KeyType::Path;
    } else {
        return KeyType::IndexList;
    }
}

template <class T> constexpr bool single_of() {
    if constexpr (is_optional<T>::value) return single_of<typename is_optional<T>::type>();
    else return std::is_same_v<T, float> || std::is_same_v<T, Vec3>;
}

template <class O> constexpr KeyOwner owner_of() {
    if constexpr (std::is_same_v<O, WorldSettings>) return KeyOwner::World;
    else if constexpr (std::is_same_v<O, SoftBodyDef>) return KeyOwner::SoftBody;
    else if constexpr (std::is_same_v<O, RigidBodyDef>) return KeyOwner::RigidBody;
    else return KeyOwner::Spring;
}

// One line of the table: the field, its name, and what the entry says beyond the field's type.
template <auto M>
constexpr KeyInfo key(std::string_view name, KeyInfo info) {
    using O = typename member_of<decltype(M)>::owner;
    using T = typename member_of<decltype(M)>::field;
    info.name = name;
    info.owner = owner_of<O>();
    info.type = type_of<T>(!info.choices.empty());
    info.single = single_of<T>();
    info.optional = is_optional<T>::value;
    if (info.optional && info.unset_word.empty()) info.unset_word = "none";
    info.get = &get_field<M>;
    info.set = &set_field<M>;
    return info;
}

// A rigid body's rotation: degrees about x, then y, then z, written into its orientation.
KeyValue get_rotation(const void*) { return std::monostate{}; }
void set_rotation(void* def, const KeyValue& value) {
    static_cast<RigidBodyDef*>(def)->orientation = Quat::from_degrees_xyz(std::get<Vec3d>(value));
}

constexpr std::string_view kIntegrators[] = {"verlet", "symplectic_euler", "explicit_euler", "rk4"};
constexpr std::string_view kAxes[] = {"x", "y", "z", "-x", "-y", "-z"};
// Surface gravity, m/s^2: Earth as Listing 8 has it, the others as planetary fact sheets give them.
constexpr KeyPreset kGravities[] = {{"Earth", "0,0,-9.81"}, {"Moon", "0,0,-1.62"}, {"Mars", "0,0,-3.71"},
                                    {"Jupiter", "0,0,-24.79"}, {"No gravity", "0,0,0"}};
constexpr std::string_view kShapes[] = {"box", "sphere", "cylinder", "mesh"};

using W = WorldSettings;
using S = SoftBodyDef;
using R = RigidBodyDef;
using P = SpringDef;

// Ranges are what the physics can honour, not what looks good on a slider: a value outside
// them is refused. Where the book gives a value (Listing 8), it is the default.
const KeyInfo kKeys[] = {
    // --- The world -----------------------------------------------------------------------------
    key<&W::gravity>("gravity", {.label = "Gravity g", .unit = "m/s^2", .meaning = "Gravitational acceleration g, z up (Listing 8: 0,0,-9.81)",
                                 .min = -1e3, .max = 1e3, .presets = kGravities, .slider_min = -30, .slider_max = 30}),
    key<&W::dt>("dt", {.label = "Time step dt", .unit = "s", .meaning = "Fixed physics tick (Listing 8: 0.02)", .min = 0, .max = 1, .above = true,
                       .slider_min = 0.001, .slider_max = 0.05, .slider_log = true}),
    key<&W::substeps>("substeps", {.label = "Substeps a tick", .meaning = "Integration steps of dt/substeps within one tick", .min = 1, .max = 1000,
                                   .slider_min = 1, .slider_max = 64}),
    key<&W::auto_substeps>("auto_substeps", {.label = "Automatic substeps", .meaning = "Use the fewest substeps the stability estimate allows (at least `substeps`)"}),
    key<&W::integrator>("integrator", {.label = "Integrator", .meaning = "verlet (default), symplectic_euler, explicit_euler or rk4", .choices = kIntegrators}),
    key<&W::air_density>("air_density", {.label = "Air density rho", .unit = "kg/m^3", .equation = "Eq. 23", .meaning = "Fluid density rho (air: 1.2)",
                                         .min = 0, .max = 1e4, .slider_min = 0, .slider_max = 1000, .slider_log = true}),
    key<&W::ground>("ground", {.label = "Ground", .meaning = "Whether the ground plane z = ground_height exists"}),
    key<&W::ground_height>("ground_height", {.label = "Ground height", .unit = "m", .meaning = "Height of the ground plane", .min = -1e4, .max = 1e4,
                                             .slider_min = -2, .slider_max = 2}),
    key<&W::restitution>("restitution", {.label = "Bounciness e (ground)", .meaning = "Coefficient of restitution e at the ground: v_n' = -e v_n", .min = 0, .max = 1,
                                         .slider_min = 0, .slider_max = 1}),
    key<&W::static_friction>("static_friction", {.label = "Static friction mu_s", .equation = "Eq. 24", .meaning = "Static friction coefficient mu_s at the ground",
                                                 .min = 0, .max = 2, .slider_min = 0, .slider_max = 2}),
    key<&W::dynamic_friction>("dynamic_friction", {.label = "Sliding friction mu_d", .equation = "Eq. 25", .meaning = "Dynamic friction coefficient mu_d at the ground",
                                                   .min = 0, .max = 2, .slider_min = 0, .slider_max = 2}),
    key<&W::renormalize_every>("renormalize_every",
                               {.label = "Renormalise q every", .unit = "ticks", .equation = "Listing 9",
                                .meaning = "Renormalise each rigid body's quaternion every this many ticks (Listing 9: 5); 0: never, and watch |q| drift",
                                .min = 0, .max = 1e6, .slider_min = 0, .slider_max = 50}),
    key<&W::sleeping>("sleeping", {.label = "Bodies at rest sleep", .meaning = "Rigid bodies at rest (slower than 5 cm/s) for half a second sleep, costing nothing, until touched, grabbed or a key changes"}),

    // --- A soft body ---------------------------------------------------------------------------
    key<&S::mesh>("mesh", {.label = "Mesh file", .meaning = "Mesh file, OBJ or OFF: one particle per distinct vertex position", .on_reset = true}),
    key<&S::scale>("scale", {.label = "Scale", .meaning = "Uniform scale from mesh units to metres; auto: the largest side 1 m, centred",
                             .min = 0, .max = 1e4, .above = true, .on_reset = true, .zero_word = "auto",
                             .slider_min = 0.05, .slider_max = 10, .slider_log = true}),
    key<&S::up_axis>("up_axis", {.label = "Up axis of the file", .meaning = "The file's up axis (x, y, z, -x, -y, -z), turned to point up (+z)", .on_reset = true,
                                 .choices = kAxes}),
    key<&S::rotation>("rotation", {.label = "Rotation", .unit = "deg", .meaning = "Turns the mesh about x, then y, then z, after up_axis",
                                   .min = -360, .max = 360, .on_reset = true, .slider_min = -180, .slider_max = 180}),
    key<&S::init_height>("init_height", {.label = "Starting height", .unit = "m", .meaning = "Height added to every vertex's z at the start (Listing 8)",
                                         .min = -1e4, .max = 1e4, .on_reset = true, .slider_min = 0, .slider_max = 10}),
    key<&S::initial_velocity>("initial_velocity", {.label = "Starting velocity", .unit = "m/s", .meaning = "Velocity of every particle at the start",
                                                   .min = -1e3, .max = 1e3, .on_reset = true, .slider_min = -10, .slider_max = 10}),
    key<&S::position>("position", {.label = "Starting position", .unit = "m",
                                   .meaning = "Where the body's centre of mass goes at the start (none: the mesh's place, lifted by init_height)",
                                   .min = -1e4, .max = 1e4, .on_reset = true}),
    key<&S::angular_velocity>("angular_velocity", {.label = "Starting spin", .unit = "rad/s",
                                                   .meaning = "Spin about the centre of mass at the start, world axes (added to initial_velocity)",
                                                   .min = -1e3, .max = 1e3, .on_reset = true, .slider_min = -20, .slider_max = 20}),
    key<&S::color>("color", {.label = "Colour", .meaning = "The body's colour r, g, b from 0 to 1 (none: the palette's)", .min = 0, .max = 1}),
    key<&S::self_collision>("self_collision", {.label = "Collides with itself", .meaning = "The body's particles collide with its own triangles (not those they belong to)"}),
    key<&S::particle_mass>("particle_mass", {.label = "Mass of a particle m", .unit = "kg", .meaning = "Mass m of each particle (Listing 8: 1)", .min = 0, .max = 1e6,
                                             .above = true, .slider_min = 0.001, .slider_max = 100, .slider_log = true}),
    key<&S::stiffness>("stiffness", {.label = "Spring constant k", .unit = "N/m", .equation = "Eq. 21", .meaning = "Spring constant k between every pair (Listing 8: 10)",
                                     .min = 0, .max = 1e7, .slider_min = 0, .slider_max = 1000, .slider_log = true}),
    key<&S::damping>("damping", {.label = "Damping c", .unit = "kg/s", .equation = "Eq. 22", .meaning = "Damper coefficient c between every pair (Listing 8: 0.1)",
                                 .min = 0, .max = 1e6, .slider_min = 0, .slider_max = 10, .slider_log = true}),
    key<&S::drag_coefficient>("drag_coefficient", {.label = "Drag coefficient C_D", .equation = "Eq. 23",
                                                   .meaning = "Drag coefficient C_D (0.1 to 0.4 for blunt bodies); 0 turns drag off",
                                                   .min = 0, .max = 10, .slider_min = 0, .slider_max = 2}),
    key<&S::pinned>("pinned", {.label = "Pinned vertices", .meaning = "Vertex indices (0-based, as in the file) held fixed in place", .on_reset = true}),
    key<&S::max_particles>("max_particles", {.label = "Most particles", .meaning = "Particle budget: a mesh with more is simulated on this many, drawn in full; all: one per vertex",
                                             .min = 4, .max = 20000, .on_reset = true, .zero_word = "all",
                                             .slider_min = 4, .slider_max = 20000, .slider_log = true}),

    // --- A rigid body --------------------------------------------------------------------------
    key<&R::shape>("shape", {.label = "Shape", .meaning = "box, sphere, cylinder (axis along the body's z) or mesh", .on_reset = true, .choices = kShapes}),
    key<&R::size>("size", {.label = "Size", .unit = "m", .equation = "Table 1", .meaning = "A box's full side lengths a, b, c", .min = 0, .max = 1e4,
                           .above = true, .on_reset = true}),
    key<&R::radius>("radius", {.label = "Radius", .unit = "m", .equation = "Table 1", .meaning = "A sphere's or a cylinder's radius", .min = 0, .max = 1e4,
                               .above = true, .on_reset = true}),
    key<&R::height>("height", {.label = "Height", .unit = "m", .equation = "Table 1", .meaning = "A cylinder's height, along the body's z", .min = 0,
                               .max = 1e4, .above = true, .on_reset = true}),
    key<&R::mesh>("mesh", {.label = "Mesh file", .meaning = "An OBJ or OFF file (shape mesh); it collides through its convex hull", .on_reset = true}),
    key<&R::scale>("scale", {.label = "Scale", .meaning = "Uniform scale from mesh units to metres", .min = 0, .max = 1e4, .above = true, .on_reset = true}),
    key<&R::mass>("mass", {.label = "Mass", .unit = "kg", .meaning = "The body's mass (or give density)", .min = 0, .max = 1e9, .above = true,
                           .on_reset = true, .slider_min = 0.01, .slider_max = 100, .slider_log = true}),
    key<&R::density>("density", {.label = "Density", .unit = "kg/m^3", .equation = "Eq. 20", .meaning = "Mass per volume (default 1000, water)", .min = 0,
                                 .max = 1e6, .above = true, .on_reset = true}),
    key<&R::position>("position", {.label = "Starting position", .unit = "m", .meaning = "Where the centre of mass goes (default: the mesh file's, or the origin)",
                                   .min = -1e4, .max = 1e4, .on_reset = true}),
    key<&R::orientation>("orientation", {.label = "Orientation q", .equation = "Eq. 35", .meaning = "Orientation quaternion w, x, y, z (normalised)", .min = -1e6,
                                         .max = 1e6, .on_reset = true}),
    KeyInfo{.name = "rotation", .label = "Rotation", .owner = KeyOwner::RigidBody, .type = KeyType::Vec3, .unit = "deg",
            .meaning = "Orientation as turns about x, then y, then z (sets orientation)", .min = -360, .max = 360, .on_reset = true,
            .alias = true, .get = &get_rotation, .set = &set_rotation},
    key<&R::velocity>("velocity", {.label = "Starting velocity", .unit = "m/s", .meaning = "Velocity of the centre of mass at the start, world axes", .min = -1e3,
                                   .max = 1e3, .on_reset = true}),
    key<&R::angular_velocity>("angular_velocity", {.label = "Starting spin omega", .unit = "rad/s", .equation = "Eq. 28", .meaning = "Angular velocity at the start, world axes",
                                                   .min = -1e3, .max = 1e3, .on_reset = true}),
    key<&R::fixed>("fixed", {.label = "Fixed in place", .meaning = "Infinite mass: scenery that never moves", .on_reset = true}),
    key<&R::restitution>("restitution", {.label = "Bounciness e", .equation = "Eq. 38", .meaning = "Coefficient of restitution e at its contacts (default: the world's)",
                                         .min = 0, .max = 1, .slider_min = 0, .slider_max = 1}),
    key<&R::friction>("friction", {.label = "Friction mu", .meaning = "Coulomb friction mu at its contacts (default: the world's dynamic_friction)", .min = 0,
                                   .max = 2, .slider_min = 0, .slider_max = 2}),
    key<&R::rolling_resistance>("rolling_resistance",
                                {.label = "Rolling resistance", .meaning = "Rolling resistance C_rr: a sphere or cylinder turning on a contact is held back by a torque C_rr |F_n| r (default 0: none)",
                                 .min = 0, .max = 1, .on_reset = true}),
    key<&R::drag_coefficient>("drag_coefficient", {.label = "Drag coefficient C_D", .equation = "Eq. 23", .meaning = "Drag coefficient C_D at its centre of mass (default 0: none)",
                                                   .min = 0, .max = 10, .on_reset = true}),
    key<&R::color>("color", {.label = "Colour", .meaning = "The body's colour r, g, b from 0 to 1 (default: the palette's)", .min = 0, .max = 1}),

    // --- A spring and its damper ---------------------------------------------------------------
    key<&P::stiffness>("stiffness", {.label = "Spring constant k", .unit = "N/m", .equation = "Eq. 21", .meaning = "Spring constant k (required in a scene file)",
                                     .min = 0, .max = 1e7, .slider_min = 1, .slider_max = 1000, .slider_log = true}),
    key<&P::damping>("damping", {.label = "Damping c", .unit = "kg/s", .equation = "Eq. 22", .meaning = "Damper coefficient c along the spring", .min = 0,
                                 .max = 1e6, .slider_min = 0, .slider_max = 10}),
    key<&P::rest_length>("rest_length", {.label = "Rest length l0", .unit = "m", .equation = "Eq. 21",
                                         .meaning = "Rest length l0 (auto: the distance between the ends at the start)", .min = 0,
                                         .max = 1e6, .unset_word = "auto", .slider_min = 0, .slider_max = 5}),
};

// The shortest text that reads back as the same number: the same float for a float's key
// ("0.02", not "0.0199999996"), the same double for a double's.
std::string number_text(double x, bool single) {
    char text[64];
    const auto result = single ? std::to_chars(text, text + sizeof text, float(x)) : std::to_chars(text, text + sizeof text, x);
    return std::string(text, result.ptr);
}

// The range's numbers as people read them: 9 digits.
std::string short_number(double x) { return number_text(x, true); }

std::string_view trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
    return s;
}

bool parse_number(std::string_view s, double& out, bool single) {
    s = trim(s);
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    if (s.empty() || ec != std::errc() || end != s.data() + s.size() || !std::isfinite(out)) return false;
    if (single) out = double(float(out));  // as the field will hold it
    return std::isfinite(out);
}

bool parse_numbers(std::string_view text, double* out, std::size_t count, bool single) {
    std::size_t got = 0;
    for (;;) {
        const auto comma = text.find(',');
        if (got == count || !parse_number(text.substr(0, comma), out[got], single)) return false;
        ++got;
        if (comma == std::string_view::npos) break;
        text.remove_prefix(comma + 1);
    }
    return got == count;
}

[[noreturn]] void refuse(const KeyInfo& info, const std::string& what) {
    throw InputError("key '" + std::string(info.name) + "': " + what);
}

void check_number(const KeyInfo& info, double value) {
    if (value == 0.0 && !info.zero_word.empty()) return;  // the word's value ("auto", "all")
    const bool low = info.above ? !(value > info.min) : !(value >= info.min);
    if (std::isfinite(value) && !low && value <= info.max) return;
    refuse(info, "must be " + key_range_text(info) + ", got " + short_number(value));
}

std::string choices_text(const KeyInfo& info) {
    std::string out;
    for (std::size_t i = 0; i < info.choices.size(); ++i) {
        out += i == 0 ? "" : i + 1 == info.choices.size() ? " or " : ", ";
        out += info.choices[i];
    }
    return out;
}

std::string_view owner_word(KeyOwner owner) {
    switch (owner) {
        case KeyOwner::World: return "world";
        case KeyOwner::SoftBody: return "soft body";
        case KeyOwner::RigidBody: return "rigid body";
        case KeyOwner::Spring: return "spring";
    }
    return "world";
}

template <class D>
KeyValue get_typed(const D& def, const KeyInfo& info) {
    if (info.owner != owner_of<D>()) throw InputError("key '" + std::string(info.name) + "' is not a " + std::string(owner_word(owner_of<D>())) + "'s");
    return info.get(&def);
}

// "soft body 'jelly': ", "spring: ", or "" for the world: who a refused value was for.
template <class D>
std::string whose(const D& def) {
    if constexpr (std::is_same_v<D, WorldSettings>) {
        return "";
    } else {
        const std::string owner(owner_word(owner_of<D>()));
        return def.name.empty() ? owner + ": " : owner + " '" + printable(def.name) + "': ";
    }
}

template <class D>
void set_typed(D& def, const KeyInfo& info, const KeyValue& value) {
    if (info.owner != owner_of<D>()) throw InputError("key '" + std::string(info.name) + "' is not a " + std::string(owner_word(owner_of<D>())) + "'s");
    try {
        check_key(info, value);
    } catch (const InputError& e) {
        throw InputError(whose(def) + e.what());
    }
    info.set(&def, value);
}

template <class D>
void validate_typed(const D& def, const std::string& prefix) {
    for (const KeyInfo& info : kKeys) {
        if (info.owner != owner_of<D>() || info.alias) continue;
        try {
            check_key(info, info.get(&def));
        } catch (const InputError& e) {
            throw InputError(prefix + e.what());
        }
    }
}

std::string type_word(const KeyInfo& info) {
    switch (info.type) {
        case KeyType::Number: return "number";
        case KeyType::Whole: return "whole number";
        case KeyType::Bool: return "true/false";
        case KeyType::Vec3: return "x,y,z";
        case KeyType::Quat: return "w,x,y,z";
        case KeyType::Word: return "word";
        case KeyType::Path: return "file";
        case KeyType::IndexList: return "indices";
    }
    return "";
}

std::string markdown_cell(std::string_view text) {
    std::string out;
    for (char c : text) {
        if (c == '|') out += "\\|";
        else out += c;
    }
    return out;
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
    for (auto candidate : {Integrator::Verlet, Integrator::SymplecticEuler, Integrator::ExplicitEuler, Integrator::RK4}) {
        if (to_string(candidate) == name) return candidate;
    }
    return std::nullopt;
}

std::string_view to_string(ShapeKind kind) {
    switch (kind) {
        case ShapeKind::Box: return "box";
        case ShapeKind::Sphere: return "sphere";
        case ShapeKind::Cylinder: return "cylinder";
        case ShapeKind::Mesh: return "mesh";
    }
    return "box";
}

std::optional<ShapeKind> shape_from_string(std::string_view name) {
    for (auto candidate : {ShapeKind::Box, ShapeKind::Sphere, ShapeKind::Cylinder, ShapeKind::Mesh}) {
        if (to_string(candidate) == name) return candidate;
    }
    return std::nullopt;
}

std::string_view to_string(KeyOwner owner) { return owner_word(owner); }

bool SoftBodyDef::operator==(const SoftBodyDef& other) const {
    if (name != other.name) return false;
    for (const KeyInfo& info : kKeys) {
        if (info.owner == KeyOwner::SoftBody && !(info.get(this) == info.get(&other))) return false;
    }
    return true;
}

std::vector<std::string> names(const WorldDef& def) {
    std::vector<std::string> out;
    for (const auto& body : def.soft_bodies) out.push_back(body.name);
    for (const auto& body : def.rigid_bodies) out.push_back(body.name);
    for (const auto& spring : def.springs) {
        if (!spring.name.empty()) out.push_back(spring.name);
    }
    return out;
}

std::span<const KeyInfo> key_table() { return kKeys; }

const KeyInfo* find_key(KeyOwner owner, std::string_view name) {
    for (const KeyInfo& info : kKeys) {
        if (info.owner == owner && info.name == name) return &info;
    }
    return nullptr;
}

std::vector<const KeyInfo*> keys_of(KeyOwner owner) {
    std::vector<const KeyInfo*> out;
    for (const KeyInfo& info : kKeys) {
        if (info.owner == owner) out.push_back(&info);
    }
    return out;
}

std::string_view closest_key(KeyOwner owner, std::string_view name) {
    // Levenshtein distance; a key within a third of its length counts as a likely typo.
    std::string_view best;
    std::size_t best_distance = name.size() / 3 + 1;
    for (const KeyInfo& info : kKeys) {
        if (info.owner != owner) continue;
        const std::string_view other = info.name;
        // The distance is at least the difference in length: no need to compute it then
        // (which also keeps a megabyte-long key from costing seconds).
        const std::size_t longer = std::max(name.size(), other.size()), shorter = std::min(name.size(), other.size());
        if (longer - shorter >= best_distance) continue;
        std::vector<std::size_t> row(other.size() + 1);
        for (std::size_t j = 0; j <= other.size(); ++j) row[j] = j;
        for (std::size_t i = 1; i <= name.size(); ++i) {
            std::size_t diagonal = row[0];
            row[0] = i;
            for (std::size_t j = 1; j <= other.size(); ++j) {
                const std::size_t above = row[j];
                row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (name[i - 1] != other[j - 1])});
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

KeyValue default_value(const KeyInfo& info) {
    switch (info.owner) {
        case KeyOwner::World: return info.get(&static_cast<const WorldSettings&>(WorldSettings{}));
        case KeyOwner::SoftBody: return info.get(&static_cast<const SoftBodyDef&>(SoftBodyDef{}));
        case KeyOwner::RigidBody: return info.get(&static_cast<const RigidBodyDef&>(RigidBodyDef{}));
        case KeyOwner::Spring: return info.get(&static_cast<const SpringDef&>(SpringDef{}));
    }
    return {};
}

std::string key_range_text(const KeyInfo& info) {
    switch (info.type) {
        case KeyType::Number:
        case KeyType::Whole:
        case KeyType::Vec3: {
            std::string range = info.above ? "above " + short_number(info.min) + " and at most " + short_number(info.max)
                                           : "between " + short_number(info.min) + " and " + short_number(info.max);
            if (!info.zero_word.empty()) range += ", or " + std::string(info.zero_word);
            if (!info.unit.empty()) range += " " + std::string(info.unit);
            return range;
        }
        case KeyType::Bool: return "true or false";
        case KeyType::Quat: return "four numbers w,x,y,z, not all zero";
        case KeyType::Word: return choices_text(info);
        case KeyType::Path: return "a file path or a generated name";
        case KeyType::IndexList: return "vertex indices from 0";
    }
    return "";
}

void check_key(const KeyInfo& info, const KeyValue& value) {
    if (std::holds_alternative<std::monostate>(value)) {
        if (info.optional || info.alias) return;
        refuse(info, "must be set");
    }
    const auto wrong = [&] { refuse(info, "expected " + key_range_text(info)); };
    switch (info.type) {
        case KeyType::Number:
        case KeyType::Whole: {
            if (!std::holds_alternative<double>(value)) wrong();
            const double x = std::get<double>(value);
            if (info.type == KeyType::Whole && std::isfinite(x) && x != std::floor(x)) refuse(info, "expected a whole number, got " + short_number(x));
            check_number(info, x);
            break;
        }
        case KeyType::Vec3: {
            if (!std::holds_alternative<Vec3d>(value)) wrong();
            const Vec3d v = std::get<Vec3d>(value);
            for (double c : {v.x, v.y, v.z}) check_number(info, c);
            break;
        }
        case KeyType::Quat: {
            if (!std::holds_alternative<Quat>(value)) wrong();
            const Quat q = std::get<Quat>(value);
            for (double c : {q.w, q.x, q.y, q.z}) check_number(info, c);
            if (!(q.norm() > 1e-9)) refuse(info, "a zero quaternion is no orientation (identity: 1,0,0,0)");
            break;
        }
        case KeyType::Bool:
            if (!std::holds_alternative<bool>(value)) wrong();
            break;
        case KeyType::Word: {
            if (!std::holds_alternative<std::string>(value)) wrong();
            const std::string& word = std::get<std::string>(value);
            if (std::find(info.choices.begin(), info.choices.end(), word) == info.choices.end()) {
                refuse(info, "expected " + choices_text(info) + ", got '" + printable(word) + "'");
            }
            break;
        }
        case KeyType::Path:
            if (!std::holds_alternative<std::string>(value)) wrong();
            break;
        case KeyType::IndexList:
            if (!std::holds_alternative<std::vector<std::uint32_t>>(value)) wrong();
            break;
    }
}

KeyValue parse_key_text(const KeyInfo& info, std::string_view text) {
    const std::string_view t = trim(text);
    const auto bad = [&](const std::string& expected) -> KeyValue {
        refuse(info, "expected " + expected + ", got '" + printable(text) + "'");
    };
    if (info.optional && t == info.unset_word) return std::monostate{};
    if (!info.zero_word.empty() && t == info.zero_word) return 0.0;  // "auto", "all": stands for 0
    const std::string or_word = info.optional ? " or " + std::string(info.unset_word)
                                : info.zero_word.empty() ? "" : " or " + std::string(info.zero_word);
    KeyValue value;
    switch (info.type) {
        case KeyType::Number: {
            double x = 0.0;
            if (!parse_number(t, x, info.single)) return bad("a finite number" + or_word);
            value = x;
            break;
        }
        case KeyType::Whole: {
            long long x = 0;
            std::string_view s = t;
            if (!s.empty() && s.front() == '+') s.remove_prefix(1);
            const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), x);
            if (s.empty() || ec != std::errc() || end != s.data() + s.size()) return bad("a whole number" + or_word);
            value = double(x);
            break;
        }
        case KeyType::Bool:
            if (t == "true" || t == "1" || t == "on" || t == "yes") value = true;
            else if (t == "false" || t == "0" || t == "off" || t == "no") value = false;
            else return bad("true or false");
            break;
        case KeyType::Vec3: {
            double v[3];
            if (!parse_numbers(t, v, 3, info.single)) return bad("three finite numbers x,y,z" + or_word);
            value = Vec3d{v[0], v[1], v[2]};
            break;
        }
        case KeyType::Quat: {
            double q[4];
            if (!parse_numbers(t, q, 4, info.single)) return bad("four finite numbers w,x,y,z");
            value = Quat{q[0], q[1], q[2], q[3]};
            break;
        }
        case KeyType::Word:
            value = std::string(t);
            break;
        case KeyType::Path:
            if (t.empty()) return bad("a file path");
            value = std::string(t);
            break;
        case KeyType::IndexList: {
            std::vector<std::uint32_t> list;
            std::string_view rest = t;
            while (!rest.empty()) {
                const auto comma = rest.find(',');
                std::string_view part = trim(rest.substr(0, comma));
                long long index = -1;
                const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), index);
                if (part.empty() || ec != std::errc() || end != part.data() + part.size() || index < 0 || index > 0xFFFFFFFEll) {
                    return bad("vertex indices (whole numbers from 0) separated by commas");
                }
                list.push_back(std::uint32_t(index));
                if (comma == std::string_view::npos) break;
                rest.remove_prefix(comma + 1);
                if (trim(rest).empty()) return bad("vertex indices (whole numbers from 0) separated by commas");
            }
            value = std::move(list);
            break;
        }
    }
    check_key(info, value);
    return value;
}

std::string key_text(const KeyInfo& info, const KeyValue& value) {
    if (std::holds_alternative<std::monostate>(value)) return std::string(info.unset_word.empty() ? "none" : info.unset_word);
    if (const double* x = std::get_if<double>(&value)) {
        if (*x == 0.0 && !info.zero_word.empty()) return std::string(info.zero_word);
        if (info.type == KeyType::Whole) return std::to_string(std::llround(*x));
        return number_text(*x, info.single);
    }
    if (const bool* b = std::get_if<bool>(&value)) return *b ? "true" : "false";
    if (const Vec3d* v = std::get_if<Vec3d>(&value)) {
        return number_text(v->x, info.single) + "," + number_text(v->y, info.single) + "," + number_text(v->z, info.single);
    }
    if (const Quat* q = std::get_if<Quat>(&value)) {
        return number_text(q->w, false) + "," + number_text(q->x, false) + "," + number_text(q->y, false) + "," + number_text(q->z, false);
    }
    if (const std::string* s = std::get_if<std::string>(&value)) return *s;
    std::string out;
    for (std::uint32_t index : std::get<std::vector<std::uint32_t>>(value)) out += (out.empty() ? "" : ",") + std::to_string(index);
    return out;
}

KeyValue get_key(const WorldSettings& def, const KeyInfo& info) { return get_typed(def, info); }
KeyValue get_key(const SoftBodyDef& def, const KeyInfo& info) { return get_typed(def, info); }
KeyValue get_key(const RigidBodyDef& def, const KeyInfo& info) { return get_typed(def, info); }
KeyValue get_key(const SpringDef& def, const KeyInfo& info) { return get_typed(def, info); }
void set_key(WorldSettings& def, const KeyInfo& info, const KeyValue& value) { set_typed(def, info, value); }
void set_key(SoftBodyDef& def, const KeyInfo& info, const KeyValue& value) { set_typed(def, info, value); }
void set_key(RigidBodyDef& def, const KeyInfo& info, const KeyValue& value) { set_typed(def, info, value); }
void set_key(SpringDef& def, const KeyInfo& info, const KeyValue& value) { set_typed(def, info, value); }

void validate(const WorldSettings& settings) { validate_typed(settings, whose(settings)); }
void validate(const SoftBodyDef& def) { validate_typed(def, whose(def)); }
void validate(const RigidBodyDef& def) { validate_typed(def, whose(def)); }
void validate(const SpringDef& def) { validate_typed(def, whose(def)); }

KeyName split_key_name(std::string_view name) {
    const auto dot = name.rfind('.');
    if (dot == std::string_view::npos) return {{}, name};
    return {std::string(name.substr(0, dot)), name.substr(dot + 1)};
}

ThingNames thing_names(const WorldDef& def) {
    ThingNames out;
    for (const SoftBodyDef& body : def.soft_bodies) out.soft.push_back(body.name);
    for (const RigidBodyDef& body : def.rigid_bodies) out.rigid.push_back(body.name);
    for (const SpringDef& spring : def.springs) out.springs.push_back(spring.name);
    return out;
}

std::vector<KeyTarget> resolve_key(std::string_view name, const ThingNames& names) {
    const KeyName k = split_key_name(name);
    const auto unknown = [&](KeyOwner owner, const std::string& what) {
        std::string message = what + "unknown key '" + printable(k.key) + "'";
        if (auto hint = closest_key(owner, k.key); !hint.empty()) message += " (did you mean '" + std::string(hint) + "'?)";
        throw InputError(message);
    };
    if (k.thing.empty()) {
        if (const KeyInfo* info = find_key(KeyOwner::World, k.key)) return {{KeyOwner::World, 0, info}};
        const KeyInfo* info = find_key(KeyOwner::SoftBody, k.key);
        if (!info) {
            std::string message = "unknown key '" + printable(name) + "'";
            std::string_view hint = closest_key(KeyOwner::World, k.key);
            if (hint.empty()) hint = closest_key(KeyOwner::SoftBody, k.key);
            if (!hint.empty()) message += " (did you mean '" + std::string(hint) + "'?)";
            throw InputError(message);
        }
        if (names.soft.empty()) {
            // A key a soft body has, in a world without one: the named things that have it.
            std::string named;
            const auto offer = [&](const std::vector<std::string_view>& list, KeyOwner owner) {
                if (!find_key(owner, k.key)) return;
                for (std::string_view thing : list) {
                    if (!thing.empty()) named += (named.empty() ? "" : ", ") + std::string(thing) + "." + std::string(k.key);
                }
            };
            offer(names.springs, KeyOwner::Spring);
            offer(names.rigid, KeyOwner::RigidBody);
            throw InputError("key '" + printable(name) + "' is a soft body's, and there is no soft body" +
                             (named.empty() ? std::string() : " (did you mean " + named + "?)"));
        }
        std::vector<KeyTarget> every;
        for (std::size_t b = 0; b < names.soft.size(); ++b) every.push_back({KeyOwner::SoftBody, b, info});
        return every;
    }
    const auto find = [&](const std::vector<std::string_view>& list) {
        const auto it = std::find(list.begin(), list.end(), k.thing);
        return it == list.end() ? std::optional<std::size_t>() : std::size_t(it - list.begin());
    };
    if (const auto b = find(names.soft)) {
        const KeyInfo* info = find_key(KeyOwner::SoftBody, k.key);
        if (!info && find_key(KeyOwner::World, k.key)) {
            throw InputError("'" + std::string(k.key) + "' is a world key: set it as " + std::string(k.key) + "=VALUE");
        }
        if (!info) unknown(KeyOwner::SoftBody, "soft body '" + printable(k.thing) + "': ");
        return {{KeyOwner::SoftBody, *b, info}};
    }
    if (const auto b = find(names.rigid)) {
        const KeyInfo* info = find_key(KeyOwner::RigidBody, k.key);
        if (!info) unknown(KeyOwner::RigidBody, "rigid body '" + printable(k.thing) + "': ");
        return {{KeyOwner::RigidBody, *b, info}};
    }
    if (const auto s = find(names.springs)) {
        const KeyInfo* info = find_key(KeyOwner::Spring, k.key);
        if (!info) unknown(KeyOwner::Spring, "spring '" + printable(k.thing) + "': ");
        return {{KeyOwner::Spring, *s, info}};
    }
    std::string known;
    for (const auto* list : {&names.soft, &names.rigid, &names.springs}) {
        for (std::string_view thing : *list) {
            if (!thing.empty()) known += (known.empty() ? "" : ", ") + std::string(thing);
        }
    }
    throw InputError("'" + printable(name) + "': nothing is named '" + printable(k.thing) + "'" +
                     (known.empty() ? std::string(" (nothing in the scene has a name)") : " (names: " + known + ")"));
}

KeyValue parse_key_text(const KeyTarget& t, const ThingNames& names, std::string_view text) {
    try {
        return parse_key_text(*t.info, text);
    } catch (const InputError& e) {
        const std::vector<std::string_view>* list = t.owner == KeyOwner::SoftBody ? &names.soft
                                                    : t.owner == KeyOwner::RigidBody ? &names.rigid
                                                    : t.owner == KeyOwner::Spring    ? &names.springs
                                                                                     : nullptr;
        if (!list || t.index >= list->size() || (*list)[t.index].empty()) throw;
        throw InputError(std::string(owner_word(t.owner)) + " '" + printable((*list)[t.index]) + "': " + e.what());
    }
}

KeyValue get_key(const WorldDef& def, const KeyTarget& t) {
    switch (t.owner) {
        case KeyOwner::World: return get_key(def.settings, *t.info);
        case KeyOwner::SoftBody: return get_key(def.soft_bodies.at(t.index), *t.info);
        case KeyOwner::RigidBody: return get_key(def.rigid_bodies.at(t.index), *t.info);
        case KeyOwner::Spring: return get_key(def.springs.at(t.index), *t.info);
    }
    return {};
}

void set_key(WorldDef& def, const KeyTarget& t, const KeyValue& value) {
    switch (t.owner) {
        case KeyOwner::World: return set_key(def.settings, *t.info, value);
        case KeyOwner::SoftBody: return set_key(def.soft_bodies.at(t.index), *t.info, value);
        case KeyOwner::RigidBody: return set_key(def.rigid_bodies.at(t.index), *t.info, value);
        case KeyOwner::Spring: return set_key(def.springs.at(t.index), *t.info, value);
    }
}

std::string keys_text() {
    std::string out;
    for (KeyOwner owner : {KeyOwner::World, KeyOwner::SoftBody, KeyOwner::RigidBody, KeyOwner::Spring}) {
        out += std::string(out.empty() ? "" : "\n") + "Keys of a " + std::string(owner_word(owner)) +
               (owner == KeyOwner::World ? " (--set KEY=VALUE)" : " (--set NAME.KEY=VALUE)") + ":\n";
        for (const KeyInfo* info : keys_of(owner)) {
            std::string line = "  " + std::string(info->name);
            line.resize(std::max<std::size_t>(line.size() + 1, 22), ' ');
            const std::string value = info->alias ? "-" : key_text(*info, default_value(*info));
            line += "default " + (value.empty() ? std::string("(none)") : value);
            if (!info->unit.empty()) line += " " + std::string(info->unit);
            line.resize(std::max<std::size_t>(line.size() + 1, 52), ' ');
            line += std::string(info->meaning);
            if (!info->equation.empty()) line += " [" + std::string(info->equation) + "]";
            if (info->on_reset) line += " (on reset)";
            out += line + "\n";
        }
    }
    return out;
}

std::string keys_markdown() {
    std::string out;
    for (KeyOwner owner : {KeyOwner::World, KeyOwner::SoftBody, KeyOwner::RigidBody, KeyOwner::Spring}) {
        std::string title(owner_word(owner));
        title[0] = char(std::toupper(title[0]));
        out += std::string(out.empty() ? "" : "\n") + "#### " + title + "\n\n";
        out += "| key | type | unit | valid | default | equation | meaning | applies |\n";
        out += "|---|---|---|---|---|---|---|---|\n";
        for (const KeyInfo* info : keys_of(owner)) {
            const std::string value = info->alias ? "" : key_text(*info, default_value(*info));
            out += "| `" + std::string(info->name) + "` | " + type_word(*info) + " | " + std::string(info->unit) + " | " +
                   markdown_cell(key_range_text(*info)) + " | " + (value.empty() ? "" : "`" + markdown_cell(value) + "`") + " | " +
                   std::string(info->equation) + " | " + markdown_cell(info->meaning) + " | " +
                   (info->on_reset ? "on reset" : "at once") + " |\n";
        }
    }
    return out;
}

std::string keys_json() {
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (const KeyInfo& info : kKeys) {
        nlohmann::ordered_json entry = {{"name", info.name},
                                        {"owner", owner_word(info.owner)},
                                        {"type", type_word(info)},
                                        {"unit", info.unit},
                                        {"equation", info.equation},
                                        {"meaning", info.meaning},
                                        {"valid", key_range_text(info)},
                                        {"on_reset", info.on_reset}};
        if (info.type == KeyType::Number || info.type == KeyType::Whole || info.type == KeyType::Vec3) {
            entry["min"] = info.min;
            entry["max"] = info.max;
            entry["above"] = info.above;
        }
        if (!info.choices.empty()) {
            entry["choices"] = nlohmann::ordered_json::array();
            for (std::string_view c : info.choices) entry["choices"].push_back(c);
        }
        if (info.optional) entry["unset"] = info.unset_word;
        if (!info.zero_word.empty()) entry["zero"] = info.zero_word;
        if (!info.alias) entry["default"] = key_text(info, default_value(info));
        if (info.slider_max > info.slider_min) {
            entry["slider"] = {{"min", info.slider_min}, {"max", info.slider_max}, {"log", info.slider_log}};
        }
        list.push_back(entry);
    }
    return list.dump(2) + "\n";
}

}  // namespace softbody

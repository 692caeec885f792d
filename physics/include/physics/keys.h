// The one table of keys: every key of the world, of a soft body, of a rigid body and of a
// spring, with its type, unit, valid range, default, equation, meaning and whether it applies
// at once or on reset. Scene files, `--set`, the app's sliders, `softbody keys` and the
// documentation's key tables all read it; each entry is bound to its field of the definition
// structs (defs.h), so a key is written twice: its field and its line here.
//
// Values travel typed (KeyValue): a slider hands over the number it holds, checked once on
// the way in (set_key); text is for the command line and is parsed once (parse_key_text).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "physics/defs.h"

namespace softbody {

// Whose key it is.
enum class KeyOwner { World, SoftBody, RigidBody, Spring };
std::string_view to_string(KeyOwner owner);  // "world", "soft body", "rigid body", "spring"

enum class KeyType {
    Number,     // a real number
    Whole,      // a whole number
    Bool,       // true or false
    Vec3,       // three numbers x, y, z (each within the range)
    Quat,       // four numbers w, x, y, z (not all zero)
    Word,       // one of `choices`
    Path,       // a file path or a generated name
    IndexList,  // vertex indices
};

// A key's value. std::monostate: unset (an optional key left out: "none" as text).
using KeyValue = std::variant<std::monostate, double, bool, Vec3d, Quat, std::string, std::vector<std::uint32_t>>;

// A value a key is often given, by name: "Moon" for gravity 0,0,-1.62. Its text as --set takes it.
struct KeyPreset {
    std::string_view name, text;
};

struct KeyInfo {
    std::string_view name{};
    std::string_view label{};    // in plain words, for a slider: "Spring constant k"
    KeyOwner owner = KeyOwner::World;
    KeyType type = KeyType::Number;
    std::string_view unit{};       // "" when it has none
    std::string_view equation{};   // "Eq. 21", or "" when it enters no numbered equation
    std::string_view meaning{};    // one line, for tooltips, `softbody keys` and the docs
    double min = 0.0, max = 0.0; // valid range (numbers, and each component of a vector)
    bool above = false;          // the range excludes min (a mass, a size)
    bool on_reset = false;       // takes effect at the next reset (it changes how the body is built)
    bool optional = false;       // may be unset (`unset_word` as text)
    std::string_view unset_word{}; // the text for unset: "none", "auto"
    std::string_view zero_word{};  // a word that stands for 0, outside the range: "auto", "all"
    std::span<const std::string_view> choices{};  // a Word's words
    std::span<const KeyPreset> presets{};         // named values the app offers beside its widget
    double slider_min = 0.0, slider_max = 0.0;  // the app's slider (0, 0: no slider)
    bool slider_log = false;                    // a slider over decades (stiffness, mass)
    bool single = false;         // held as float: text and files keep 9 digits
    bool alias = false;          // write-only: sets another key (a rigid body's rotation sets its orientation)

    // The field it is bound to, on a definition of `owner`'s kind (type-checked by the typed
    // overloads below, not by callers).
    KeyValue (*get)(const void* def) = nullptr;
    void (*set)(void* def, const KeyValue& value) = nullptr;
};

std::span<const KeyInfo> key_table();
const KeyInfo* find_key(KeyOwner owner, std::string_view name);
// The keys of one owner, in the table's order.
std::vector<const KeyInfo*> keys_of(KeyOwner owner);
// The closest key of `owner` to a misspelt one, for "did you mean" ("" when none is close).
std::string_view closest_key(KeyOwner owner, std::string_view name);

// The default: the value a default-made definition holds.
KeyValue default_value(const KeyInfo& info);

// Reads command-line text ("10", "0,0,-9.81", "true", "rk4", "0,5,7", "none", "auto") as a
// value of the key, checked. Throws InputError "key 'NAME': ..." naming what was expected.
KeyValue parse_key_text(const KeyInfo& info, std::string_view text);
// The value as command-line text (parse_key_text reads it back to the same value).
std::string key_text(const KeyInfo& info, const KeyValue& value);
// Throws InputError "key 'NAME': must be ..." when the value is of the wrong kind or out of range.
void check_key(const KeyInfo& info, const KeyValue& value);
// The range as words: "between 0 and 1e+07 N/m", "above 0 and at most 1e+06 kg", or the choices.
std::string key_range_text(const KeyInfo& info);

// Reading and writing a definition's key. set_key checks the value first (check_key) and
// throws InputError naming the key; the definition is unchanged then.
KeyValue get_key(const WorldSettings& def, const KeyInfo& info);
KeyValue get_key(const SoftBodyDef& def, const KeyInfo& info);
KeyValue get_key(const RigidBodyDef& def, const KeyInfo& info);
KeyValue get_key(const SpringDef& def, const KeyInfo& info);
void set_key(WorldSettings& def, const KeyInfo& info, const KeyValue& value);
void set_key(SoftBodyDef& def, const KeyInfo& info, const KeyValue& value);
void set_key(RigidBodyDef& def, const KeyInfo& info, const KeyValue& value);
void set_key(SpringDef& def, const KeyInfo& info, const KeyValue& value);

// Every key of a definition within its range. Throws InputError naming the key (and the thing:
// "soft body 'jelly': key 'stiffness': ...").
void validate(const WorldSettings& settings);
void validate(const SoftBodyDef& def);
void validate(const RigidBodyDef& def);
void validate(const SpringDef& def);

// The table as `softbody keys` prints it: plain text, a Markdown table per owner (the docs'
// tables are this, and a test compares them), or JSON.
std::string keys_text();
std::string keys_markdown();
std::string keys_json();

// A key as a scene and the command line name it: "dt" (the world's), "stiffness" (every soft
// body's), "bob.mass" (the thing named bob's).
struct KeyName {
    std::string thing;       // empty: the world's, or every soft body's
    std::string_view key;
};
KeyName split_key_name(std::string_view name);

// What a key's name names in a world: the world's key, one key of every soft body, or one
// thing's key (owner, and the thing's index among its kind).
struct KeyTarget {
    KeyOwner owner = KeyOwner::World;
    std::size_t index = 0;
    const KeyInfo* info = nullptr;
};
// The names of the things in a world, in order, by kind (a spring's may be empty).
struct ThingNames {
    std::vector<std::string_view> soft, rigid, springs;
};
ThingNames thing_names(const WorldDef& def);
// Throws InputError naming the key: unknown (with the closest key), a soft body's key where
// there is no soft body (with the named things that have it), a name nothing has.
std::vector<KeyTarget> resolve_key(std::string_view name, const ThingNames& names);

// Reads text as the value of the key a name resolves to ("rigid body 'bob': key 'mass': ..."
// when refused).
KeyValue parse_key_text(const KeyTarget& target, const ThingNames& names, std::string_view text);

// One key of a world's definition, as resolve_key found it.
KeyValue get_key(const WorldDef& def, const KeyTarget& target);
void set_key(WorldDef& def, const KeyTarget& target, const KeyValue& value);

}  // namespace softbody

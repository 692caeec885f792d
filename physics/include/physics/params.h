// Every tunable of the simulation, with one set of names shared by scene files (JSON),
// `--set key=value` on the command line, the UI's sliders and README.md's table.
//
// Units are SI. Equation numbers are the addendum's (see README.md, "Equations in the code").
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "physics/vec3.h"

namespace softbody {

enum class Integrator {
    Verlet,           // position Verlet + explicit Euler velocities (Listing 8's advice)
    SymplecticEuler,  // v += a h, then x += v h
    ExplicitEuler,    // x += v h and v += a h from the same state (Listings 10, 11)
    RK4,              // classic Runge-Kutta, four force evaluations per step
};
std::string_view to_string(Integrator integrator);
std::optional<Integrator> integrator_from_string(std::string_view name);

struct Params {
    std::string mesh;                          // OBJ or OFF file (or a generated name, generated.h)
    float scale = 1.0f;                        // mesh units -> metres; 0: automatic ("auto", see soft_body.h)
    std::string up_axis = "z";                 // the file's up axis, turned to +z: x, y, z, -x, -y or -z
    Vec3 rotation{0.0f, 0.0f, 0.0f};           // degrees about x, then y, then z, after up_axis
    float init_height = 2.0f;                  // m added to every vertex's z (Listing 8)
    Vec3 initial_velocity{0.0f, 0.0f, 0.0f};   // m/s, every particle
    std::optional<Vec3> position;              // m: where the centre of mass goes (instead of init_height)
    Vec3 angular_velocity{0.0f, 0.0f, 0.0f};   // rad/s about the centre of mass, world axes, at the start
    std::optional<Vec3> color;                 // r, g, b from 0 to 1 (empty: the palette's)
    bool self_collision = false;               // the body's particles against its own triangles
    float particle_mass = 1.0f;                // kg per particle (Listing 8)
    float stiffness = 10.0f;                   // k, N/m (Eq. 21)
    float damping = 0.1f;                      // c, kg/s (Eq. 22)
    Vec3 gravity{0.0f, 0.0f, -9.81f};          // m/s^2, z is up
    float dt = 0.02f;                          // s, the fixed tick
    int substeps = 1;                          // steps of dt/substeps within one tick
    bool auto_substeps = true;                 // pick the fewest substeps that stay stable (Listing 8: false)
    Integrator integrator = Integrator::Verlet;
    float drag_coefficient = 0.3f;             // C_D (Eq. 23)
    float air_density = 1.2f;                  // rho, kg/m^3 (Eq. 23)
    bool ground = true;                        // a plane z = ground_height
    float ground_height = 0.0f;                // m
    float restitution = 0.3f;                  // e, normal bounce
    float static_friction = 0.6f;              // mu_s (Eq. 24)
    float dynamic_friction = 0.4f;             // mu_d (Eq. 25)
    std::vector<std::uint32_t> pinned;         // vertex indices (0-based, as in the file)
    int max_particles = 3000;                  // particle budget: a larger mesh is simulated on this many; 0: all
    int renormalize_every = 5;                 // ticks between renormalising quaternions (Listing 9); 0: never
    bool sleeping = true;                      // rigid bodies at rest sleep until touched (World, sleep.h)

    bool operator==(const Params&) const = default;
};

// OptionalVec3: three numbers, or the word "none" (unset; a scene file leaves the key out).
enum class ParamType { Float, Int, Bool, Vec3, String, Integrator, IndexList, Axis, OptionalVec3 };

// Whose key it is: the world's (dt, gravity, the ground, ...), or a soft body's (its mesh,
// mass, springs, ...). A scene file's flat keys hold both: the world's and those of the soft
// body named "body"; each entry of "soft_bodies" holds body keys only.
enum class ParamScope { World, Body };

// Describes one key: for validation, documentation and the UI.
struct ParamInfo {
    std::string_view key;
    ParamType type;
    std::string_view unit;      // "" when it has none
    std::string_view equation;  // "Eq. 21", or "" when it enters no numbered equation
    std::string_view summary;   // one line for tooltips and README.md
    double min = 0.0;           // valid range (numbers, and each component of a vector)
    double max = 0.0;
    bool min_exclusive = false;
    bool live = true;           // false: takes effect on reset (it changes the particles)
    ParamScope scope = ParamScope::World;
    std::string_view zero_word = {};  // a word that stands for 0, outside the range: "auto", "all"
};
std::span<const ParamInfo> param_table();
const ParamInfo* find_param(std::string_view key);

// Throws InputError naming the key when a value is out of range or not finite.
void validate(const Params& params);

// Sets one key from command-line text ("10", "0,0,-9.81", "true", "rk4", "0,5,7").
// Throws InputError naming the key for an unknown key or a bad value.
void set_param(Params& params, std::string_view key, std::string_view text);

// The value of one key as command-line text (the inverse of set_param).
std::string param_text(const Params& params, std::string_view key);

// Closest known key to a misspelt one, for "did you mean" hints ("" when none is close).
std::string_view closest_key(std::string_view key);

}  // namespace softbody

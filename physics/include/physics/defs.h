// What a world is made from: its own settings, and one plain definition per thing in it (a soft
// body, a rigid body, a spring with its damper). Each thing has a name and its own keys; the
// keys' units, ranges, equations and meanings are in one table (keys.h), which the scene files,
// `--set`, the sliders and the documentation all read.
//
// Default-constructed, each struct holds the keys' defaults: Listing 8's constants where the
// addendum gives them. Units are SI; the world is z-up.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "physics/mesh.h"
#include "physics/quat.h"
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

// The world's own keys: the tick, gravity, the integrator, the ground, the air and the
// materials contacts use when a body does not set its own.
struct WorldSettings {
    Vec3 gravity{0.0f, 0.0f, -9.81f};  // m/s^2, z is up (Listing 8)
    float dt = 0.02f;                  // s, the fixed tick (Listing 8)
    int substeps = 1;                  // steps of dt/substeps within one tick
    bool auto_substeps = true;         // the fewest substeps that stay stable (Listing 8: false)
    Integrator integrator = Integrator::Verlet;
    float air_density = 1.2f;          // rho of Eq. 23, kg/m^3
    bool ground = true;                // a plane z = ground_height
    float ground_height = 0.0f;        // m
    float restitution = 0.3f;          // e at the ground, and the default of every body
    float static_friction = 0.6f;      // mu_s (Eq. 24)
    float dynamic_friction = 0.4f;     // mu_d (Eq. 25)
    int renormalize_every = 5;         // ticks between renormalising quaternions (Listing 9); 0: never
    bool sleeping = true;              // rigid bodies at rest sleep until touched (sleep.h)

    bool operator==(const WorldSettings&) const = default;
};

// One soft body of Listing 8: a particle at every distinct vertex of its mesh, a spring and a
// damper between every pair.
struct SoftBodyDef {
    std::string name;
    std::string mesh;                          // OBJ or OFF file, or a generated name (generated.h)
    float scale = 1.0f;                        // mesh units -> metres; 0: automatic ("auto", soft_body.h)
    std::string up_axis = "z";                 // the file's up axis, turned to +z: x, y, z, -x, -y or -z
    Vec3 rotation{0.0f, 0.0f, 0.0f};           // degrees about x, then y, then z, after up_axis
    float init_height = 2.0f;                  // m added to every vertex's z (Listing 8)
    Vec3 initial_velocity{0.0f, 0.0f, 0.0f};   // m/s, every particle
    std::optional<Vec3> position;              // m: where the centre of mass goes (instead of init_height)
    Vec3 angular_velocity{0.0f, 0.0f, 0.0f};   // rad/s about the centre of mass, world axes
    std::optional<Vec3> color;                 // r, g, b from 0 to 1 (empty: the palette's)
    bool self_collision = false;               // the body's particles against its own triangles
    float particle_mass = 1.0f;                // kg per particle (Listing 8)
    float stiffness = 10.0f;                   // k, N/m (Eq. 21; Listing 8)
    float damping = 0.1f;                      // c, kg/s (Eq. 22; Listing 8)
    float drag_coefficient = 0.3f;             // C_D (Eq. 23)
    std::vector<std::uint32_t> pinned;         // vertex indices (0-based, as in the file)
    int max_particles = 3000;                  // particle budget (mesh_reduce.h); 0: all

    // The mesh as loaded, when the caller has it (a test's, the app's Add menu); empty: the
    // world loads `mesh`. Not a key: two definitions with the same keys are equal.
    std::shared_ptr<const Mesh> geometry;

    bool operator==(const SoftBodyDef& other) const;
};

enum class ShapeKind { Box, Sphere, Cylinder, Mesh };
std::string_view to_string(ShapeKind kind);
std::optional<ShapeKind> shape_from_string(std::string_view name);

// A rigid body (Listings 9-11). Keys left out keep these values; the optional ones left out
// are empty (and the shape's dimensions must then be given: a box without a size is refused).
struct RigidBodyDef {
    std::string name;
    ShapeKind shape = ShapeKind::Box;
    std::optional<Vec3d> size;         // box: full side lengths, m
    std::optional<double> radius;      // sphere, cylinder: m
    std::optional<double> height;      // cylinder, along the body's z: m
    std::string mesh;                  // mesh: an OBJ or OFF file
    double scale = 1.0;                // mesh: file units to metres
    std::optional<double> mass;        // kg; or
    std::optional<double> density;     // kg/m^3 (default 1000, water)
    std::optional<Vec3d> position;     // where the centre of mass goes, m (default: the file's, or the origin)
    Quat orientation;                  // quaternion w, x, y, z (or `rotation`, degrees about x, y, z);
                                       // normalised when the body is made
    Vec3d velocity;                    // m/s, world axes
    Vec3d angular_velocity;            // rad/s, world axes
    bool fixed = false;                // infinite mass: scenery
    std::optional<float> restitution;  // e at contacts (default: the world's `restitution`)
    std::optional<float> friction;     // mu at contacts (default: the world's `dynamic_friction`)
    float drag_coefficient = 0.0f;     // C_D of Eq. 23 (default 0: no drag)
    float rolling_resistance = 0.0f;   // C_rr: a round body's turn on a contact is held back by
                                       // C_rr |F_n| r (default 0: none)
    std::optional<Vec3d> color;        // r, g, b from 0 to 1 (default: the palette's)

    bool operator==(const RigidBodyDef&) const = default;
};

// An end of a spring: { "body": NAME, "point": [x, y, z] } on a rigid body (its own axes, from
// its centre of mass), { "body": NAME, "vertex": K } on a soft body, { "point": [x, y, z] }
// fixed in the world.
struct SpringEndDef {
    std::string body;                    // empty: the world
    std::optional<Vec3d> point;          // body axes from the centre of mass (rigid), or world (no body)
    std::optional<std::int64_t> vertex;  // a soft body's vertex, numbered as in its file from 0
    bool operator==(const SpringEndDef&) const = default;
};

// A spring (Eq. 21) with its damper (Eq. 22) between two ends. With a name, its keys are set
// like a body's: NAME.stiffness, NAME.damping, NAME.rest_length.
struct SpringDef {
    std::string name;                   // may be empty
    SpringEndDef a, b;
    double stiffness = 0.0;             // k, N/m (a scene file must give it)
    double damping = 0.0;               // c, kg/s
    std::optional<double> rest_length;  // l0, m (empty: the ends' distance at the start)
    bool operator==(const SpringDef&) const = default;
};

// A whole world: its settings and what is in it, in order (the order is part of the result:
// bodies are stepped and hashed in it).
struct WorldDef {
    WorldSettings settings;
    std::vector<SoftBodyDef> soft_bodies;
    std::vector<RigidBodyDef> rigid_bodies;
    std::vector<SpringDef> springs;
    bool operator==(const WorldDef&) const = default;
    bool empty() const { return soft_bodies.empty() && rigid_bodies.empty(); }
};

// Every name in the world, in order: the soft bodies, the rigid bodies, then the named springs.
std::vector<std::string> names(const WorldDef& def);

}  // namespace softbody

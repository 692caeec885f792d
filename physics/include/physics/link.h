// Springs with dampers between bodies (Eq. 21, 22), each end a point fixed on a rigid body (in
// its own axes, from its centre of mass), a vertex of a soft body, or a point fixed in the
// world. Each end gets its force and, on a rigid body, the torque r x F about the centre of
// mass (Eq. 27, 33; the addendum's Figure 2).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "physics/vec3.h"

namespace softbody {

// An end as a scene file names it: { "body": NAME, "point": [x, y, z] } on a rigid body,
// { "body": NAME, "vertex": K } on a soft body, { "point": [x, y, z] } fixed in the world.
struct SpringEndDef {
    std::string body;             // empty: the world
    std::optional<Vec3d> point;   // body axes from the centre of mass (rigid), or world (no body)
    std::optional<std::int64_t> vertex;  // a soft body's vertex, numbered as in its file from 0
    bool operator==(const SpringEndDef&) const = default;
};

struct SpringDef {
    SpringEndDef a, b;
    std::optional<double> stiffness;    // k, N/m (required)
    double damping = 0.0;               // c, kg/s
    std::optional<double> rest_length;  // l0, m (default: the ends' distance at the start)
    bool operator==(const SpringDef&) const = default;
};

// An end once the names are resolved: indices, not names or pointers.
struct LinkEnd {
    enum class Kind { World, Rigid, Soft } kind = Kind::World;
    std::uint32_t body = 0;      // index among the rigid or the soft bodies
    std::uint32_t particle = 0;  // Soft: the particle of the vertex
    Vec3d point;                 // World: where; Rigid: in body axes from the centre of mass
};

struct Link {
    LinkEnd a, b;
    double k = 0.0;   // stiffness, N/m (Eq. 21)
    double c = 0.0;   // damping, kg/s (Eq. 22)
    double l0 = 0.0;  // rest length, m
};

}  // namespace softbody

// Springs with dampers between bodies (Eq. 21, 22), each end a point fixed on a rigid body (in
// its own axes, from its centre of mass), a vertex of a soft body, or a point fixed in the
// world. Each end gets its force and, on a rigid body, the torque r x F about the centre of
// mass (Eq. 27, 33; the addendum's Figure 2).
#pragma once

#include <cstdint>
#include "physics/defs.h"
#include "physics/vec3.h"

namespace softbody {

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

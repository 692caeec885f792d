// Rigid bodies: the addendum's second half (Eq. 26-36, Listings 9-11).
//
// A rigid body's state is Listing 10's thirteen numbers: linear momentum P, centre-of-mass
// position x, angular momentum L and orientation quaternion q. The World keeps every body's
// thirteen in one flat array, and one implementation of each integrator advances them all
// (Listing 11's point; integrators.cpp). They are held in double rather than Listing 10's
// float: resting contact and the closed-form tests (a flip period, a precession rate) want
// the digits, and a few hundred bodies cost nothing either way.
//
// What is fixed about a body (its shape, mass and inertia tensor in its own axes, about its
// centre of mass) lives here; what changes lives in the flat array.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "physics/convex_hull.h"
#include "physics/defs.h"
#include "physics/mat3.h"
#include "physics/mesh.h"
#include "physics/quat.h"
#include "physics/vec3.h"

namespace softbody {

// Listing 10's layout of one body's thirteen numbers in the flat state array.
namespace rigid {
inline constexpr int kStateSize = 13;
inline constexpr int P = 0;   // linear momentum, kg m/s
inline constexpr int X = 3;   // centre-of-mass position, m
inline constexpr int L = 6;   // angular momentum about the centre of mass, kg m^2/s
inline constexpr int Q = 9;   // orientation quaternion w, x, y, z (body to world)
}  // namespace rigid

// What a body is made of, once its shape is known: everything the simulation needs that never
// changes. Built by make_rigid_body().
struct RigidBody {
    std::string name;
    ShapeKind shape = ShapeKind::Box;
    Vec3d size;                 // box
    double radius = 0.0;        // sphere, cylinder
    double height = 0.0;        // cylinder
    std::shared_ptr<const ConvexHull> hull;  // collision shape in body axes about the centre of
                                             // mass (box, cylinder, mesh; none for a sphere)
    Mesh render_mesh;           // for drawing, in body axes about the centre of mass
    double bounding_radius = 0.0;  // from the centre of mass
    double volume = 0.0;
    bool hull_mass_properties = false;  // an open or non-manifold mesh: its hull's were used

    double mass = 0.0;          // kg (infinite when fixed: inv_mass = 0)
    double inv_mass = 0.0;
    Mat3 J_body;                // inertia tensor about the centre of mass, body axes (Eq. 29-31)
    Mat3 J_body_inv;            // its inverse (zero when fixed)
    Mat3 principal_axes;        // J_body's eigenvectors (columns, body axes), for the free turn
    Vec3d principal_moments;    // its eigenvalues, ascending, kg m^2
    bool fixed = false;

    std::optional<float> restitution, friction;  // empty: the world's
    std::optional<Vec3d> color;                  // empty: the palette's (for drawing only)
    float drag_coefficient = 0.0f;
    float rolling_resistance = 0.0f;
    double rolling_radius = 0.0;  // the radius it rolls on: a sphere's or a cylinder's (0: it tips, it does not roll)
    double drag_area = 0.0;     // S of Eq. 23: the bounding sphere's cross-section, m^2

    std::array<double, rigid::kStateSize> initial{};  // the state it starts from (reset)
    std::vector<std::string> notes;  // what was decided for the user (a normalised quaternion, a hull's mass)
};

// Builds a body from its definition: loads a mesh, computes its hull (Qhull) and its mass
// properties (Table 1 for the primitives; Mirtich/Eberly volume integrals for a closed mesh,
// else its hull's), and its initial state. Throws InputError naming the body and the key.
RigidBody make_rigid_body(const RigidBodyDef& def);

// The thirteen numbers' derived quantities (Eq. 32, 36), for one body.
struct RigidMotion {
    Vec3d P, x, L;
    Quat q;
    Mat3 R;          // body to world, from q (Listing 9: computed, not renormalised)
    Mat3 J_inv;      // R J_body^-1 R^T (Eq. 32)
    Vec3d v;         // P / m
    Vec3d omega;     // J_world^-1 L (Eq. 36)
};
RigidMotion rigid_motion(const RigidBody& body, const double* state);

}  // namespace softbody

// Rigid bodies: what a body is made of (mass properties, hull, drawing mesh).
#include "physics/rigid_body.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "message_text.h"
#include "physics/error.h"
#include "physics/generated.h"
#include "physics/keys.h"
#include "physics/mass_properties.h"
#include "physics/portable_math.h"
#include "physics/shape_meshes.h"

namespace softbody {

namespace {

constexpr double kDefaultDensity = 1000.0;  // kg/m^3: water
constexpr int kCylinderHullSides = 32;      // a cylinder collides as a prism of this many sides

std::string number_text(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", x);
    return text;
}

[[noreturn]] void refuse(const RigidBodyDef& def, std::string_view key, const std::string& what) {
    throw InputError("rigid body '" + printable(def.name) + "', key '" + std::string(key) + "': " + what);
}

// Mass properties in the body's own frame (the centre of mass at the origin) for unit density,
// the hull it collides through, and the mesh it is drawn with.
struct Geometry {
    MassProperties unit;
    std::shared_ptr<const ConvexHull> hull;
    Mesh render_mesh;
    double bounding_radius = 0.0;
    bool from_hull = false;
    Vec3d file_center;  // a mesh's centre of mass in the file's coordinates (after scale)
};

ConvexHull box_hull(const Vec3d& size) {
    std::vector<Vec3d> corners;
    for (int i = 0; i < 8; ++i) {
        corners.push_back({(i & 1 ? 0.5 : -0.5) * size.x, (i & 2 ? 0.5 : -0.5) * size.y, (i & 4 ? 0.5 : -0.5) * size.z});
    }
    return convex_hull(corners);
}

ConvexHull cylinder_hull(double radius, double height) {
    std::vector<Vec3d> rim;
    for (int k = 0; k < kCylinderHullSides; ++k) {
        const double angle = 2.0 * 3.14159265358979323846 * k / kCylinderHullSides;
        for (double z : {-0.5 * height, 0.5 * height}) rim.push_back({radius * portable::cos(angle), radius * portable::sin(angle), z});
    }
    return convex_hull(rim);
}

// A box's or a cylinder's hull, shared by the bodies of one shape and size: the last few made
// on this thread are kept, so a pyramid of 2,870 equal cubes builds one hull, not 2,870 (each
// a convex hull of its corners). The same hull, so the same bits. `dims`: the shape's numbers.
std::shared_ptr<const ConvexHull> shared_hull(ShapeKind shape, const Vec3d& dims) {
    struct Made {
        ShapeKind shape;
        Vec3d dims;
        std::shared_ptr<const ConvexHull> hull;
    };
    constexpr std::size_t kKept = 8;
    thread_local std::vector<Made> made;
    for (const Made& m : made) {
        if (m.shape == shape && m.dims.x == dims.x && m.dims.y == dims.y && m.dims.z == dims.z) return m.hull;
    }
    auto hull = std::make_shared<const ConvexHull>(shape == ShapeKind::Box ? box_hull(dims) : cylinder_hull(dims.x, dims.y));
    if (made.size() == kKept) made.erase(made.begin());
    made.push_back({shape, dims, hull});
    return hull;
}

Geometry mesh_geometry(const RigidBodyDef& def) {
    if (def.mesh.empty()) refuse(def, "mesh", "a mesh body needs a mesh file");
    Mesh mesh;
    try {
        mesh = open_mesh(def.mesh);
    } catch (const InputError& e) {
        rethrow_within("rigid body '" + printable(def.name) + "': ", e);
    }
    std::vector<Vec3d> points;
    points.reserve(mesh.positions.size());
    for (const Vec3& p : mesh.positions) points.push_back(Vec3d(p) * def.scale);
    const std::vector<std::array<std::uint32_t, 3>> triangles = particle_triangles(mesh);
    Geometry g;
    ConvexHull hull;
    try {
        hull = convex_hull(points);
    } catch (const InputError& e) {
        refuse(def, "mesh", std::string(def.mesh) + " is flat: it encloses no volume (" + e.what() + ")");
    }
    if (!triangles.empty() && is_closed_oriented(triangles)) {
        g.unit = mesh_mass_properties(points, triangles);
    } else {
        // Open, non-manifold or a point cloud: the hull is the solid it stands for.
        std::vector<Vec3d> full_points = points;
        const ConvexHull full = convex_hull(full_points, full_points.size());
        g.unit = mesh_mass_properties(full.vertices, full.triangles());
        g.from_hull = true;
    }
    // A closed mesh that encloses (next to) nothing: a folded sheet, two faces back to back.
    double extent = 0.0;
    for (const Vec3d& p : hull.vertices) extent = std::max(extent, length(p - hull.vertices.front()));
    if (!(g.unit.volume > 1e-9 * extent * extent * extent)) {
        refuse(def, "mesh", std::string(def.mesh) + " is flat: it encloses no volume");
    }
    g.file_center = g.unit.center;
    // The body frame: the file's axes about the centre of mass.
    ConvexHull centred = hull;
    for (Vec3d& v : centred.vertices) v -= g.file_center;
    for (ConvexHull::Face& f : centred.faces) f.offset -= dot(f.normal, g.file_center);
    g.hull = std::make_shared<const ConvexHull>(std::move(centred));
    g.unit.center = {};
    for (Vec3& p : mesh.positions) p = to_float(Vec3d(p) * def.scale - g.file_center);
    for (const Vec3d& v : g.hull->vertices) g.bounding_radius = std::max(g.bounding_radius, length(v));
    for (const Vec3& p : mesh.positions) g.bounding_radius = std::max(g.bounding_radius, length(Vec3d(p)));
    g.render_mesh = std::move(mesh);
    return g;
}

Geometry shape_geometry(const RigidBodyDef& def) {
    const auto needs = [&](bool present, std::string_view key) {
        if (!present) refuse(def, key, "a " + std::string(to_string(def.shape)) + " needs '" + std::string(key) + "'");
    };
    const auto unused = [&](bool present, std::string_view key) {
        if (present) {
            refuse(def, key, "does not apply to a " + std::string(to_string(def.shape)));
        }
    };
    unused(def.shape != ShapeKind::Box && def.size.has_value(), "size");
    unused((def.shape == ShapeKind::Box || def.shape == ShapeKind::Mesh) && def.radius.has_value(), "radius");
    unused(def.shape != ShapeKind::Cylinder && def.height.has_value(), "height");
    unused(def.shape != ShapeKind::Mesh && !def.mesh.empty(), "mesh");
    Geometry g;
    switch (def.shape) {
        case ShapeKind::Box:
            needs(def.size.has_value(), "size");
            g.unit = box_mass_properties(*def.size);
            g.hull = shared_hull(ShapeKind::Box, *def.size);
            g.render_mesh = box_mesh(*def.size);
            g.bounding_radius = 0.5 * length(*def.size);
            break;
        case ShapeKind::Sphere:
            needs(def.radius.has_value(), "radius");
            g.unit = sphere_mass_properties(*def.radius);
            g.render_mesh = sphere_mesh(*def.radius);
            g.bounding_radius = *def.radius;
            break;
        case ShapeKind::Cylinder:
            needs(def.radius.has_value(), "radius");
            needs(def.height.has_value(), "height");
            g.unit = cylinder_mass_properties(*def.radius, *def.height);
            g.hull = shared_hull(ShapeKind::Cylinder, {*def.radius, *def.height, 0.0});
            g.render_mesh = cylinder_mesh(*def.radius, *def.height);
            g.bounding_radius = portable::hypot(*def.radius, 0.5 * *def.height);
            break;
        case ShapeKind::Mesh: return mesh_geometry(def);
    }
    return g;
}

}  // namespace

RigidBody make_rigid_body(const RigidBodyDef& def) {
    if (def.name.empty()) throw InputError("a rigid body needs a \"name\"");
    validate(def);
    if (def.mass && def.density) refuse(def, "mass", "give 'mass' or 'density', not both");
    const double q_norm = def.orientation.norm();
    if (!(q_norm > 1e-9)) refuse(def, "orientation", "a zero quaternion is no orientation (identity: 1,0,0,0)");

    const Geometry g = shape_geometry(def);
    RigidBody body;
    body.name = def.name;
    body.shape = def.shape;
    body.size = def.size.value_or(Vec3d{});
    body.radius = def.radius.value_or(0.0);
    body.height = def.height.value_or(0.0);
    body.hull = g.hull;
    body.render_mesh = g.render_mesh;
    body.bounding_radius = g.bounding_radius;
    body.volume = g.unit.volume;
    body.hull_mass_properties = g.from_hull;
    if (g.from_hull) {
        body.notes.push_back("rigid body '" + def.name + "': " + def.mesh +
                             " is not a closed surface; its convex hull's mass properties are used");
    }

    // Eq. 20, 29-31: the mass properties at unit density, scaled to the body's mass.
    body.mass = def.mass ? *def.mass : def.density.value_or(kDefaultDensity) * g.unit.volume;
    body.J_body = g.unit.inertia * (body.mass / g.unit.volume);
    body.fixed = def.fixed;
    body.inv_mass = def.fixed ? 0.0 : 1.0 / body.mass;
    body.J_body_inv = def.fixed ? Mat3{} : body.J_body.inverse();
    symmetric_eigen(body.J_body, body.principal_moments, body.principal_axes);
    body.restitution = def.restitution;
    body.friction = def.friction;
    body.color = def.color;
    body.drag_coefficient = def.drag_coefficient;
    body.rolling_resistance = def.rolling_resistance;
    // A ball rolls on its radius, a cylinder on its side; a box or a hull does not roll (it
    // tips over its edges, which its contact points already hold).
    body.rolling_radius = def.shape == ShapeKind::Sphere || def.shape == ShapeKind::Cylinder ? body.radius : 0.0;
    body.drag_area = 3.14159265358979323846 * g.bounding_radius * g.bounding_radius;

    // The initial state, Listing 10's thirteen numbers. L = J_world omega (Eq. 28, 32).
    Quat q = def.orientation;
    if (std::abs(q_norm - 1.0) > 1e-12) {
        q = q * (1.0 / q_norm);
        body.notes.push_back("rigid body '" + def.name + "': orientation normalised (its length was " +
                             number_text(q_norm) + ")");
    }
    const Vec3d x = def.position.value_or(def.shape == ShapeKind::Mesh ? g.file_center : Vec3d{});
    const Vec3d P = def.fixed ? Vec3d{} : def.velocity * body.mass;
    const Mat3 R = q.to_matrix();
    const Vec3d L = def.fixed ? Vec3d{} : (R * body.J_body * R.transposed()) * def.angular_velocity;
    double* s = body.initial.data();
    for (int k = 0; k < 3; ++k) {
        s[rigid::P + k] = P[k];
        s[rigid::X + k] = x[k];
        s[rigid::L + k] = L[k];
    }
    s[rigid::Q + 0] = q.w;
    s[rigid::Q + 1] = q.x;
    s[rigid::Q + 2] = q.y;
    s[rigid::Q + 3] = q.z;
    return body;
}

RigidMotion rigid_motion(const RigidBody& body, const double* s) {
    RigidMotion m;
    m.P = {s[rigid::P], s[rigid::P + 1], s[rigid::P + 2]};
    m.x = {s[rigid::X], s[rigid::X + 1], s[rigid::X + 2]};
    m.L = {s[rigid::L], s[rigid::L + 1], s[rigid::L + 2]};
    m.q = {s[rigid::Q], s[rigid::Q + 1], s[rigid::Q + 2], s[rigid::Q + 3]};
    m.R = m.q.to_matrix();
    // Eq. 32 with the rotation q stands for (q made unit): between renormalisations |q| drifts
    // (explicit Euler, RK4), and R from a longer q is no rotation. The body as drawn swells with
    // it (m.R, as Listing 9 converts q); its spin does not: with R's growth in J_world^-1, w
    // would grow with |q| and |q| faster with w, which blew RK4 up once a body spun fast.
    const Mat3 rotation = m.q.normalized().to_matrix();
    m.J_inv = rotation * body.J_body_inv * rotation.transposed();
    m.v = m.P * body.inv_mass;
    m.omega = m.J_inv * m.L;  // Eq. 36
    return m;
}

}  // namespace softbody

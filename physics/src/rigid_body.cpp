// Rigid bodies: their keys, and what a body is made of (mass properties, hull, drawing mesh).
#include "physics/rigid_body.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

#include "message_text.h"
#include "physics/error.h"
#include "physics/generated.h"
#include "physics/mass_properties.h"
#include "physics/portable_math.h"
#include "physics/shape_meshes.h"

namespace softbody {

namespace {

constexpr double kDefaultDensity = 1000.0;  // kg/m^3: water
constexpr int kCylinderHullSides = 32;      // a cylinder collides as a prism of this many sides

constexpr RigidKeyInfo kKeys[] = {
    {"shape", RigidKeyType::Shape, "", "", "box, sphere, cylinder (axis along the body's z) or mesh", 0, 0},
    {"size", RigidKeyType::Vec3, "m", "Table 1", "A box's full side lengths a, b, c", 0, 1e4},
    {"radius", RigidKeyType::PositiveNumber, "m", "Table 1", "A sphere's or a cylinder's radius", 0, 1e4},
    {"height", RigidKeyType::PositiveNumber, "m", "Table 1", "A cylinder's height, along the body's z", 0, 1e4},
    {"mesh", RigidKeyType::Text, "", "", "An OBJ or OFF file (shape mesh); it collides through its convex hull", 0, 0},
    {"scale", RigidKeyType::PositiveNumber, "", "", "Uniform scale from mesh units to metres", 0, 1e4},
    {"mass", RigidKeyType::PositiveNumber, "kg", "", "The body's mass (or give density)", 0, 1e9},
    {"density", RigidKeyType::PositiveNumber, "kg/m^3", "Eq. 20", "Mass per volume (default 1000, water)", 0, 1e6},
    {"position", RigidKeyType::Vec3, "m", "", "Where the centre of mass goes (default: the mesh file's, or the origin)", -1e4, 1e4},
    {"orientation", RigidKeyType::Quat, "", "Eq. 35", "Orientation quaternion w, x, y, z (normalised)", -1e6, 1e6},
    {"rotation", RigidKeyType::Vec3, "deg", "", "Orientation as turns about x, then y, then z", -360, 360},
    {"velocity", RigidKeyType::Vec3, "m/s", "", "Velocity of the centre of mass at the start, world axes", -1e3, 1e3},
    {"angular_velocity", RigidKeyType::Vec3, "rad/s", "Eq. 28", "Angular velocity at the start, world axes", -1e3, 1e3},
    {"fixed", RigidKeyType::Bool, "", "", "Infinite mass: scenery that never moves", 0, 0},
    {"restitution", RigidKeyType::Number, "", "Eq. 38", "Coefficient of restitution e at its contacts (default: the world's)", 0, 1},
    {"friction", RigidKeyType::Number, "", "", "Coulomb friction mu at its contacts (default: the world's dynamic_friction)", 0, 2},
    {"rolling_resistance", RigidKeyType::Number, "", "", "Rolling resistance C_rr: a sphere or cylinder turning on a contact is held back by a torque C_rr |F_n| r (default 0: none)", 0, 1},
    {"drag_coefficient", RigidKeyType::Number, "", "Eq. 23", "Drag coefficient C_D at its centre of mass (default 0: none)", 0, 10},
    {"color", RigidKeyType::Vec3, "", "", "The body's colour r, g, b from 0 to 1 (default: the palette's)", 0, 1},
};

std::string number_text(double x) {
    std::ostringstream out;
    out.precision(9);
    out << x;
    return out.str();
}

std::string_view trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
    return s;
}

bool parse_number(std::string_view s, double& out) {
    s = trim(s);
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    return !s.empty() && ec == std::errc() && end == s.data() + s.size() && std::isfinite(out);
}

bool parse_numbers(std::string_view text, double* out, std::size_t count) {
    std::size_t got = 0;
    for (;;) {
        const auto comma = text.find(',');
        if (got == count || !parse_number(text.substr(0, comma), out[got])) return false;
        ++got;
        if (comma == std::string_view::npos) break;
        text.remove_prefix(comma + 1);
    }
    return got == count;
}

[[noreturn]] void refuse(const RigidBodyDef& def, std::string_view key, const std::string& what) {
    throw InputError("rigid body '" + printable(def.name) + "', key '" + std::string(key) + "': " + what);
}

void check_range(const RigidBodyDef& def, const RigidKeyInfo& info, double value) {
    const bool positive = info.type == RigidKeyType::PositiveNumber ||
                          (info.type == RigidKeyType::Vec3 && info.key == "size");
    const bool low = positive ? !(value > info.min) : !(value >= info.min);
    if (!low && value <= info.max) return;
    const std::string unit = info.unit.empty() ? "" : " " + std::string(info.unit);
    refuse(def, info.key,
           "must be " + (positive ? "above " + number_text(info.min) + " and at most " : "between " + number_text(info.min) + " and ") +
               number_text(info.max) + unit + ", got " + number_text(value));
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

Geometry mesh_geometry(const RigidBodyDef& def) {
    if (def.mesh.empty()) refuse(def, "mesh", "a mesh body needs a mesh file");
    Mesh mesh;
    try {
        mesh = open_mesh(def.mesh);
    } catch (const InputError& e) {
        throw InputError("rigid body '" + printable(def.name) + "': " + e.what());
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
            g.hull = std::make_shared<const ConvexHull>(box_hull(*def.size));
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
            g.hull = std::make_shared<const ConvexHull>(cylinder_hull(*def.radius, *def.height));
            g.render_mesh = cylinder_mesh(*def.radius, *def.height);
            g.bounding_radius = portable::hypot(*def.radius, 0.5 * *def.height);
            break;
        case ShapeKind::Mesh: return mesh_geometry(def);
    }
    return g;
}

}  // namespace

std::string_view to_string(ShapeKind kind) {
    switch (kind) {
        case ShapeKind::Box: return "box";
        case ShapeKind::Sphere: return "sphere";
        case ShapeKind::Cylinder: return "cylinder";
        case ShapeKind::Mesh: return "mesh";
    }
    return "box";
}

std::span<const RigidKeyInfo> rigid_key_table() { return kKeys; }

const RigidKeyInfo* find_rigid_key(std::string_view key) {
    for (const auto& info : kKeys) {
        if (info.key == key) return &info;
    }
    return nullptr;
}

void set_rigid_key(RigidBodyDef& def, std::string_view key, std::string_view text) {
    const RigidKeyInfo* info = find_rigid_key(key);
    if (!info) {
        std::string known;
        for (const auto& k : kKeys) known += (known.empty() ? "" : ", ") + std::string(k.key);
        throw InputError("rigid body '" + printable(def.name) + "': unknown key '" + printable(key) + "' (" + known + ")");
    }
    const auto bad = [&](const char* expected) { refuse(def, key, std::string("expected ") + expected + ", got '" + printable(text) + "'"); };
    const std::string_view t = trim(text);
    switch (info->type) {
        case RigidKeyType::Number:
        case RigidKeyType::PositiveNumber: {
            double value = 0.0;
            if (!parse_number(t, value)) bad("a finite number");
            check_range(def, *info, value);
            if (key == "radius") def.radius = value;
            else if (key == "height") def.height = value;
            else if (key == "scale") def.scale = value;
            else if (key == "mass") def.mass = value;
            else if (key == "density") def.density = value;
            else if (key == "restitution") def.restitution = static_cast<float>(value);
            else if (key == "friction") def.friction = static_cast<float>(value);
            else if (key == "drag_coefficient") def.drag_coefficient = static_cast<float>(value);
            else if (key == "rolling_resistance") def.rolling_resistance = static_cast<float>(value);
            break;
        }
        case RigidKeyType::Vec3: {
            double v[3];
            if (!parse_numbers(t, v, 3)) bad("three finite numbers x,y,z");
            for (double c : v) check_range(def, *info, c);
            const Vec3d value{v[0], v[1], v[2]};
            if (key == "size") def.size = value;
            else if (key == "position") def.position = value;
            else if (key == "rotation") def.orientation = Quat::from_degrees_xyz(value);
            else if (key == "velocity") def.velocity = value;
            else if (key == "angular_velocity") def.angular_velocity = value;
            else if (key == "color") def.color = value;
            break;
        }
        case RigidKeyType::Quat: {
            double q[4];
            if (!parse_numbers(t, q, 4)) bad("four finite numbers w,x,y,z");
            for (double c : q) check_range(def, *info, c);
            const Quat value{q[0], q[1], q[2], q[3]};
            if (!(value.norm() > 1e-9)) refuse(def, key, "a zero quaternion is no orientation (identity: 1,0,0,0)");
            def.orientation = value;
            break;
        }
        case RigidKeyType::Bool:
            if (t == "true" || t == "1" || t == "on" || t == "yes") def.fixed = true;
            else if (t == "false" || t == "0" || t == "off" || t == "no") def.fixed = false;
            else bad("true or false");
            break;
        case RigidKeyType::Shape:
            if (t == "box") def.shape = ShapeKind::Box;
            else if (t == "sphere") def.shape = ShapeKind::Sphere;
            else if (t == "cylinder") def.shape = ShapeKind::Cylinder;
            else if (t == "mesh") def.shape = ShapeKind::Mesh;
            else refuse(def, key, "unknown shape '" + printable(t) + "' (box, sphere, cylinder or mesh)");
            break;
        case RigidKeyType::Text:
            if (t.empty()) bad("a file path");
            def.mesh = std::string(t);
            break;
    }
}

std::string rigid_key_text(const RigidBodyDef& def, std::string_view key) {
    const auto vec = [](const Vec3d& v) { return number_text(v.x) + "," + number_text(v.y) + "," + number_text(v.z); };
    if (key == "shape") return std::string(to_string(def.shape));
    if (key == "size") return def.size ? vec(*def.size) : "";
    if (key == "radius") return def.radius ? number_text(*def.radius) : "";
    if (key == "height") return def.height ? number_text(*def.height) : "";
    if (key == "mesh") return def.mesh;
    if (key == "scale") return number_text(def.scale);
    if (key == "mass") return def.mass ? number_text(*def.mass) : "";
    if (key == "density") return def.density ? number_text(*def.density) : "";
    if (key == "position") return def.position ? vec(*def.position) : "";
    if (key == "orientation") {
        const Quat& q = def.orientation;
        return number_text(q.w) + "," + number_text(q.x) + "," + number_text(q.y) + "," + number_text(q.z);
    }
    if (key == "rotation") return "";  // kept as the orientation
    if (key == "velocity") return vec(def.velocity);
    if (key == "angular_velocity") return vec(def.angular_velocity);
    if (key == "fixed") return def.fixed ? "true" : "false";
    if (key == "restitution") return def.restitution ? number_text(*def.restitution) : "";
    if (key == "friction") return def.friction ? number_text(*def.friction) : "";
    if (key == "drag_coefficient") return number_text(def.drag_coefficient);
    if (key == "rolling_resistance") return number_text(def.rolling_resistance);
    if (key == "color") return def.color ? vec(*def.color) : "";
    return "";
}

RigidBody make_rigid_body(const RigidBodyDef& def) {
    if (def.name.empty()) throw InputError("a rigid body needs a \"name\"");
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

#include "physics/generated.h"

#include <charconv>
#include <cstdint>
#include <utility>
#include <cmath>
#include <algorithm>
#include <random>
#include <vector>

#include "physics/error.h"
#include "physics/mesh.h"
#include "physics/portable_math.h"
#include "physics/shape_meshes.h"

namespace softbody {

namespace {

constexpr std::size_t kMaxCloud = 400000;  // the most particles a mesh may have
constexpr std::size_t kMaxPile = 5000;
constexpr std::size_t kMaxLayers = 30;  // pyramid:30 is 9,455 boxes

struct Part {
    std::string_view kind, count;
};

// "kind:N" -> {kind, N}; empty kind when it is not of that form.
Part split(std::string_view part) {
    const auto colon = part.find(':');
    if (colon == std::string_view::npos) return {};
    const std::string_view kind = part.substr(0, colon);
    if (kind != "cloud" && kind != "ball" && kind != "pile" && kind != "boxes" && kind != "pyramid" && kind != "random" &&
        kind != "bin" && kind != "stack" &&
        kind != "torus" && kind != "lattice" && kind != "cube" && kind != "sheet") {
        return {};
    }
    return {kind, part.substr(colon + 1)};
}

std::size_t count_of(std::string_view name, const Part& part, std::size_t most) {
    std::size_t n = 0;
    const char* end = part.count.data() + part.count.size();
    const auto [at, error] = std::from_chars(part.count.data(), end, n);
    if (error != std::errc() || at != end || part.count.empty()) {
        throw InputError(std::string(name) + ": '" + std::string(part.count) + "' is not a whole number (write " +
                         std::string(part.kind) + ":N)");
    }
    if (n < 1 || n > most) {
        throw InputError(std::string(name) + ": " + std::string(part.kind) + " takes 1 to " + std::to_string(most) +
                         ", not " + std::to_string(n));
    }
    return n;
}

int subdivisions_of(std::string_view name, const Part& part) {
    if (part.count.size() != 1 || part.count[0] < '0' || part.count[0] > '5') {
        throw InputError(std::string(name) + ": ball takes 0 to 5 subdivisions (10 * 4^S + 2 particles)");
    }
    return part.count[0] - '0';
}

// "RxS" of torus:RxS -> {R, S}, each 3 or more, R S at most kMaxCloud.
std::pair<int, int> rings_segments_of(std::string_view name, const Part& part) {
    const auto x = part.count.find('x');
    const auto bad = [&] {
        return InputError(std::string(name) + ": torus takes rings x segments, each 3 or more and " +
                          std::to_string(kMaxCloud) + " particles at most (write torus:RxS, e.g. torus:100x100)");
    };
    if (x == std::string_view::npos) throw bad();
    const std::string_view a = part.count.substr(0, x), b = part.count.substr(x + 1);
    std::size_t rings = 0, segments = 0;
    const auto parse = [](std::string_view text, std::size_t& value) {
        const auto [at, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        return !text.empty() && error == std::errc() && at == text.data() + text.size();
    };
    if (!parse(a, rings) || !parse(b, segments) || rings < 3 || segments < 3 || rings > kMaxCloud ||
        segments > kMaxCloud / rings) {
        throw bad();
    }
    return {int(rings), int(segments)};
}

// A closed torus about the z axis, 1.4 m across (centre line radius 0.5 m, tube radius
// 0.2 m): `rings` vertices around the centre line times `segments` around the tube, each quad
// two triangles, smooth.
Mesh torus(int rings, int segments, std::string_view name) {
    RawMesh raw;
    const float major = 0.5f, minor = 0.2f, turn = 6.28318531f;
    for (int i = 0; i < rings; ++i) {
        const float u = turn * float(i) / float(rings);
        for (int j = 0; j < segments; ++j) {
            const float v = turn * float(j) / float(segments);
            raw.positions.push_back({(major + minor * portable::cos(v)) * portable::cos(u), (major + minor * portable::cos(v)) * portable::sin(u),
                                     minor * portable::sin(v)});
        }
    }
    const auto at = [&](int i, int j) { return std::int32_t((i % rings) * segments + (j % segments)); };
    for (int i = 0; i < rings; ++i) {
        for (int j = 0; j < segments; ++j) {
            const std::int32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
            for (std::int32_t corner : {a, b, c, a, c, d}) raw.triangle_corners.push_back(Corner{corner, -1, -1});
        }
    }
    return build_mesh(raw, std::string(name));
}

// A x A x A particles on a cubic grid filling a 1 m cube centred on the origin, no faces.
Mesh lattice(std::size_t a) {
    RawMesh raw;
    const float pitch = 1.0f / float(a - 1);
    for (std::size_t i = 0; i < a; ++i) {
        for (std::size_t j = 0; j < a; ++j) {
            for (std::size_t k = 0; k < a; ++k) {
                raw.positions.push_back({float(i) * pitch - 0.5f, float(j) * pitch - 0.5f, float(k) * pitch - 0.5f});
            }
        }
    }
    return build_mesh(raw, "lattice:" + std::to_string(a));
}

// A closed cube 1 m a side centred on the origin, each face an S x S grid of squares (two
// triangles each, wound outward): 6 S^2 + 2 particles on its surface, none inside.
Mesh cube(std::size_t s, std::string_view name) {
    RawMesh raw;
    std::vector<std::int32_t> index;  // of each grid point of the (S+1)^3 block, -1 inside
    const std::size_t a = s + 1;
    index.assign(a * a * a, -1);
    const auto at = [&](std::size_t i, std::size_t j, std::size_t k) -> std::int32_t& { return index[(i * a + j) * a + k]; };
    const float pitch = 1.0f / float(s);
    for (std::size_t i = 0; i < a; ++i) {
        for (std::size_t j = 0; j < a; ++j) {
            for (std::size_t k = 0; k < a; ++k) {
                if (i != 0 && i != s && j != 0 && j != s && k != 0 && k != s) continue;
                at(i, j, k) = std::int32_t(raw.positions.size());
                raw.positions.push_back({float(i) * pitch - 0.5f, float(j) * pitch - 0.5f, float(k) * pitch - 0.5f});
            }
        }
    }
    // Each face: axis d held at 0 or S, the other two (u, v) running so that u x v points out.
    const auto quad = [&](std::int32_t p, std::int32_t q, std::int32_t r, std::int32_t t) {
        for (std::int32_t corner : {p, q, r, p, r, t}) raw.triangle_corners.push_back(Corner{corner, -1, -1});
    };
    for (int d = 0; d < 3; ++d) {
        for (std::size_t side : {std::size_t(0), s}) {
            const int u = (d + 1) % 3, v = (d + 2) % 3;
            for (std::size_t m = 0; m < s; ++m) {
                for (std::size_t n = 0; n < s; ++n) {
                    const auto point = [&](std::size_t mu, std::size_t nv) {
                        std::size_t c[3];
                        c[d] = side;
                        c[u] = mu;
                        c[v] = nv;
                        return at(c[0], c[1], c[2]);
                    };
                    // e_u x e_v = e_d: counter-clockwise seen from +d; the far side is turned over.
                    if (side == s) quad(point(m, n), point(m + 1, n), point(m + 1, n + 1), point(m, n + 1));
                    else quad(point(m, n), point(m, n + 1), point(m + 1, n + 1), point(m + 1, n));
                }
            }
        }
    }
    return build_mesh(raw, std::string(name));
}

// A flat square sheet 1 m a side in the xy plane, centred on the origin: N x N particles, two
// triangles a square, facing up. Its corners are vertices 0, N - 1, N (N - 1) and N N - 1.
Mesh sheet(std::size_t n, std::string_view name) {
    RawMesh raw;
    const float pitch = 1.0f / float(n - 1);
    for (std::size_t j = 0; j < n; ++j) {
        for (std::size_t i = 0; i < n; ++i) raw.positions.push_back({float(i) * pitch - 0.5f, float(j) * pitch - 0.5f, 0.0f});
    }
    for (std::size_t j = 0; j + 1 < n; ++j) {
        for (std::size_t i = 0; i + 1 < n; ++i) {
            const auto p = std::int32_t(j * n + i), q = p + 1, r = p + 1 + std::int32_t(n), t = p + std::int32_t(n);
            for (std::int32_t corner : {p, q, r, p, r, t}) raw.triangle_corners.push_back(Corner{corner, -1, -1});
        }
    }
    return build_mesh(raw, std::string(name));
}

constexpr std::size_t kMaxLattice = 73;  // 73^3 = 389,017 particles, within kMaxCloud

Mesh cloud(std::size_t n) {
    std::mt19937 rng(20240601u + static_cast<unsigned>(n));
    std::uniform_real_distribution<float> u(-0.5f, 0.5f);
    RawMesh raw;
    while (raw.positions.size() < n) {
        const Vec3 p{u(rng), u(rng), u(rng)};
        if (dot(p, p) <= 0.25f) raw.positions.push_back(p);
    }
    return build_mesh(raw, "cloud:" + std::to_string(n));
}

// A fixed bin for n bodies in layers of side x side at `pitch`: four walls 0.4 m high on the
// ground. Returns the side.
std::size_t bin(std::size_t n, double pitch, const char* prefix, Scene& scene, double wall_height = 0.4) {
    const std::size_t side = std::max<std::size_t>(3, std::size_t(std::ceil(std::sqrt(double(n) / 2.0))));
    const double half = 0.5 * pitch * double(side) + 0.1;
    const auto wall = [&](const char* name, Vec3d at, Vec3d size) {
        RigidBodyDef def;
        def.name = std::string(prefix) + name;
        def.shape = ShapeKind::Box;
        def.size = size;
        def.fixed = true;
        def.position = at;
        scene.rigid_bodies.push_back(def);
    };
    const double h = wall_height;
    wall("_wall_n", {0.0, half + 0.05, 0.5 * h}, {2.0 * half + 0.2, 0.1, h});
    wall("_wall_s", {0.0, -half - 0.05, 0.5 * h}, {2.0 * half + 0.2, 0.1, h});
    wall("_wall_e", {half + 0.05, 0.0, 0.5 * h}, {0.1, 2.0 * half, h});
    wall("_wall_w", {-half - 0.05, 0.0, 0.5 * h}, {0.1, 2.0 * half, h});
    return side;
}

// The rolling resistance of a pile's balls and cylinders (wood on wood, about): a ball left
// rolling or spinning on the floor of the bin stops within a second or two, as a real one does,
// and the pile comes to rest (and sleeps) instead of keeping a few balls turning for ever.
constexpr float kPileRolling = 0.01f;

// Body i of n in layers of side x side at `pitch` over the bin, 0.7 m up, 0.35 m a layer.
Vec3d layer_position(std::size_t i, std::size_t side, double pitch) {
    const std::size_t layer = i / (side * side), row = (i / side) % side, column = i % side;
    return {(double(column) - 0.5 * double(side - 1)) * pitch, (double(row) - 0.5 * double(side - 1)) * pitch,
            0.7 + 0.35 * double(layer)};
}

// N bodies in layers of a square grid over a fixed bin, each turned at random (fixed seed):
// boxes, spheres, cylinders and mesh bodies (icosahedra) in turn.
void pile(std::size_t n, Scene& scene) {
    const double pitch = 0.3;
    const std::size_t side = bin(n, pitch, "pile", scene);
    std::mt19937 rng(50u);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (std::size_t i = 0; i < n; ++i) {
        RigidBodyDef def;
        def.name = "pile" + std::to_string(i + 1);
        def.position = layer_position(i, side, pitch);
        def.orientation = Quat::from_degrees_xyz({360.0 * unit(rng), 90.0 * unit(rng), 360.0 * unit(rng)});
        def.density = 300.0 + 500.0 * unit(rng);
        switch (i % 4) {
            case 0:
                def.shape = ShapeKind::Box;
                def.size = {0.12 + 0.1 * unit(rng), 0.12 + 0.1 * unit(rng), 0.08 + 0.1 * unit(rng)};
                break;
            case 1:
                def.shape = ShapeKind::Sphere;
                def.radius = 0.06 + 0.05 * unit(rng);
                def.rolling_resistance = kPileRolling;
                break;
            case 2:
                def.shape = ShapeKind::Cylinder;
                def.radius = 0.05 + 0.04 * unit(rng);
                def.height = 0.12 + 0.1 * unit(rng);
                def.rolling_resistance = kPileRolling;
                break;
            default:
                // A mesh body: an icosahedron 0.25 m across.
                def.shape = ShapeKind::Mesh;
                def.mesh = "ball:0";
                def.scale = 0.25;
                break;
        }
        scene.rigid_bodies.push_back(def);
    }
}

// N boxes and balls by turns, dropped into a bin as pile:N is (the scene engines compare
// on): boxes 0.12 to 0.22 m a side, balls 0.12 to 0.22 m across, densities 300 to 800 kg/m^3,
// each turned at random (fixed seed).
void boxes(std::size_t n, Scene& scene) {
    const double pitch = 0.3;
    const std::size_t side = bin(n, pitch, "boxes", scene);
    std::mt19937 rng(51u);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (std::size_t i = 0; i < n; ++i) {
        RigidBodyDef def;
        def.name = (i % 2 == 0 ? "box" : "ball") + std::to_string(i / 2 + 1);
        def.position = layer_position(i, side, pitch);
        def.orientation = Quat::from_degrees_xyz({360.0 * unit(rng), 90.0 * unit(rng), 360.0 * unit(rng)});
        def.density = 300.0 + 500.0 * unit(rng);
        if (i % 2 == 0) {
            def.shape = ShapeKind::Box;
            def.size = {0.12 + 0.1 * unit(rng), 0.12 + 0.1 * unit(rng), 0.12 + 0.1 * unit(rng)};
        } else {
            def.shape = ShapeKind::Sphere;
            def.radius = 0.06 + 0.05 * unit(rng);
            def.rolling_resistance = kPileRolling;
        }
        scene.rigid_bodies.push_back(def);
    }
}

// A square pyramid of unit boxes (1 m cubes, 1,000 kg) standing on the ground: `layers` x
// `layers` at the bottom, one fewer each way on each layer up, each box on the four below it,
// 5 cm between neighbours in a layer; friction 0.6, no bounce. Placed touching, at rest.
void pyramid(std::size_t layers, Scene& scene) {
    const double pitch = 1.05;
    for (std::size_t k = 0; k < layers; ++k) {
        const std::size_t side = layers - k;
        for (std::size_t row = 0; row < side; ++row) {
            for (std::size_t column = 0; column < side; ++column) {
                RigidBodyDef def;
                def.name = "p" + std::to_string(k + 1) + "_" + std::to_string(row + 1) + "_" + std::to_string(column + 1);
                def.shape = ShapeKind::Box;
                def.size = Vec3d{1.0, 1.0, 1.0};
                def.density = 1000.0;
                def.position = Vec3d{(double(column) - 0.5 * double(side - 1)) * pitch,
                                     (double(row) - 0.5 * double(side - 1)) * pitch, 0.5 + double(k)};
                def.friction = 0.6f;
                def.restitution = 0.0f;
                scene.rigid_bodies.push_back(def);
            }
        }
    }
}

// Scenes the solver was not tuned on, as another engine's comparison built them. bin:N: N boxes
// 0.2 to 0.4 m a side and balls 0.1 to 0.2 m in radius by turns, 1,000 kg/m^3, no rolling
// resistance, friction 0.5 and restitution 0.2 everywhere (the ground too), dropped into four
// fixed walls 1 m high.
void bin_of_boxes_and_balls(std::size_t n, Scene& scene) {
    const double pitch = 0.5;
    const std::size_t side = bin(n, pitch, "bin", scene, 1.0);
    scene.settings.static_friction = scene.settings.dynamic_friction = 0.5f;
    scene.settings.restitution = 0.2f;
    std::mt19937 rng(52u);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (std::size_t i = 0; i < n; ++i) {
        RigidBodyDef def;
        def.name = (i % 2 == 0 ? "box" : "ball") + std::to_string(i / 2 + 1);
        def.position = layer_position(i, side, pitch) + Vec3d{0.0, 0.0, 0.5 * double(i / (side * side))};
        def.orientation = Quat::from_degrees_xyz({360.0 * unit(rng), 90.0 * unit(rng), 360.0 * unit(rng)});
        def.density = 1000.0;
        def.friction = 0.5f;
        def.restitution = 0.2f;
        if (i % 2 == 0) {
            def.shape = ShapeKind::Box;
            def.size = {0.2 + 0.2 * unit(rng), 0.2 + 0.2 * unit(rng), 0.2 + 0.2 * unit(rng)};
        } else {
            def.shape = ShapeKind::Sphere;
            def.radius = 0.1 + 0.1 * unit(rng);
        }
        scene.rigid_bodies.push_back(def);
    }
}

// stack:L: a square pyramid of 1 m cubes of 1 kg, `layers` x `layers` at the bottom, each
// exactly on the four below it and touching its neighbours in the layer (no gap), friction 0.5.
void stack(std::size_t layers, Scene& scene) {
    for (std::size_t k = 0; k < layers; ++k) {
        const std::size_t side = layers - k;
        for (std::size_t row = 0; row < side; ++row) {
            for (std::size_t column = 0; column < side; ++column) {
                RigidBodyDef def;
                def.name = "s" + std::to_string(k + 1) + "_" + std::to_string(row + 1) + "_" + std::to_string(column + 1);
                def.shape = ShapeKind::Box;
                def.size = Vec3d{1.0, 1.0, 1.0};
                def.mass = 1.0;
                def.position = Vec3d{double(column) - 0.5 * double(side - 1), double(row) - 0.5 * double(side - 1), 0.5 + double(k)};
                def.friction = 0.5f;
                def.restitution = 0.0f;
                scene.rigid_bodies.push_back(def);
            }
        }
    }
}

// A scene nobody tuned, from its seed: two to eight boxes, balls and cylinders 5 cm to 5 m
// across (log-uniform), 100 to 20,000 kg/m^3, thrown at up to 20 m/s and spun at up to
// 20 rad/s, restitution 0 to 1 (a quarter of them exactly 1), friction 0 to 2, and none to
// three fixed bodies in the air as obstacles, over the ground; no two overlap at the start
// (their bounding spheres apart). The same seed gives the same scene on every machine: the
// draws are integers from the generator, turned into numbers here, not by the standard
// library's distributions (whose algorithms it leaves to each implementation).
void random_scene(std::uint64_t seed, Scene& scene) {
    std::mt19937_64 rng(0x5eedULL * 1000003ULL + seed);
    const auto unit = [&] { return double(rng() >> 11) * 0x1.0p-53; };  // [0, 1)
    const auto between = [&](double lo, double hi) { return lo + (hi - lo) * unit(); };
    // lo (hi / lo)^u, the power by square roots of square roots for u's first 30 bits (no pow:
    // the same bits everywhere, portable_math.h).
    const auto log_between = [&](double lo, double hi) {
        double u = unit(), root = hi / lo, value = lo;
        for (int bit = 0; bit < 30; ++bit) {
            root = std::sqrt(root);
            u *= 2.0;
            if (u >= 1.0) {
                value *= root;
                u -= 1.0;
            }
        }
        return value;
    };
    const auto direction = [&] {
        for (;;) {
            const Vec3d d{between(-1, 1), between(-1, 1), between(-1, 1)};
            const double l = length(d);
            if (l > 0.1 && l <= 1.0) return d / l;
        }
    };
    const std::size_t moving = 2 + std::size_t(rng() % 7), fixed = std::size_t(rng() % 4);
    std::vector<std::pair<Vec3d, double>> placed;  // centres and bounding radii
    for (std::size_t i = 0; i < moving + fixed; ++i) {
        RigidBodyDef def;
        const bool is_fixed = i >= moving;
        def.name = (is_fixed ? "wall" : "b") + std::to_string(is_fixed ? i - moving + 1 : i + 1);
        double radius = 0.0;  // of the bounding sphere
        switch (rng() % 3) {
            case 0: {
                def.shape = ShapeKind::Box;
                const Vec3d size{log_between(0.05, 5.0), log_between(0.05, 5.0), log_between(0.05, 5.0)};
                def.size = size;
                radius = 0.5 * length(size);
                break;
            }
            case 1:
                def.shape = ShapeKind::Sphere;
                def.radius = 0.5 * log_between(0.05, 5.0);
                radius = *def.radius;
                break;
            default:
                def.shape = ShapeKind::Cylinder;
                def.radius = 0.5 * log_between(0.05, 5.0);
                def.height = log_between(0.05, 5.0);
                radius = portable::hypot(*def.radius, 0.5 * *def.height);
                break;
        }
        def.density = log_between(100.0, 20000.0);
        def.orientation = Quat::from_axis_angle(direction(), between(0.0, 6.283185307179586));
        def.restitution = float(rng() % 4 == 0 ? 1.0 : unit());
        def.friction = float(between(0.0, 2.0));
        def.fixed = is_fixed;
        if (!is_fixed) {
            def.velocity = direction() * between(0.0, 20.0);
            def.angular_velocity = direction() * between(0.0, 20.0);
        }
        // A place where it overlaps nothing placed so far, above the ground (the fixed ones in
        // the air); after many tries, higher up.
        for (int attempt = 0;; ++attempt) {
            const double spread = 6.0 + 0.1 * attempt;
            const Vec3d at{between(-spread, spread), between(-spread, spread),
                           radius + (is_fixed ? between(1.0, 6.0) : between(0.0, 8.0)) + 0.1 * attempt};
            const bool clear = std::all_of(placed.begin(), placed.end(), [&](const auto& other) {
                return length(at - other.first) > radius + other.second;
            });
            if (clear) {
                def.position = at;
                placed.emplace_back(at, radius);
                break;
            }
        }
        scene.rigid_bodies.push_back(def);
    }
}

}  // namespace

bool is_generated(std::string_view name) {
    if (name.empty()) return false;
    std::size_t start = 0;
    while (start <= name.size()) {
        const std::size_t plus = name.find('+', start);
        const std::string_view part = name.substr(start, plus == std::string_view::npos ? std::string_view::npos : plus - start);
        if (split(part).kind.empty()) return false;
        if (plus == std::string_view::npos) return true;
        start = plus + 1;
    }
    return false;
}

Mesh generated_mesh(std::string_view name) {
    const Part part = split(name);
    if (part.kind == "cloud") return cloud(count_of(name, part, kMaxCloud));
    if (part.kind == "ball") {
        Mesh mesh = sphere_mesh(0.5, subdivisions_of(name, part));
        mesh.source = std::string(name);
        return mesh;
    }
    if (part.kind == "torus") {
        const auto [rings, segments] = rings_segments_of(name, part);
        return torus(rings, segments, name);
    }
    if (part.kind == "lattice") {
        const std::size_t a = count_of(name, part, kMaxLattice);
        if (a < 2) throw InputError(std::string(name) + ": lattice takes 2 to " + std::to_string(kMaxLattice) + ", not 1");
        return lattice(a);
    }
    if (part.kind == "cube") return cube(count_of(name, part, 64), name);
    if (part.kind == "sheet") {
        const std::size_t n = count_of(name, part, 400);
        if (n < 2) throw InputError(std::string(name) + ": sheet takes 2 to 400, not 1");
        return sheet(n, name);
    }
    throw InputError(std::string(name) +
                     ": not a mesh (a mesh is cloud:N, ball:S, torus:RxS, lattice:A, cube:S or sheet:N; pile:N, boxes:N, pyramid:L, bin:N, stack:L and random:SEED are scenes: use --scene)");
}

Mesh open_mesh(const std::string& name) { return is_generated(name) ? generated_mesh(name) : load_mesh(name); }

Scene generated_scene(std::string_view name) {
    Scene scene;
    std::size_t start = 0;
    bool soft = false;
    for (;;) {
        const std::size_t plus = name.find('+', start);
        const std::string_view text = name.substr(start, plus == std::string_view::npos ? std::string_view::npos : plus - start);
        const Part part = split(text);
        if (part.kind == "cloud" || part.kind == "ball" || part.kind == "torus" || part.kind == "lattice" ||
            part.kind == "cube" || part.kind == "sheet") {
            if (soft) throw InputError(std::string(name) + ": one cloud or ball at most (it is the scene's soft body)");
            soft = true;
            generated_mesh(text);  // checks the count; the World makes the mesh again from its name
            SoftBodyDef body;
            body.name = "body";
            body.mesh = std::string(text);
            // Every particle the name asks for is simulated (no particle budget): cloud:5000 in
            // the app is the body `softbody bench` times at N = 5,000.
            body.max_particles = 0;
            scene.soft_bodies.insert(scene.soft_bodies.begin(), std::move(body));
            scene.settings.auto_substeps = true;
        } else if (part.kind == "pile") {
            pile(count_of(name, part, kMaxPile), scene);
        } else if (part.kind == "boxes") {
            boxes(count_of(name, part, kMaxPile), scene);
        } else if (part.kind == "pyramid") {
            pyramid(count_of(name, part, kMaxLayers), scene);
        } else if (part.kind == "bin") {
            bin_of_boxes_and_balls(count_of(name, part, kMaxPile), scene);
        } else if (part.kind == "stack") {
            stack(count_of(name, part, kMaxLayers), scene);
        } else if (part.kind == "random") {
            random_scene(count_of(name, part, std::size_t(1) << 40), scene);
        } else {
            throw InputError(std::string(name) + ": '" + std::string(text) +
                             "' is not cloud:N, ball:S, torus:RxS, lattice:A, cube:S, sheet:N, pile:N, boxes:N, pyramid:L, bin:N, stack:L or random:SEED");
        }
        if (plus == std::string_view::npos) break;
        start = plus + 1;
    }
    return scene;
}

}  // namespace softbody

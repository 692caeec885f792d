// softbody_peer_bullet: the peer of `softbody bench`'s "rigid bodies at scale". It builds a
// scene of rigid bodies (a generated name such as boxes:1000 or pyramid:10, or a scene file)
// through the project's own scene code, so its shapes, masses, inertia tensors, poses,
// velocities, friction and restitution are the very ones softbody simulates, then builds the
// same world in Bullet and times it: a 0.02 s tick (the scene's dt), wall clock of the step calls
// only, and the soundness figures of app/soundness.h after the run. One JSON object per run on
// stdout. Built only where CMake finds Bullet (Debian's libbullet-dev); the project needs none of
// it.
//
//   softbody_peer_bullet --scene boxes:1000 [--config iterations,substeps,sleeping] [--seconds 10]
//
// The three configurations of the table:
//   iterations  one step a tick, the default solver (10 iterations), no sleeping
//   substeps    stepSimulation(dt, 2, dt / 2): two steps a tick, no sleeping
//   sleeping    one step a tick, Bullet's default deactivation (bodies at rest sleep)
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "physics/error.h"
#include "physics/rigid_body.h"
#include "physics/scene_io.h"
#include "physics/world.h"
#include "soundness.h"

namespace {

using namespace softbody;
using namespace softbody::app;

constexpr const char* kUsage =
    "usage: softbody_peer_bullet --scene NAME [--config iterations,substeps,sleeping] [--seconds S]\n"
    "  --scene    a scene of rigid bodies only: a generated name (boxes:1000, pyramid:10, pile:100) or a file\n"
    "  --config   which of the three runs (default all, each its own world): iterations (one step a tick,\n"
    "             10 solver iterations, no sleeping), substeps (2 steps a tick, no sleeping), sleeping (one\n"
    "             step a tick, Bullet's default deactivation)\n"
    "  --seconds  simulated seconds per run (default 10)";

struct BadInput : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The ground is told apart from the bodies by its user index, for the material callbacks.
constexpr int kGround = 1;

// Materials as softbody mixes them (physics/README.md, "Materials"): between two
// bodies restitution is the larger and friction sqrt(mu_1 mu_2); at the ground the body's own.
// Bullet's own combiners multiply both, so its globals are pointed here instead.
btScalar combined_restitution(const btCollisionObject* a, const btCollisionObject* b) {
    if (a->getUserIndex() == kGround) return b->getRestitution();
    if (b->getUserIndex() == kGround) return a->getRestitution();
    return std::max(a->getRestitution(), b->getRestitution());
}
btScalar combined_friction(const btCollisionObject* a, const btCollisionObject* b) {
    if (a->getUserIndex() == kGround) return b->getFriction();
    if (b->getUserIndex() == kGround) return a->getFriction();
    return std::sqrt(a->getFriction() * b->getFriction());
}

// Rolling and spinning friction as softbody mixes rolling resistance: the larger of the two.
btScalar combined_rolling(const btCollisionObject* a, const btCollisionObject* b) {
    return std::max(a->getRollingFriction(), b->getRollingFriction());
}
btScalar combined_spinning(const btCollisionObject* a, const btCollisionObject* b) {
    return std::max(a->getSpinningFriction(), b->getSpinningFriction());
}

enum class Config { Iterations, Substeps, Sleeping };
const char* label(Config c) {
    switch (c) {
        case Config::Iterations: return "10 iterations";
        case Config::Substeps: return "2 substeps";
        default: return "sleeping on";
    }
}
const char* key(Config c) {
    switch (c) {
        case Config::Iterations: return "iterations";
        case Config::Substeps: return "substeps";
        default: return "sleeping";
    }
}

btVector3 bt(const Vec3d& v) { return {btScalar(v.x), btScalar(v.y), btScalar(v.z)}; }
Vec3d ours(const btVector3& v) { return {double(v.x()), double(v.y()), double(v.z())}; }

// A hull's margin lies outside its points in Bullet (a box's and a cylinder's lie inside their
// extents), so the default 4 cm would swell a 25 cm icosahedron by a third: 5 mm here.
constexpr btScalar kHullMargin = 0.005f;

std::unique_ptr<btCollisionShape> make_shape(const RigidBody& body) {
    switch (body.shape) {
        case ShapeKind::Box: return std::make_unique<btBoxShape>(bt(body.size * 0.5));
        case ShapeKind::Sphere: return std::make_unique<btSphereShape>(btScalar(body.radius));
        case ShapeKind::Cylinder:  // our cylinders' axis is the body's z
            return std::make_unique<btCylinderShapeZ>(
                btVector3(btScalar(body.radius), btScalar(body.radius), btScalar(0.5 * body.height)));
        case ShapeKind::Mesh: {
            auto hull = std::make_unique<btConvexHullShape>();
            for (const Vec3d& p : body.hull->vertices) hull->addPoint(bt(p), false);
            hull->recalcLocalAabb();
            hull->setMargin(kHullMargin);
            return hull;
        }
    }
    throw BadInput("body '" + body.name + "': unknown shape");
}

struct Run {
    double ms_per_tick = 0.0;
    int ticks = 0, steps = 0, sleeping = 0;  // steps: Bullet's internal ones; sleeping: dynamic bodies
    bool finite = true;
    Soundness figures;
};

void count_step(btDynamicsWorld* world, btScalar) { ++*static_cast<int*>(world->getWorldUserInfo()); }

Run run(const Scene& scene, const std::vector<RigidBody>& made, Config config, double seconds, bool pyramid) {
    const WorldSettings& p = scene.settings;
    btDefaultCollisionConfiguration configuration;
    btCollisionDispatcher dispatcher(&configuration);
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
    world.setGravity(btVector3(p.gravity.x, p.gravity.y, p.gravity.z));
    world.getSolverInfo().m_numIterations = 10;  // Bullet's default, said out loud
    Run r;
    world.setInternalTickCallback(count_step, &r.steps);

    std::vector<std::unique_ptr<btCollisionShape>> shapes;
    std::vector<std::unique_ptr<btRigidBody>> bodies;
    std::unique_ptr<btRigidBody> ground;
    if (p.ground) {
        shapes.push_back(std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), btScalar(p.ground_height)));
        ground = std::make_unique<btRigidBody>(btRigidBody::btRigidBodyConstructionInfo(0, nullptr, shapes.back().get()));
        ground->setUserIndex(kGround);
        world.addRigidBody(ground.get());
    }
    for (const RigidBody& body : made) {
        shapes.push_back(make_shape(body));
        const RigidMotion m = rigid_motion(body, body.initial.data());
        btTransform start;
        start.setOrigin(bt(m.x));
        start.setRotation(btQuaternion(btScalar(m.q.x), btScalar(m.q.y), btScalar(m.q.z), btScalar(m.q.w)));
        const double mass = body.fixed ? 0.0 : body.mass;
        const btVector3 inertia = body.fixed ? btVector3(0, 0, 0)
                                             : btVector3(btScalar(body.J_body.m[0][0]), btScalar(body.J_body.m[1][1]),
                                                         btScalar(body.J_body.m[2][2]));
        btRigidBody::btRigidBodyConstructionInfo info(btScalar(mass), nullptr, shapes.back().get(), inertia);
        info.m_startWorldTransform = start;
        info.m_restitution = body.restitution.value_or(p.restitution);
        info.m_friction = body.friction.value_or(p.dynamic_friction);
        // Rolling resistance: softbody's torque limit C_rr r |F_n| is Bullet's rolling (and
        // spinning) friction, a length times the normal impulse, at C_rr r.
        info.m_rollingFriction = btScalar(double(body.rolling_resistance) * body.rolling_radius);
        info.m_spinningFriction = info.m_rollingFriction;
        auto rb = std::make_unique<btRigidBody>(info);
        if (!body.fixed) {
            rb->setLinearVelocity(bt(m.v));
            rb->setAngularVelocity(bt(m.omega));
            if (config != Config::Sleeping) rb->setActivationState(DISABLE_DEACTIVATION);
        }
        world.addRigidBody(rb.get());
        bodies.push_back(std::move(rb));
    }

    // Whole ticks of dt; the clock runs over the step calls only.
    const btScalar dt = p.dt;
    r.ticks = std::max(1, int(std::lround(seconds / double(p.dt))));
    std::chrono::steady_clock::duration spent{};
    for (int tick = 0; tick < r.ticks; ++tick) {
        const auto t0 = std::chrono::steady_clock::now();
        if (config == Config::Substeps) world.stepSimulation(dt, 2, dt / 2);
        else world.stepSimulation(dt, 1, dt);
        spent += std::chrono::steady_clock::now() - t0;
    }
    r.ms_per_tick = std::chrono::duration<double, std::milli>(spent).count() / r.ticks;

    std::vector<BodyNow> now;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const btRigidBody& rb = *bodies[i];
        const btTransform& t = rb.getCenterOfMassTransform();
        const btMatrix3x3& basis = t.getBasis();
        BodyNow b;
        b.x = ours(t.getOrigin());
        for (int row = 0; row < 3; ++row)
            for (int column = 0; column < 3; ++column) b.R.m[row][column] = double(basis[row][column]);
        b.v = ours(rb.getLinearVelocity());
        b.omega = ours(rb.getAngularVelocity());
        // Bullet's own shape's support point straight down (its margin included).
        const btConvexShape* shape = static_cast<const btConvexShape*>(rb.getCollisionShape());
        const btVector3 down = basis.transpose() * btVector3(0, 0, -1);
        b.lowest_z = double((t * shape->localGetSupportingVertex(down)).z());
        if (!is_finite(b.x) || !is_finite(b.v) || !is_finite(b.omega)) r.finite = false;
        if (!made[i].fixed && rb.getActivationState() == ISLAND_SLEEPING) ++r.sleeping;
        now.push_back(b);
    }
    r.figures = soundness(made, now, p.ground ? std::optional<double>(p.ground_height) : std::nullopt, pyramid);

    for (auto& rb : bodies) world.removeRigidBody(rb.get());
    if (ground) world.removeRigidBody(ground.get());
    return r;
}

std::vector<Config> parse_configs(std::string_view text) {
    std::vector<Config> configs;
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t comma = std::min(text.find(',', start), text.size());
        const std::string_view name = text.substr(start, comma - start);
        if (name == "all") configs.insert(configs.end(), {Config::Iterations, Config::Substeps, Config::Sleeping});
        else if (name == "iterations") configs.push_back(Config::Iterations);
        else if (name == "substeps") configs.push_back(Config::Substeps);
        else if (name == "sleeping") configs.push_back(Config::Sleeping);
        else throw BadInput("--config: expected iterations, substeps, sleeping or all, got '" + std::string(name) + "'");
        start = comma + 1;
    }
    return configs;
}

int peer(int argc, char** argv) {
    std::string scene_name;
    std::vector<Config> configs{Config::Iterations, Config::Substeps, Config::Sleeping};
    double seconds = 10.0;
    for (int i = 1; i < argc; ++i) {
        const std::string_view option = argv[i];
        const auto value = [&]() -> std::string_view {
            if (i + 1 >= argc) throw BadInput(std::string(option) + " needs a value");
            return argv[++i];
        };
        if (option == "--scene") scene_name = value();
        else if (option == "--config") configs = parse_configs(value());
        else if (option == "--seconds") {
            const std::string text(value());
            char* end = nullptr;
            seconds = std::strtod(text.c_str(), &end);
            if (text.empty() || *end != '\0' || !(seconds > 0.0 && seconds <= 3600.0)) {
                throw BadInput("--seconds: expected a number above 0, at most 3600, got '" + text + "'");
            }
        } else if (option == "--help" || option == "-h") {
            std::cout << kUsage << "\n";
            return 0;
        } else {
            throw BadInput("unknown option '" + std::string(option) + "' (--help lists them)");
        }
    }
    if (scene_name.empty()) throw BadInput("--scene NAME is required (--help lists the options)");

    const Scene scene = load_scene(scene_name);
    if (!scene.soft_bodies.empty() || !scene.springs.empty()) {
        throw BadInput(scene_name + ": the peer builds rigid bodies only, and this scene has a soft body or springs");
    }
    std::vector<RigidBody> made;
    for (const RigidBodyDef& body : scene.rigid_bodies) made.push_back(make_rigid_body(body));
    for (const RigidBody& body : made) {
        // Bullet takes the inertia tensor's diagonal in the body's own axes; ours is diagonal
        // there for boxes, spheres and cylinders, and for symmetric meshes.
        const Mat3& J = body.J_body;
        const double off = std::abs(J.m[0][1]) + std::abs(J.m[0][2]) + std::abs(J.m[1][2]);
        if (!body.fixed && off > 1e-6 * J.trace()) {
            throw BadInput("body '" + body.name + "': its inertia tensor is not diagonal in its own axes; the peer takes "
                           "boxes, spheres, cylinders and symmetric meshes");
        }
    }

    gCalculateCombinedRestitutionCallback = combined_restitution;
    gCalculateCombinedFrictionCallback = combined_friction;
    gCalculateCombinedRollingFrictionCallback = combined_rolling;
    gCalculateCombinedSpinningFrictionCallback = combined_spinning;
    for (Config config : configs) {
        const Run r = run(scene, made, config, seconds, is_pyramid(scene_name));
        const Soundness& s = r.figures;
        nlohmann::ordered_json j = {
            {"engine", "bullet"},
            {"version", btGetVersion()},
            {"scene", scene_name},
            {"config", key(config)},
            {"label", label(config)},
            {"bodies", s.bodies},
            {"seconds", std::round(r.ticks * double(scene.settings.dt) * 1e6) / 1e6},
            {"ticks", r.ticks},
            {"steps", r.steps},
            {"ms_per_tick", r.ms_per_tick},
            {"penetration_m", s.penetration_m ? nlohmann::ordered_json(*s.penetration_m) : nlohmann::ordered_json()},
            {"moving", s.moving},
            {"kinetic_J", s.kinetic_J},
            {"top_moved_m", s.top_moved_m ? nlohmann::ordered_json(*s.top_moved_m) : nlohmann::ordered_json()},
            {"sleeping", r.sleeping},
            {"status", r.finite ? "ok" : "diverged"},
        };
        std::cout << j.dump() << std::endl;
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return peer(argc, argv);
    } catch (const BadInput& e) {
        std::cerr << "softbody_peer_bullet: " << e.what() << "\n";
        return 2;
    } catch (const softbody::InputError& e) {
        std::cerr << "softbody_peer_bullet: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "softbody_peer_bullet: " << e.what() << "\n";
        return 4;
    }
}

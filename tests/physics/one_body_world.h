// A world of one soft body, as tests write it: the world's keys and the body's in one struct
// (the old flat scene form), and the mesh. Shared by the physics, kernel and render tests.
#pragma once

#include <memory>

#include "physics/defs.h"
#include "physics/mesh.h"
#include "physics/scene_io.h"
#include "physics/world.h"

namespace softbody::test {

// The world's keys and one soft body's (named "body") in one struct, as the old flat scene form
// held them: a test sets what it examines on one object.
struct FlatKeys : WorldSettings, SoftBodyDef {
    FlatKeys() { name = "body"; }
};

// A world of that one soft body, made of `mesh`.
inline WorldDef one_body(const FlatKeys& keys, const Mesh& mesh) {
    WorldDef def;
    def.settings = keys;
    SoftBodyDef body = keys;
    body.geometry = std::make_shared<const Mesh>(mesh);
    def.soft_bodies.push_back(std::move(body));
    return def;
}

// The world's keys and its first soft body's, and back: what set_params did before the keys
// were split into the world's settings and each body's definition.
inline FlatKeys flat_keys(const World& world) {
    FlatKeys keys;
    static_cast<WorldSettings&>(keys) = world.settings();
    if (world.soft_body_count() > 0) static_cast<SoftBodyDef&>(keys) = world.soft_body(0).def;
    return keys;
}
inline void set_flat(World& world, const FlatKeys& keys) {
    world.set_settings(keys);
    if (world.soft_body_count() > 0) {
        SoftBodyDef body = keys;
        body.name = world.soft_body(0).name();
        body.geometry = world.soft_body(0).def.geometry;
        world.set_def(world.soft_body_id(0), body);
    }
}
// A rigid body's restitution and friction (empty: the world's), from the next contact on.
inline void set_material(World& world, std::size_t body, std::optional<float> restitution, std::optional<float> friction) {
    RigidBodyDef def = world.def(world.rigid_body_id(body));
    def.restitution = restitution;
    def.friction = friction;
    world.set_def(world.rigid_body_id(body), def);
}

// A scene of those keys: the world's, and with a mesh the soft body "body" (as the flat form).
inline Scene scene_of(const FlatKeys& keys) {
    Scene scene;
    scene.settings = keys;
    if (!keys.mesh.empty()) scene.soft_bodies.push_back(keys);
    return scene;
}

// A World of one soft body, made as the tests write it: its keys and its mesh.
struct OneBodyWorld : World {
    OneBodyWorld(const FlatKeys& keys, const Mesh& mesh, WorldOptions options = {}) : World(one_body(keys, mesh), options) {}
};

}  // namespace softbody::test

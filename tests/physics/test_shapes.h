// Collision shapes made as a scene makes them (RigidBodyDef -> make_rigid_body ->
// collision_shape), and turns by axis and angle: shared by the collision tests and benchmarks.
#pragma once

#include <numbers>

#include "physics/collide.h"
#include "physics/quat.h"
#include "physics/rigid_body.h"

namespace softbody::test {

inline CollisionShape box(const Vec3d& size) {
    RigidBodyDef def;
    def.name = "box";
    def.shape = ShapeKind::Box;
    def.size = size;
    return collision_shape(make_rigid_body(def));
}

inline CollisionShape ball(double radius) {
    RigidBodyDef def;
    def.name = "ball";
    def.shape = ShapeKind::Sphere;
    def.radius = radius;
    return collision_shape(make_rigid_body(def));
}

inline CollisionShape cylinder(double radius, double height) {
    RigidBodyDef def;
    def.name = "cylinder";
    def.shape = ShapeKind::Cylinder;
    def.radius = radius;
    def.height = height;
    return collision_shape(make_rigid_body(def));
}

inline Quat turn(const Vec3d& axis, double degrees) {
    return Quat::from_axis_angle(normalize(axis), degrees * std::numbers::pi / 180.0);
}

}  // namespace softbody::test

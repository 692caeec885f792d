// How sound a rigid scene is after a run, in figures two engines can share: how deep the
// deepest body is in the ground, how many bodies still move, the kinetic energy left, and how
// far the top of a pyramid has gone. `softbody bench` computes them from the World and the peer
// (app/peer_bullet.cpp) from its own engine's state, each with its own collision shapes'
// lowest points, so the figures of both columns mean the same thing.
#pragma once

#include <optional>
#include <span>
#include <string_view>

#include "physics/mat3.h"
#include "physics/rigid_body.h"
#include "physics/vec3.h"

namespace softbody::app {

// Faster than this at any point of it, a body still moves: 1 cm/s, the "at rest".
inline constexpr double kMovingSpeed = 0.01;

// One body as an engine has it after the run.
struct BodyNow {
    Vec3d x;          // centre of mass, m
    Mat3 R;           // body to world
    Vec3d v, omega;   // m/s, rad/s (world axes)
    double lowest_z;  // lowest point of its collision shape (the shape's support point straight down), m
    bool asleep = false;  // the engine has put it to sleep (softbody: the `sleeping` key)
};

struct Soundness {
    int bodies = 0;                       // dynamic ones (the bin's walls are not counted)
    std::optional<double> penetration_m;  // deepest lowest point below the ground (0: none); empty without a ground
    int moving = 0;                       // bodies whose fastest point, |v| + |w| r, exceeds kMovingSpeed
    int sleeping = 0;                     // bodies the engine has put to sleep
    double kinetic_J = 0.0;               // sum 1/2 m |v|^2 + 1/2 w . J_world w
    std::optional<double> top_moved_m;    // a pyramid's: how far the highest box at the start has gone
};

// `defs` are the bodies as made (their initial state says where the top box started); `now` is
// each one's state after the run, in the same order. `pyramid`: report the top box.
Soundness soundness(std::span<const RigidBody> defs, std::span<const BodyNow> now, std::optional<double> ground_height,
                    bool pyramid);

// True for a generated pyramid scene ("pyramid:10", "stack:10").
inline bool is_pyramid(std::string_view scene) { return scene.rfind("pyramid:", 0) == 0 || scene.rfind("stack:", 0) == 0; }

// Lowest point of one of our collision shapes (a sphere exactly, else its hull's vertices).
double lowest_point(const RigidBody& body, const Vec3d& x, const Mat3& R);

}  // namespace softbody::app

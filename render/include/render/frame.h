// What the renderer is asked to draw: a read-only view of the body's state, the camera, and
// the switches. Plain data: the renderer never changes the simulation, and the simulation
// knows nothing of GL.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "physics/mesh.h"
#include "render/camera.h"

namespace softbody::render {

// N vectors as three arrays, one per axis: how the physics stores positions and velocities.
struct Vec3Span {
    const float* x = nullptr;
    const float* y = nullptr;
    const float* z = nullptr;
    std::size_t size = 0;

    bool empty() const { return size == 0; }
    glm::vec3 operator[](std::size_t i) const { return {x[i], y[i], z[i]}; }
};

// The body as it is this frame. Only mesh and positions are required.
struct BodyView {
    const Mesh* mesh = nullptr;    // topology: render vertices, normal slots, triangles
    Vec3Span positions;            // particles at the latest tick
    Vec3Span previous_positions;   // particles one tick earlier; empty: no interpolation
    float alpha = 1.0f;            // draws lerp(previous_positions, positions, alpha)
    Vec3Span velocities;           // for the velocity arrows
    Vec3Span forces;               // net force on each particle, N: for the force arrows
    Vec3Span rest_positions;       // for the springs' strain colours
    std::span<const float> inverse_masses;  // 0 marks a pinned particle
};

enum class BodyStyle { Solid, Ghost, Wireframe, Hidden };

// Each overlay on its own switch.
struct Overlays {
    bool particles = false;       // every particle as a small sphere
    bool springs = false;         // springs coloured by strain (a sample when there are many)
    bool pins = true;             // pinned particles marked
    bool center_of_mass = false;  // marker, with a line down to the ground
    bool velocities = false;      // the centre of mass's velocity, and a sample of the particles'
    bool forces = false;          // a sample of the particles' net forces, scaled to the body
    bool normals = false;         // a sample of the recomputed surface normals
    // The mouse's pull: a line from the grabbed particle to the point it is pulled toward.
    bool grab = false;
    std::uint32_t grab_particle = 0;
    glm::vec3 grab_target{0.0f};
};

struct Appearance {
    glm::vec3 body_color{0.93f, 0.45f, 0.24f};  // sRGB, 0..1
    BodyStyle body = BodyStyle::Solid;
    bool pattern = true;              // soft checks fixed in the body's material: rolling shows
    bool ground = true;
    float ground_height = 0.0f;       // m: the plane z = ground_height
    bool shadows = true;
    int samples = 4;                  // multisample anti-aliasing; 1 turns it off
    std::size_t max_springs = 48;     // over twice this many pairs: surface springs + this many more
    std::size_t max_arrows = 40;      // particles' velocity arrows (every k-th particle beyond)
    float velocity_scale = 0.2f;      // arrow length per speed, m per (m/s)
};

// Deliberate faults, for proving that the screenshot tests notice them. Off in normal use.
struct DebugOptions {
    glm::vec3 body_offset{0.0f};  // draws the body (and all that follows it) shifted, m
    bool flip_normals = false;    // inverts the recomputed normals
};

struct Frame {
    BodyView body;
    Camera camera;
    Overlays overlays;
    Appearance appearance;
    DebugOptions debug;
};

}  // namespace softbody::render

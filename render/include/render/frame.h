// What the renderer is asked to draw: read-only views of the bodies' state, the camera, and
// the switches. Plain data: the renderer never changes the simulation, and the simulation
// knows nothing of GL.
//
// Soft bodies are streamed: their particles move every vertex, so every frame recomputes the
// surface and uploads it. Rigid bodies are a fixed vertex buffer each (uploaded once) drawn
// with a model matrix from their position and orientation, interpolated between ticks.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "physics/mesh.h"
#include "physics/mesh_reduce.h"
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

// A soft body as it is this frame. Only mesh and positions are required.
struct BodyView {
    const Mesh* mesh = nullptr;    // topology: render vertices, normal slots, triangles
    // A body simulated on fewer particles than its mesh has (physics/mesh_reduce.h): `surface`
    // is the full-resolution mesh drawn, each of its particles placed by `skin` from the
    // simulated ones; `mesh` is then the simulated particles' own mesh (for the overlays).
    const Mesh* surface = nullptr;
    std::span<const SkinBinding> skin;
    Vec3Span positions;            // particles at the latest tick
    Vec3Span previous_positions;   // particles one tick earlier; empty: no interpolation
    float alpha = 1.0f;            // draws lerp(previous_positions, positions, alpha)
    Vec3Span velocities;           // for the velocity arrows
    Vec3Span forces;               // net force on each particle, N: for the force arrows
    Vec3Span rest_positions;       // for the springs' strain colours
    std::span<const float> inverse_masses;  // 0 marks a pinned particle
    // Drawn shifted and in a colour of its own (the integrator comparison's side-by-side bodies);
    // no colour: the appearance's body colour.
    glm::vec3 offset{0.0f};
    std::optional<glm::vec3> color;
};

// A rigid body as it is this frame: its mesh in its own axes (about its centre of mass), and
// where it is at the last two ticks. The orientation is the physics' quaternion as it stands
// (w, x, y, z): drawn by the same formula the physics turns it into a matrix with, so a
// quaternion left to drift from unit length (renormalize_every = 0) shows as a body that
// swells and shears.
struct RigidBodyView {
    const Mesh* mesh = nullptr;
    glm::vec3 position{0.0f}, previous_position{0.0f};
    glm::vec4 orientation{1.0f, 0.0f, 0.0f, 0.0f}, previous_orientation{1.0f, 0.0f, 0.0f, 0.0f};
    float alpha = 1.0f;              // draws between previous (0) and current (1)
    glm::vec3 color{0.5f};           // sRGB
    float radius = 0.0f;             // bounding sphere about the centre of mass, m
    float mass = 0.0f;               // kg, to scale the L overlay
    bool fixed = false;              // scenery: drawn in a quieter colour
    glm::vec3 velocity{0.0f};        // m/s, for the velocity overlay
    glm::vec3 angular_velocity{0.0f};   // rad/s, world axes: the omega overlay
    glm::vec3 angular_momentum{0.0f};   // kg m^2/s, world axes: the L overlay
};

// The body-to-world matrix of a rigid body view at its alpha: position lerped, orientation
// turned along the shorter arc (its length lerped), then the physics' quaternion formula.
glm::mat4 model_matrix(const RigidBodyView& body);

// A spring between bodies, end to end, for drawing (coloured by strain).
struct LinkView {
    glm::vec3 a{0.0f}, b{0.0f};
    float rest_length = 0.0f;
};

// A contact point of the last step: where, its normal, and the impulse it carried.
struct ContactView {
    glm::vec3 point{0.0f};
    glm::vec3 normal{0.0f, 0.0f, 1.0f};
    float impulse = 0.0f;  // N s along the normal
};

// An arrow the caller places (the inspector's forces): from a point, a vector, drawn on top.
struct ArrowView {
    glm::vec3 from{0.0f}, vector{0.0f};  // m
    glm::vec3 color{1.0f};               // sRGB
    float width = 2.5f;                  // px
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
    bool links = true;            // springs between bodies
    bool contacts = false;        // contact points, normals and impulses
    bool angular = false;         // rigid bodies' omega and L arrows
    // The mouse's pull: a line from the grabbed point to the point it is pulled toward.
    bool grab = false;
    std::uint32_t grab_particle = 0;  // of the first soft body, unless grab_point is set
    bool grab_on_rigid = false;       // the pull starts at grab_point (a rigid body's point)
    glm::vec3 grab_point{0.0f};
    glm::vec3 grab_target{0.0f};
};

struct Appearance {
    glm::vec3 body_color{0.93f, 0.45f, 0.24f};  // sRGB, 0..1: the soft bodies
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
    glm::vec3 body_offset{0.0f};  // draws the soft bodies (and all that follows them) shifted, m
    bool flip_normals = false;    // inverts the recomputed normals
    bool particle_mesh = false;   // draws a reduced body's simulated particles' mesh, not its full surface
};

struct Frame {
    std::vector<BodyView> soft_bodies;
    std::vector<RigidBodyView> rigid_bodies;
    std::vector<LinkView> links;
    std::vector<ContactView> contacts;
    std::vector<ArrowView> arrows;
    Camera camera;
    Overlays overlays;
    Appearance appearance;
    DebugOptions debug;
};

}  // namespace softbody::render

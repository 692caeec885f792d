// One soft body of Listing 8: a particle at every distinct vertex of a mesh, and a spring
// (Eq. 21) and a damper (Eq. 22) between every pair of particles.
//
// Plain data, owned by the World (world.h), which advances it; what acts on it lives in one
// file per concept: forces.cpp (gravity, drag, the grab), pair_forces.cpp (springs and
// dampers), ground_contact.cpp (Eq. 24, 25 and impacts), integrators.cpp (the steps),
// stability.cpp, divergence.cpp, energy.cpp.
//
// Topology apart from state: the rest positions (every rest
// length comes from them) never change after the body is built; x, Verlet's step
// x_n - x_{n-1}, v and 1/m are the state, in flat arrays.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "physics/arrays.h"
#include "physics/mesh.h"
#include "physics/mesh_reduce.h"
#include "physics/pair_forces.h"
#include "physics/defs.h"

namespace softbody {

// A particle touching the ground at the start of a step, and what friction did to it
// (ground_contact.cpp).
struct ParticleContact {
    std::uint32_t particle;
    bool held;            // static friction (Eq. 24) cancelled the whole tangential force
    bool sliding;         // dynamic friction (Eq. 25) acted
    float x0, y0;         // tangential position at the start of the step
    float vx0, vy0;       // tangential velocity at the start of the step
    float fx = 0.0f, fy = 0.0f;  // friction's force then (Eq. 24 past its limit, or 25), N
};

struct SoftBody {
    SoftBodyDef def;            // its name and keys as they are now
    SoftBodyDef built;          // as its particles were made (reset makes them from `def` again)
    Mesh mesh;                  // as loaded: what is drawn; vertex numbers (pins, springs) are its

    // Above the particle budget (def.max_particles) the body is simulated on a subset of the
    // mesh's particles (mesh_reduce.h), and every particle of `mesh` follows three of them:
    // `reduced` says which, `skin` is its bindings with offsets in metres (scaled as the body
    // is), `particle_mesh` the simulated particles as a mesh (for overlays). Null and empty when
    // every particle of `mesh` is simulated.
    std::shared_ptr<const ReducedMesh> reduced;
    std::size_t reduced_budget = 0;   // the budget `reduced` was made for
    std::vector<SkinBinding> skin;
    Mesh particle_mesh;
    // What build_particles did with the file's units and axes.
    float scale_used = 1.0f;          // file units to metres (def.scale, or the automatic one)
    Vec3 file_centre;                 // subtracted before turning, when sized automatically

    // Topology (fixed): rest positions.
    Vec3Array rest;
    float rest_radius = 0.0f;  // bounding sphere about the rest centre (Eq. 23's S)

    // State.
    Vec3Array x, v;
    Vec3Array verlet_step;     // Verlet's x_n - x_{n-1}, carried as such (see integrators.cpp)
    FloatArray inv_mass;       // 0 for pinned particles
    float mass = 1.0f;         // of each particle
    // The springs' and dampers' k and c (Eq. 21, 22) as simulated: the body's keys, or for a
    // reduced body (below), with r = (mesh particles) / (simulated particles), r times them,
    // as `mass` is r times particle_mass: the body weighs what the whole mesh would (for
    // contacts, drag, a grab), and moves as a body of the simulated particles at the keys:
    // the same strain under its own weight (m g / (k N R) for N particles) and the same fastest
    // mode (omega^2 = k N / m), so it costs, and needs the substeps of, the budget, not the
    // mesh. (k r^2 would keep the whole mesh's stiffness, N^2 k, and its substeps: a 38,000-
    // vertex scan needed 49 and ran at a third of real time.)
    float stiffness = 0.0f, damping = 0.0f;
    float verlet_h = 0.0f;     // step verlet_step was made for (0: make it from v)

    // Net force on each particle (N) at the last force evaluation, friction included: for display.
    Vec3Array force;
    // Positions at the start of the last tick: the renderer draws between them and x.
    Vec3Array x_tick_prev;

    // What the World keeps between ticks and steps.
    std::unique_ptr<PairForceKernel> kernel;   // Eq. 21, 22 over every pair
    std::vector<ParticleContact> contacts;     // ground contacts of the current step
    Vec3Array accel[4], x_tmp, v_stage, v_sum; // integrator scratch (four stages for RK4)
    Vec3Array x_good, v_good, verlet_step_good;  // the last state that passed the checks
    Vec3Array x_step_start, v_step_start;  // the step's start: contacts with rigid bodies are found there
    float verlet_h_good = 0.0f;

    std::size_t particle_count() const { return x.size(); }
    std::size_t spring_count() const { return particle_count() * (particle_count() - 1) / 2; }
    bool is_pinned(std::uint32_t particle) const { return inv_mass[particle] == 0.0f; }
    const std::string& name() const { return def.name; }
};

// Listing 8: one particle per distinct vertex of body.mesh, as body.def says (or, above max_particles, per
// particle the reduction keeps), turned so the file's `up_axis` points up (+z), then by
// `rotation`, scaled by `scale` and lifted by `init_height`, at rest, all moving at
// `initial_velocity`, pinned where `pinned` says. Resets the whole state; body.built becomes
// body.def.
//
// With `scale` automatic (0, "auto"), the mesh is centred (its bounding box's centre at the
// origin) and scaled so that its largest side is 1 m; a mesh of one point keeps scale 1.
// Throws InputError when the budget cannot hold the mesh (max_particles below 4).
void build_particles(SoftBody& body);

// What the user should hear about the particle budget, or "" when the body runs on what it asked
// for: `max_particles` all (0) promises a particle per vertex, but no body runs on more than
// kMaxParticles, so a larger mesh is reduced to at most that many. One line: the cap, the
// particles used, and how to ask for fewer. (A budget given as a number is kept as asked.)
std::string particle_cap_note(const SoftBody& body);

// The simulated particle a vertex of body.mesh moves with: its own, or, when the body is
// reduced and the vertex's particle was dropped, the one of its three it follows most.
std::uint32_t particle_of_vertex(const SoftBody& body, std::uint32_t vertex);
// The first vertex of body.mesh at a simulated particle (for saving a pin as a vertex number).
std::uint32_t vertex_of_particle(const SoftBody& body, std::uint32_t particle);

// Pins or frees one particle; a pinned particle has 1/m = 0 and stays where it is.
void set_pinned(SoftBody& body, std::uint32_t particle, bool pinned);

// Applies the body's particle_mass, stiffness and damping keys of body.def (live: pins stay), scaled by r
// for a reduced body as `stiffness` above says.
void apply_body_keys(SoftBody& body);

}  // namespace softbody

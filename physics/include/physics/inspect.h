// What acts on one particle, equation by equation, with numbers: the app's inspector. Every
// term is computed afresh from the body's state as it stands (the forces the next step starts
// from), by the same functions the step uses, so that the terms add up to the net force and a
// student can follow Listing 8's CalcForce one line at a time.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "physics/world.h"

namespace softbody {

struct ForceTerm {
    std::string name;      // "weight", "springs", "dampers", "drag", "ground", "friction", ...
    std::string equation;  // where it comes from: "Listing 8", "Eq. 21", ...
    Vec3 force;            // N
    std::string detail;    // the numbers that decide it (friction's regime, a contact's impulse)
};

// One of the pairs that pull or push the particle hardest.
struct PairTerm {
    std::uint32_t other = 0;  // the other particle
    float length = 0.0f, rest_length = 0.0f;  // m
    Vec3 spring, damper;      // on the inspected particle: Eq. 21 and Eq. 22, N
};

enum class FrictionRegime { None, Held, Slipping, Sliding };

struct ParticleInspection {
    std::size_t body = 0;
    std::uint32_t particle = 0;
    Vec3 x, v, a;             // position, velocity, and a = net / m
    float mass = 0.0f;        // kg (0: pinned, it does not move)
    std::vector<ForceTerm> terms;
    std::vector<PairTerm> strongest;  // at most three, the largest |spring + damper| first
    Vec3 net;                 // the sum of the terms, N
    FrictionRegime friction = FrictionRegime::None;
    bool on_ground = false;   // touching it and pressed into it
};

// Throws std::out_of_range for a body or particle that does not exist.
ParticleInspection inspect_particle(const World& world, std::size_t body, std::uint32_t particle);

// A rigid body: each force with the torque it has about the centre of mass (Eq. 27, 33), and
// the impulses its contacts took in the last step (Eq. 37) with their angular parts.
struct WrenchTerm {
    std::string name, equation;
    Vec3d force;    // N (for a contact: the impulse over the step, N)
    Vec3d torque;   // N m, r x F about the centre of mass
    Vec3d impulse;  // a contact's impulse, N s (zero for the others)
    std::string detail;
};
struct RigidInspection {
    std::size_t body = 0;
    std::vector<WrenchTerm> terms;
    Vec3d force, torque;  // the sums
};
RigidInspection inspect_rigid(const World& world, std::size_t body);

}  // namespace softbody

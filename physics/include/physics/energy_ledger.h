// The energy a world has let go of, as a running total: what its dampers (Eq. 22), drag
// (Eq. 23), friction (Eq. 24, 25) and contacts took, so that kinetic + gravitational + elastic
// + dissipated stays the energy it had, as a classroom's energy bars show it.
//
// Tick by tick, dissipated grows by what the total fell in that tick. A tick across which
// something from outside changed the world (a key, a grab, a pin, a body made or unmade:
// World::outside_changes) is not counted: that energy was put in or taken by a person, not by
// the physics. What the integrator itself gains or loses is in it too: nothing for a resting
// body, an oscillation of a few parts in a thousand for Verlet and symplectic Euler, growth for
// explicit Euler (which then shows as negative dissipation).
#pragma once

#include <cstdint>

#include "physics/world.h"

namespace softbody {

class EnergyLedger {
public:
    // After every tick, and once before the first: the world's energies now.
    void observe(World& world);

    const Energy& energy() const { return energy_; }   // at the last observe
    double dissipated() const { return dissipated_; }  // J, since the first observe
    // kinetic + gravitational + elastic + dissipated: the energy the world started with (and
    // what was put in since), J.
    double total() const { return energy_.total() + dissipated_; }

private:
    Energy energy_;
    double dissipated_ = 0.0;
    std::uint64_t changes_ = 0;
    bool started_ = false;
};

}  // namespace softbody

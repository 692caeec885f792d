#include "physics/energy_ledger.h"

namespace softbody {

void EnergyLedger::observe(World& world) {
    const Energy now = world.energy();
    if (started_ && world.outside_changes() == changes_) dissipated_ += energy_.total() - now.total();
    energy_ = now;
    changes_ = world.outside_changes();
    started_ = true;
}

}  // namespace softbody

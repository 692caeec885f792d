// Internal to the physics library: the stability estimate of one soft body (stability.cpp).
#pragma once

#include "physics/world.h"

namespace softbody {

Stability soft_body_stability(const SoftBody& body, const WorldSettings& world, int substeps);

}  // namespace softbody

// A contact: a rigid body or a soft body's particle (side a) against the ground or a rigid body
// (side b): where, along which normal, how deep, and what the solver did there. The World keeps
// the contacts of its last step for display and teaching (the app's contact overlay).
#pragma once

#include <cstdint>

#include "physics/vec3.h"

namespace softbody {

struct RigidContact {
    std::uint32_t a = 0;         // the rigid body the normal points toward (or the particle, see `soft`)
    std::int32_t b = -1;         // the other rigid body, or -1 for the ground (static: 1/m = 0, J^-1 = 0)
    std::int32_t soft = -1;      // >= 0: side a is particle a of this soft body (no rotation term)
    std::uint32_t feature = 0;   // which vertex or edge made it, to carry its impulses to the next tick
    Vec3d point;                 // world, m, where the tick began
    Vec3d arm_a, arm_b;          // from each body's centre of mass to the point, world axes (the r of Eq. 38)
    Vec3d normal;                // unit, out of b toward a
    double separation = 0.0;     // the points' gap along the normal as the tick began, m (< 0: overlapping)
    double depth = 0.0;          // penetration where the tick left the bodies, m (> 0: overlapping)
    double restitution = 0.0;    // e
    double friction = 0.0;       // mu; for a particle, mu_d of Eq. 25 while it slides
    double rolling = 0.0;        // C_rr r: the torque holding back a turn of a round body on
                                 // this contact, per newton of normal force, m (0: none)
    double static_friction = 0.0;  // a particle's stick limit: mu_s (Eq. 24) when it was at rest
                                   // as the tick began, mu_d when it was already sliding

    // What the solver did (Eq. 37, 38), over the whole tick.
    double approach_speed = 0.0; // -v_rel . n as the tick began (> 0: closing), m/s
    double normal_impulse = 0.0; // lambda, every substep's and the bounce's, N s
    double tangent_impulse[2] = {0.0, 0.0};  // friction's, along contact_tangents(normal)
    double bounce_impulse = 0.0; // restitution's part of normal_impulse, N s
    // The impulses of the tick's last substep, per second (N): the next tick starts from them.
    double warm_normal = 0.0;
    double warm_tangent[2] = {0.0, 0.0};
    double warm_twist = 0.0;   // friction's turn about the normal (its manifold's share)
    Vec3d warm_roll;           // rolling resistance's torque (its manifold's share), N m
};

// A particle of one soft body against the surface of another (or of its own, with
// self_collision): against a triangle, or a point cloud's particle (soft_contacts.h). Its
// impulse acts on the particle (side a) and, opposite, on the three particles of the other
// side by their weights, so that momentum is kept exactly.
struct SoftContact {
    std::uint32_t body_a = 0, particle = 0;  // the particle
    std::uint32_t body_b = 0;                // the surface's body (body_a itself in self contact)
    std::uint32_t other[3] = {0, 0, 0};      // its particles: a triangle's corners, or one particle three times
    float weight[3] = {0.0f, 0.0f, 0.0f};    // barycentric weights of the nearest point (sum 1)
    Vec3d normal;                            // unit, out of the surface toward the particle
    double separation = 0.0;                 // gap beyond the contact distance as the substep began, m (< 0: overlap)
    double distance = 0.0;                   // the contact distance: the surface's thickness plus the particle's radius, m
    double normal_impulse = 0.0;             // lambda on the particle over the last substep, N s
    double tangent_impulse = 0.0;            // friction's size over the last substep, N s
    Vec3d impulse;                           // the whole impulse on the particle over the last substep, N s
};

// The whole impulse a contact's solver applied on side a, normal and tangential (friction)
// together, N s (side b took the opposite).
Vec3d contact_impulse(const RigidContact& contact);

// Eq. 38 for one contact, term by term, as a student checks it by hand: the impulse along n that
// takes the closing speed v_rel . n to -e times it, for this contact alone (World::impulse_terms).
// Body 1 is side a (a rigid body, or a particle: no rotation term), body 2 side b (the ground:
// 1/m = 0, no rotation term).
struct ImpulseTerms {
    Vec3d n;                  // the normal, out of body 2 toward body 1
    double v_rel_n = 0.0;     // (v_1 + w_1 x r_1 - v_2 - w_2 x r_2) . n before the impulses, m/s (< 0: closing)
    double e = 0.0;           // restitution
    Vec3d r1, r2;             // from each centre of mass to the point, m
    Vec3d r1_x_n, r2_x_n;     // r x n, m
    double inv_mass_1 = 0.0, inv_mass_2 = 0.0;  // 1/m, 1/kg
    double rotation_1 = 0.0;  // n . ((J_1^-1 (r_1 x n)) x r_1), 1/kg
    double rotation_2 = 0.0;  // n . ((J_2^-1 (r_2 x n)) x r_2), 1/kg
    double denominator = 0.0; // the sum of the four, 1/kg
    double lambda = 0.0;      // -(1 + e) v_rel . n / denominator, N s
    double solver_lambda = 0.0;  // what the solver applied here, every contact and friction at once, N s
};

}  // namespace softbody

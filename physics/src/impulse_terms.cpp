// Eq. 38 for one contact, term by term: what the app's "last collision" read-out shows. The
// inertia tensors are the ones the solver used: where the contact was found.
#include "physics/world.h"

namespace softbody {

ImpulseTerms World::impulse_terms(const RigidContact& c) const {
    ImpulseTerms t;
    t.n = c.normal;
    t.v_rel_n = -c.approach_speed;
    t.e = c.restitution;
    t.solver_lambda = c.normal_impulse;
    // One side's 1/m and rotation term: a rigid body's from its inverse inertia tensor in world
    // axes (Eq. 32), a particle's 1/m alone, the ground's nothing.
    const auto side = [&](bool particle, std::int64_t index, const Vec3d& arm, Vec3d& r, Vec3d& r_x_n, double& inv_mass,
                          double& rotation) {
        if (index < 0) return;
        if (particle) {
            inv_mass = soft_[std::size_t(c.soft)].inv_mass[std::size_t(index)];
            return;
        }
        // Where the contact was found: the orientation its impulses were solved with.
        const std::size_t i = std::size_t(index);
        const RigidMotion m = softbody::rigid_motion(rigid_[i], y_contacts_start_.empty() ? rigid_previous_state(i)
                                                                                          : &y_contacts_start_[i * rigid::kStateSize]);
        r = arm;
        r_x_n = cross(r, t.n);
        inv_mass = rigid_[i].inv_mass;
        rotation = dot(t.n, cross(m.J_inv * r_x_n, r));
    };
    side(c.soft >= 0, c.a, c.arm_a, t.r1, t.r1_x_n, t.inv_mass_1, t.rotation_1);
    side(false, c.b, c.arm_b, t.r2, t.r2_x_n, t.inv_mass_2, t.rotation_2);
    t.denominator = t.inv_mass_1 + t.inv_mass_2 + t.rotation_1 + t.rotation_2;
    if (t.denominator > 0.0) t.lambda = -(1.0 + t.e) * t.v_rel_n / t.denominator;
    return t;
}

}  // namespace softbody

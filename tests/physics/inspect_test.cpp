// The inspector (physics/inspect.h): each force on one particle, named by its equation, adding
// up to the net force; friction's regime as Eq. 24 and 25 decide it.
#include <cmath>

#include "physics/inspect.h"
#include "physics/pair_forces.h"
#include "test_support.h"

namespace softbody::test {
namespace {

const ForceTerm* term(const ParticleInspection& in, const std::string& name) {
    for (const ForceTerm& t : in.terms) {
        if (t.name == name) return &t;
    }
    return nullptr;
}

FlatKeys cube_params() {
    FlatKeys p = listing8_params();
    p.particle_mass = 0.1f;
    p.stiffness = 200.0f;
    p.damping = 0.5f;
    p.init_height = 0.0f;
    p.auto_substeps = true;
    return p;
}

// A cube resting on the ground: a bottom particle is held by static friction (Eq. 24), the
// ground holds it up, and the terms, weight to friction, add up to a net force of about zero.
TEST(Inspector, RestingParticleNamesEq24AndItsTermsSumToTheNet) {
    std::vector<Vec3> corners = cube_corners(0.3f);
    for (Vec3& c : corners) c.z += 0.15f;  // bottom face on the ground
    OneBodyWorld world(cube_params(), points(corners));
    world.run(250);  // 5 s: settled
    ASSERT_EQ(world.status(), Status::Ok);
    const ParticleInspection in = inspect_particle(world, 0, 0);  // corner 0: bottom
    ASSERT_TRUE(in.on_ground);
    EXPECT_EQ(in.friction, FrictionRegime::Held);
    const ForceTerm* friction = term(in, "friction");
    ASSERT_NE(friction, nullptr);
    EXPECT_EQ(friction->equation, "Eq. 24");
    EXPECT_NE(friction->detail.find("mu_s"), std::string::npos);
    ASSERT_NE(term(in, "ground"), nullptr);
    ASSERT_NE(term(in, "weight"), nullptr);
    EXPECT_EQ(term(in, "springs")->equation, "Eq. 21");
    EXPECT_EQ(term(in, "dampers")->equation, "Eq. 22");
    Vec3 sum;
    for (const ForceTerm& t : in.terms) sum += t.force;
    EXPECT_EQ(sum, in.net);  // the same sum, term by term
    // At rest: the ground and friction cancel what the rest applies, exactly by construction in
    // z and in the plane; what is left is the dampers' and springs' last ringing, far below the
    // weight (0.98 N).
    EXPECT_LT(length(in.net), 1e-3f);
    EXPECT_EQ(in.a, in.net / 0.1f);
}

// The springs and dampers on one particle are the reference kernel's (Eq. 21, 22 over every
// pair), and its three strongest pairs are named.
TEST(Inspector, SpringsAndDampersAreTheKernelsForThatParticle) {
    FlatKeys p = cube_params();
    p.ground = false;
    p.gravity = {0.0f, 0.0f, 0.0f};
    p.initial_velocity = {0.0f, 0.0f, 0.0f};
    std::vector<Vec3> cloud = random_cloud(40, 3, 0.5f);
    OneBodyWorld world(p, points(cloud));
    // Give it a shape to spring back from: a pull on one particle for a few ticks.
    world.set_grab(Grab{5, Vec3{2.0f, 0.0f, 0.0f}, 50.0f, 0, false, {}});
    world.run(10);
    world.set_grab(std::nullopt);
    const SoftBody& body = world.soft_body(0);
    const PairInput input{body.x.x.data(),    body.x.y.data(),    body.x.z.data(),    body.v.x.data(),
                          body.v.y.data(),    body.v.z.data(),    body.rest.x.data(), body.rest.y.data(),
                          body.rest.z.data(), body.particle_count(), body.stiffness, body.damping};
    Vec3Array reference;
    pair_forces_reference(input, reference);
    for (std::uint32_t i : {0u, 5u, 39u}) {
        const ParticleInspection in = inspect_particle(world, 0, i);
        const Vec3 pairs = term(in, "springs")->force + term(in, "dampers")->force;
        // Summed in another order than the reference: float rounding, 1e-5 of the largest pair.
        EXPECT_LT(length(pairs - reference[i]), 1e-5f * (1.0f + length(reference[i]))) << "particle " << i;
        ASSERT_EQ(in.strongest.size(), 3u);
        EXPECT_GE(length(in.strongest[0].spring + in.strongest[0].damper), length(in.strongest[2].spring + in.strongest[2].damper));
    }
}

// Sliding on a slope steeper than mu_s allows (gravity tilted, as contact_test.cpp does):
// dynamic friction, Eq. 25, mu_d times the normal force, against the slide.
TEST(Inspector, SlidingParticleNamesEq25) {
    FlatKeys p = listing8_params();
    p.init_height = 0.0f;
    const double angle = 40.0 * kPi / 180.0;
    p.gravity = {float(9.81 * std::sin(angle)), 0.0f, float(-9.81 * std::cos(angle))};
    OneBodyWorld world(p, points({{0.0f, 0.0f, 0.0f}}));
    world.run(20);
    const ParticleInspection in = inspect_particle(world, 0, 0);
    EXPECT_EQ(in.friction, FrictionRegime::Sliding);
    const ForceTerm* friction = term(in, "friction");
    ASSERT_NE(friction, nullptr);
    EXPECT_EQ(friction->equation, "Eq. 25");
    const float F_n = float(9.81 * std::cos(angle));  // 1 kg
    EXPECT_NEAR(length(friction->force), 0.4f * F_n, 1e-5f);
    EXPECT_LT(friction->force.x, 0.0f);  // against the slide (downhill is +x)
}

}  // namespace
}  // namespace softbody::test

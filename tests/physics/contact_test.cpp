// The ground: Coulomb friction (Eq. 24 static, Eq. 25 dynamic) and restitution.
//
// A slope is made by tilting gravity instead of the ground: g = g0 (sin a, 0, -cos a) on the
// plane z = 0 is a block on a plane inclined by a, seen in the plane's own frame. The normal
// force is then m g0 cos a and the downhill force m g0 sin a, so Eq. 24 holds the block while
// tan a <= mu_s, and once it slides Eq. 25 leaves the acceleration g0 (sin a - mu_d cos a).
#include <cmath>
#include <vector>

#include "test_support.h"

namespace softbody::test {
namespace {

constexpr float kMuS = 0.6f, kMuD = 0.4f;

FlatKeys ground_params() {
    FlatKeys p = bare_params();
    p.ground = true;
    p.ground_height = 0.0f;
    p.static_friction = kMuS;
    p.dynamic_friction = kMuD;
    return p;
}

FlatKeys slope_params(double angle) {
    FlatKeys p = ground_params();
    p.gravity = {float(kG * std::sin(angle)), 0.0f, float(-kG * std::cos(angle))};
    return p;
}

// The bodies that rest on the slope: a single particle, and a flat square of four particles
// joined by stiff damped springs, all four on the ground.
std::vector<Mesh> blocks() {
    return {points({{0.0f, 0.0f, 0.0f}}, "particle"),
            points({{0.0f, 0.0f, 0.0f}, {0.5f, 0.0f, 0.0f}, {0.0f, 0.5f, 0.0f}, {0.5f, 0.5f, 0.0f}}, "square")};
}

FlatKeys with_springs(FlatKeys p, const Mesh& mesh) {
    if (mesh.particle_count() > 1) {
        p.stiffness = 200.0f;  // N (k h^2 + 2 c h) = 4 (0.08 + 0.04) = 0.48 < 4 m: stable
        p.damping = 0.5f;
    }
    return p;
}

double degrees(double a) { return a * kPi / 180.0; }

TEST(StaticFriction, HoldsBelowMuS) {
    const double at_limit = std::atan(double(kMuS));  // 30.96 degrees
    // At rest, or drifting slower than the static threshold (1e-4 m/s): downhill, uphill or
    // across. Eq. 24 holds it where it is; merely cancelling the force would let the drift go on.
    const Vec3 drifts[] = {{0.0f, 0.0f, 0.0f}, {5e-5f, 0.0f, 0.0f}, {-5e-5f, 0.0f, 0.0f}, {0.0f, 5e-5f, 0.0f}};
    for (const Mesh& mesh : blocks()) {
        for (double angle : {degrees(10.0), degrees(25.0), at_limit - degrees(0.5)}) {
          for (const Vec3& drift : drifts) {
            FlatKeys p = with_springs(slope_params(angle), mesh);
            p.initial_velocity = drift;
            OneBodyWorld world(p, mesh);
            std::vector<Vec3> x0;
            for (std::size_t i = 0; i < world.soft_body(0).particle_count(); ++i) x0.push_back(position(world, i));
            world.run(500);  // 10 s
            ASSERT_EQ(world.status(), Status::Ok);
            for (std::size_t i = 0; i < world.soft_body(0).particle_count(); ++i) {
                // |F_t| <= mu_s |F_n|: Eq. 24 cancels F_t exactly, and the step ends where it
                // began. Zero displacement, exactly: any creep at all is a failure.
                EXPECT_EQ(position(world, i).x, x0[i].x) << mesh.source << " at " << angle * 180 / kPi << " deg";
                EXPECT_EQ(position(world, i).y, x0[i].y) << mesh.source << " at " << angle * 180 / kPi << " deg";
                EXPECT_EQ(velocity(world, i).x, 0.0f);
                // Resting on the ground, not sinking into it or hopping off it.
                EXPECT_EQ(position(world, i).z, 0.0f);
            }
          }
        }
    }
}

// Pushed uphill at v0 on a slope it can rest on (tan a < mu_s), a block decelerates at
// g (sin a + mu_d cos a) (gravity and Eq. 25's friction both pull it back), stops after
// v0^2 / (2 g (sin a + mu_d cos a)), and then Eq. 24 holds it there: it never slides back.
TEST(StaticFriction, BlockPushedUphillStopsAndStays) {
    const double angle = degrees(25.0);  // tan 25 = 0.47: above mu_d, below mu_s
    const double v0 = 2.0;
    FlatKeys p = slope_params(angle);
    p.initial_velocity = {float(-v0), 0.0f, 0.0f};  // downhill is +x
    OneBodyWorld world(p, points({{0.0f, 0.0f, 0.0f}}));
    double highest = 0.0;
    int stopped_at = -1;
    for (int n = 1; n <= 500; ++n) {
        world.tick();
        const double x = position(world, 0).x;
        ASSERT_LE(x, highest + 1e-7) << "tick " << n << ": moved back uphill after stopping?";
        if (stopped_at < 0) {
            highest = std::min(highest, x);
            if (velocity(world, 0).x == 0.0f) stopped_at = n;
        } else {
            // After the stop: exactly where it stopped, at rest.
            ASSERT_EQ(x, highest) << "tick " << n << ": slid after stopping";
            ASSERT_EQ(velocity(world, 0).x, 0.0f) << "tick " << n;
        }
    }
    ASSERT_GT(stopped_at, 0);
    const double a = kG * (std::sin(angle) + double(kMuD) * std::cos(angle));
    // As for the level stop below: the discrete slide falls short of v0^2 / (2a) by less than
    // one step's travel, v0 h.
    EXPECT_NEAR(-highest, v0 * v0 / (2.0 * a), v0 * 0.02);
    EXPECT_NEAR(stopped_at * 0.02, v0 / a, 0.02 + 1e-9);
}

TEST(StaticFriction, SlidesAboveMuSWithAccelerationFromMuD) {
    const double at_limit = std::atan(double(kMuS));
    for (const Mesh& mesh : blocks()) {
        for (double angle : {at_limit + degrees(1.0), degrees(40.0), degrees(60.0)}) {
            OneBodyWorld world(with_springs(slope_params(angle), mesh), mesh);
            world.run(20);
            const double v1 = velocity(world, 0).x;
            const double x1 = position(world, 0).x;
            world.run(100);
            ASSERT_EQ(world.status(), Status::Ok);
            const double v2 = velocity(world, 0).x;
            const double x2 = position(world, 0).x;
            const double t = 100 * 0.02;
            const double expected = kG * (std::sin(angle) - double(kMuD) * std::cos(angle));
            // Once sliding, the net force is constant, so v gains exactly a h per step and
            // x follows the matching discrete parabola. Float rounding of v (up to 16 m/s,
            // half an ulp 1e-6 m/s) over 100 steps stays below 1e-4 m/s, against a gain of
            // 3.7 m/s or more; 1e-3 relative is generous, and hundreds of times smaller than
            // the change from using mu_s instead of mu_d (46% at 40 degrees).
            EXPECT_NEAR((v2 - v1) / t, expected, 1e-3 * expected) << mesh.source << " at " << angle * 180 / kPi;
            // Positions: x2 - x1 = v1 t + a h^2 n (n+1) / 2 for symplectic Euler with n = 100.
            const double h = 0.02, n = 100;
            EXPECT_NEAR(x2 - x1, v1 * t + expected * h * h * n * (n + 1) / 2.0, 1e-3 * (x2 - x1)) << mesh.source;
            // Still on the ground, and sliding straight downhill.
            EXPECT_EQ(position(world, 0).z, 0.0f);
            EXPECT_NEAR(position(world, 0).y, 0.0f, 1e-6);
        }
    }
}

// A particle sliding on level ground at v0 decelerates at mu_d g (Eq. 25) and stops after
// v0^2 / (2 mu_d g). It must never reverse, and once stopped static friction holds it.
TEST(DynamicFriction, StopsAfterV0SquaredOver2MuDG) {
    for (const Vec3 v0 : {Vec3{3.0f, 0.0f, 0.0f}, Vec3{-1.2f, 2.5f, 0.0f}, Vec3{0.5f, 0.5f, 0.0f}}) {
        FlatKeys p = ground_params();
        p.gravity = {0.0f, 0.0f, float(-kG)};
        p.initial_velocity = v0;
        OneBodyWorld world(p, points({{0.0f, 0.0f, 0.0f}}));
        const double speed = length(v0);
        const Vec3 direction = v0 / length(v0);
        double along = 0.0;
        int stopped_at = -1;
        for (int n = 1; n <= 400; ++n) {
            world.tick();
            const Vec3 x = position(world, 0), v = velocity(world, 0);
            const double now = dot(x, direction);
            // Never reverses: the velocity never points back, the position never moves back.
            ASSERT_GE(dot(v, direction), 0.0f) << "tick " << n;
            ASSERT_GE(now, along) << "tick " << n;
            // And it moves along the line it started on (float rounding of x only).
            ASSERT_NEAR(length(x - direction * float(now)), 0.0, 1e-5) << "tick " << n;
            along = now;
            if (stopped_at < 0 && v.x == 0.0f && v.y == 0.0f) stopped_at = n;
        }
        ASSERT_GT(stopped_at, 0) << "never stopped";
        const double distance = speed * speed / (2.0 * double(kMuD) * kG);
        // The discrete slide covers sum_k (v0 - k a h) h = v0^2 / (2a) - O(v0 h): the last step,
        // which would overshoot the stop, ends it where it began. So |error| < v0 h.
        EXPECT_NEAR(along, distance, speed * 0.02) << "v0 = " << speed;
        // It stops at t = v0 / (mu_d g), within a step.
        EXPECT_NEAR(stopped_at * 0.02, speed / (double(kMuD) * kG), 0.02 + 1e-9);
        // Held after stopping: 400 ticks in, it is exactly where it stopped.
        EXPECT_EQ(velocity(world, 0).x, 0.0f);
        EXPECT_EQ(velocity(world, 0).y, 0.0f);
    }
}

// A particle dropped from height H hits the ground at about sqrt(2 g H) and leaves it at e
// times its impact speed (v_n' = -e v_n).
TEST(Restitution, BouncesBackWithETimesImpactSpeed) {
    const double H = 1.0, h = 0.02;
    for (const float e : {0.0f, 0.3f, 0.5f, 1.0f}) {
        FlatKeys p = ground_params();
        p.gravity = {0.0f, 0.0f, float(-kG)};
        p.restitution = e;
        p.init_height = float(H);
        OneBodyWorld world(p, points({{0.0f, 0.0f, 0.0f}}));
        float v_before = 0.0f;
        int n = 0;
        while (position(world, 0).z > 0.0f && n < 1000) {
            v_before = velocity(world, 0).z;
            world.tick();
            ++n;
        }
        ASSERT_EQ(position(world, 0).z, 0.0f) << "e = " << e;  // on the ground, not below it
        // The step that reached the ground ended with v = v_before - g h (the impact speed);
        // restitution turned it into -e times that. Both are float operations on the same
        // numbers, so only a few ulps of 4.4 m/s remain: 1e-5 m/s.
        const float impact = v_before + float(-kG) * float(h);
        EXPECT_NEAR(velocity(world, 0).z, -e * impact, 1e-5) << "e = " << e;
        // The impact speed itself is sqrt(2 g H) = 4.43 m/s within the step's g h = 0.2 m/s.
        EXPECT_NEAR(-impact, std::sqrt(2.0 * kG * H), kG * h) << "e = " << e;

        // It rises to (e v)^2 / (2 g), within the distance of one step at that speed, and
        // never goes below the ground.
        float top = 0.0f;
        for (int k = 0; k < 100; ++k) {
            world.tick();
            top = std::max(top, position(world, 0).z);
            ASSERT_GE(position(world, 0).z, 0.0f);
            if (velocity(world, 0).z < 0.0f && position(world, 0).z <= top - 0.01f) break;
        }
        const double rise = (e * impact) * (e * impact) / (2.0 * kG);
        EXPECT_NEAR(top, rise, std::abs(e * impact) * h + 1e-6) << "e = " << e;
    }
}

TEST(Ground, DroppedBodyStaysAboveIt) {
    // A falling cube with Listing 8's springs: every particle stays at or above the ground,
    // at every tick (the contact puts a particle back on the surface within the step).
    FlatKeys p = listing8_params();
    OneBodyWorld world(p, points(cube_corners()));
    for (int n = 0; n < 500; ++n) {
        world.tick();
        ASSERT_GE(world.min_z(), p.ground_height) << "tick " << n;
    }
    ASSERT_EQ(world.status(), Status::Ok);
    // It comes to rest on the ground: the lowest particles touch it.
    EXPECT_NEAR(world.min_z(), p.ground_height, 1e-5);
}

}  // namespace
}  // namespace softbody::test

// Rigid bodies against closed forms: free rotation (Eq. 26, 28, 35, 36), the intermediate-axis
// flip, a symmetric top's precession, bounces (Eq. 37, 38 at the ground), resting contact,
// springs between bodies (Eq. 33), renormalisation (Listing 9), and determinism.
#include <cmath>
#include <numeric>

#include "physics/scene_io.h"
#include "test_support.h"

namespace softbody::test {
namespace {

// A world from scene text (the keys of app/README.md#scene-files).
// Body-axes angular velocity R^T w of rigid body i.
Vec3d body_omega(const World& world, std::size_t i) {
    const RigidMotion m = world.rigid_motion(i);
    return m.R.transposed() * m.omega;
}

double rotational_energy(const World& world, std::size_t i) {
    const RigidMotion m = world.rigid_motion(i);
    return 0.5 * dot(m.L, m.omega);
}

// The complete elliptic integral of the first kind K(k) = pi / (2 AGM(1, sqrt(1 - k^2))).
double elliptic_K(double k2) {
    double a = 1.0, b = std::sqrt(1.0 - k2);
    for (int i = 0; i < 40 && std::abs(a - b) > 1e-16 * a; ++i) {
        const double next = 0.5 * (a + b);
        b = std::sqrt(a * b);
        a = next;
    }
    return kPi / (2.0 * a);
}

// A spinning box in empty space: 1 m x 0.5 m x 0.15 m, 1 kg, so J = diag(0.0227, 0.0852, 0.1042)
// kg m^2: three different moments, y the intermediate axis.
std::string spinning_box(const char* integrator, const char* omega, const char* extra = "") {
    return std::string("{\"gravity\": [0, 0, 0], \"ground\": false, \"integrator\": \"") + integrator + "\"" + extra +
           ", \"rigid_bodies\": [{\"name\": \"box\", \"shape\": \"box\", \"size\": [1.0, 0.5, 0.15], \"mass\": 1,"
           " \"angular_velocity\": " + omega + "}]}";
}

// --- Free rotation ---------------------------------------------------------------------------

// No torque, so dL/dt = 0 (Eq. 26): every integrator leaves L exactly as it was (the momentum
// slots get h * 0 added), whatever it does to q. Energy 1/2 L . w: RK4 keeps it, symplectic
// Euler lets it wander without drifting, explicit Euler (Listing 9) gains it.
TEST(FreeRotation, AngularMomentumIsConservedAndEnergyBehavesAsEachIntegratorDoes) {
    struct Case {
        const char* integrator;
        double max_drift;  // |E(60 s) / E(0) - 1|
    };
    // RK4 at h w = 0.06 a step: local error (h w)^5 ~ 1e-6, and a measured 4e-6 after 3,000
    // steps; 1e-5 allows for it. Symplectic Euler's energy error is of order h w (wandering,
    // bounded): measured 1.1e-4; 1e-3 bounds it without letting a drift through (that is what
    // the 10-minute check below is for).
    for (const Case c : {Case{"rk4", 1e-5}, Case{"verlet", 1e-3}, Case{"symplectic_euler", 1e-3}}) {
        World world = world_of(spinning_box(c.integrator, "[1.0, 3.0, 1.0]"));
        const Vec3d L0 = world.rigid_motion(0).L;
        const double E0 = rotational_energy(world, 0);
        world.run(3000);
        ASSERT_EQ(world.status(), Status::Ok) << c.integrator;
        EXPECT_EQ(world.rigid_motion(0).L, L0) << c.integrator;  // bit for bit
        EXPECT_NEAR(rotational_energy(world, 0) / E0, 1.0, c.max_drift) << c.integrator;
    }
    // Bounded, not drifting: ten minutes later symplectic Euler is still within the same band.
    World world = world_of(spinning_box("verlet", "[1.0, 3.0, 1.0]"));
    const double E0 = rotational_energy(world, 0);
    world.run(30000);
    EXPECT_NEAR(rotational_energy(world, 0) / E0, 1.0, 1e-3);

    // Listing 9's explicit Euler gains energy: q + h/2 w q turns the body a little too far
    // each step, toward the axis of least inertia, where the same L has the most energy.
    World euler = world_of(spinning_box("explicit_euler", "[1.0, 3.0, 1.0]"));
    const Vec3d L0 = euler.rigid_motion(0).L;
    euler.run(500);
    ASSERT_EQ(euler.status(), Status::Ok);
    EXPECT_EQ(euler.rigid_motion(0).L, L0);
    EXPECT_GT(rotational_energy(euler, 0), 1.5 * E0);
    // And never past that axis's energy, L^2 / (2 I_min): the gain has a ceiling.
    const double I_min = 1.0 / 12.0 * (0.25 + 0.0225);
    EXPECT_LE(rotational_energy(euler, 0), dot(L0, L0) / (2.0 * I_min) * (1.0 + 1e-9));
}

// The intermediate-axis (Dzhanibekov) flip. Landau and Lifshitz, Mechanics, section 37: for
// I1 < I2 < I3 and M^2 > 2 E I2, the body-axes w2 is proportional to sn(tau, k) with
//   tau = t sqrt((I3 - I2)(M^2 - 2E I1) / (I1 I2 I3)),
//   k^2 = (I2 - I1)(2E I3 - M^2) / ((I3 - I2)(M^2 - 2E I1)),
// so w2 changes sign every 2K(k) of tau: a flip every T = 2K sqrt(I1 I2 I3 / ((I3 - I2)(M^2 - 2E I1))).
TEST(FreeRotation, IntermediateAxisFlipsWithTheEllipticPeriod) {
    World world = world_of(spinning_box("rk4", "[0.4, 3.0, 0.4]", ", \"dt\": 0.005"));
    const double I1 = (0.25 + 0.0225) / 12.0, I2 = (1.0 + 0.0225) / 12.0, I3 = (1.0 + 0.25) / 12.0;
    const Vec3d w0 = body_omega(world, 0);
    const double twoE = I1 * w0.x * w0.x + I2 * w0.y * w0.y + I3 * w0.z * w0.z;
    const double M2 = I1 * I1 * w0.x * w0.x + I2 * I2 * w0.y * w0.y + I3 * I3 * w0.z * w0.z;
    ASSERT_GT(M2, twoE * I2);  // the branch of the formula above
    const double k2 = (I2 - I1) * (twoE * I3 - M2) / ((I3 - I2) * (M2 - twoE * I1));
    const double T = 2.0 * elliptic_K(k2) * std::sqrt(I1 * I2 * I3 / ((I3 - I2) * (M2 - twoE * I1)));

    // The times w2 crosses zero, each found between two ticks by linear interpolation.
    std::vector<double> crossings;
    double previous = w0.y;
    while (world.time() < 12.0 * T && crossings.size() < 7) {
        world.tick();
        const double now = body_omega(world, 0).y;
        if ((previous > 0.0) != (now > 0.0)) {
            crossings.push_back(world.time() - 0.005 * now / (now - previous));
        }
        previous = now;
    }
    ASSERT_GE(crossings.size(), 4u) << "the body did not flip (T = " << T << " s)";
    for (std::size_t i = 1; i < crossings.size(); ++i) {
        // RK4 at h = 0.005 s keeps E and M^2 to about 1e-9 (so k and T to about the same), and
        // linear interpolation of w2 near a zero errs by O(h^2 w2'') ~ 1e-6 s: 1e-4 of T holds both.
        EXPECT_NEAR(crossings[i] - crossings[i - 1], T, 1e-4 * T) << "flip " << i;
    }
}

// A symmetric top (I1 = I2 = I, I3) spinning freely: in its own axes, (w1, w2) turns about the
// symmetry axis at Omega = w3 (I3 - I) / I (Euler's equations), w3 constant.
TEST(FreeRotation, SymmetricTopPrecessesAtTheEulerRate) {
    // A cylinder of radius 0.3 m and height 0.2 m: I3 = m r^2 / 2 = 0.045 m, I = m (3 r^2 + h^2) / 12
    // = 0.02583 m (Table 1), so Omega = 5 (0.045 - 0.02583) / 0.02583 = 3.71 rad/s.
    World world = world_of(
        "{\"gravity\": [0, 0, 0], \"ground\": false, \"integrator\": \"rk4\", \"dt\": 0.005, \"rigid_bodies\": "
        "[{\"name\": \"top\", \"shape\": \"cylinder\", \"radius\": 0.3, \"height\": 0.2, \"mass\": 1,"
        " \"angular_velocity\": [0.5, 0, 5]}]}");
    const double I = (3.0 * 0.09 + 0.04) / 12.0, I3 = 0.5 * 0.09;
    const double Omega = 5.0 * (I3 - I) / I;
    double angle = 0.0, last = std::atan2(body_omega(world, 0).y, body_omega(world, 0).x);
    for (int t = 0; t < 1000; ++t) {  // 5 s, about 3 turns of the precession
        world.tick();
        const Vec3d w = body_omega(world, 0);
        const double now = std::atan2(w.y, w.x);
        angle += std::remainder(now - last, 2.0 * kPi);
        last = now;
        // w3 stays 5 rad/s: RK4's error at h w = 0.025 is far below 1e-7 rad/s.
        ASSERT_NEAR(w.z, 5.0, 1e-7);
    }
    // The angle swept over 5 s, against Omega t. RK4's phase error over 1,000 steps of
    // h Omega = 0.019 is about (h Omega)^4 per step: 1e-4 rad in all; 1e-6 relative to the
    // 18.6 rad swept would be too tight, 1e-5 is not.
    EXPECT_NEAR(angle / world.time(), Omega, 1e-5 * Omega);
}

// Listing 9 renormalises q every few ticks: without it (renormalize_every = 0) explicit Euler's
// q + h/2 w q grows |q| by sqrt(1 + h^2 |w|^2 / 4) a step; with it, |q| = 1 at every fifth tick.
TEST(FreeRotation, RenormalisationKeepsTheQuaternionUnit) {
    World drifting = world_of(spinning_box("explicit_euler", "[0.2, 3.0, 0.2]", ", \"renormalize_every\": 0"));
    drifting.run(50);
    // 50 steps of at least sqrt(1 + (0.02 * 3)^2 / 4) each: |q| >= 1.0225 (w only grows).
    EXPECT_GT(drifting.rigid_motion(0).q.norm(), 1.02);

    World kept = world_of(spinning_box("explicit_euler", "[0.2, 3.0, 0.2]", ", \"renormalize_every\": 5"));
    for (int t = 1; t <= 50; ++t) {
        kept.tick();
        const double norm = kept.rigid_motion(0).q.norm();
        if (t % 5 == 0) EXPECT_NEAR(norm, 1.0, 1e-15) << "tick " << t;  // just renormalised: rounding only
        else EXPECT_LT(norm, 1.01) << "tick " << t;                      // four steps of drift at most
    }
}

// --- Gravity and the ground ------------------------------------------------------------------

// A spinning body in free fall: gravity acts at the centre of mass, so x follows the parabola of
// symplectic Euler exactly and the spin is untouched (no torque).
TEST(Ground, GravityAtTheCentreOfMassDoesNotTurnTheBody) {
    World world = world_of(
        "{\"ground\": false, \"rigid_bodies\": [{\"name\": \"b\", \"shape\": \"box\", \"size\": [0.3, 0.6, 0.2],"
        " \"mass\": 2, \"position\": [0, 0, 10], \"velocity\": [1, 0, 3], \"angular_velocity\": [2, 1, 0]}]}");
    const Vec3d L0 = world.rigid_motion(0).L;
    world.run(50);
    const RigidMotion m = world.rigid_motion(0);
    EXPECT_EQ(m.L, L0);
    // Symplectic Euler: v_n = v_0 + n h g, x_n = x_0 + h sum_{k=1..n} v_k = x_0 + n h v_0 + h^2 g n (n + 1) / 2.
    const double h = 0.02f, g = -9.81f;  // as the world holds them: floats
    const double n = 50;
    EXPECT_NEAR(m.x.z, 10.0 + n * h * 3.0 + h * h * g * n * (n + 1) / 2.0, 1e-12);
    EXPECT_NEAR(m.x.x, n * h * 1.0, 1e-12);
    EXPECT_NEAR(m.v.z, 3.0 + n * h * g, 1e-12);
}

// A sphere bouncing with restitution e: each apex is e^2 times the one before (v' = -e v at the
// ground, Eq. 38 against a static body), e^(2n) h0 in all.
TEST(Ground, BouncingSphereApexesFallAsEToTheTwoN) {
    const double e = 0.5, h0 = 1.0, dt = 0.002;
    World world = world_of("{\"restitution\": 0.5, \"dt\": 0.002, \"rigid_bodies\": [{\"name\": \"ball\", \"shape\": "
                           "\"sphere\", \"radius\": 0.1, \"position\": [0, 0, 1.1]}]}");
    std::vector<double> apexes;
    double vz_before = 0.0;
    while (world.time() < 2.5) {
        world.tick();
        const RigidMotion m = world.rigid_motion(0);
        if (vz_before > 0.0 && m.v.z <= 0.0) apexes.push_back(m.x.z - 0.1);
        vz_before = m.v.z;
        ASSERT_GE(m.x.z, 0.1 - 1e-3) << "the ball sank into the ground at t = " << world.time();
    }
    ASSERT_GE(apexes.size(), 3u);
    for (std::size_t n = 1; n <= 3; ++n) {
        // The bounce happens between two steps and symplectic Euler's free flight is itself off
        // by O(v h): each apex is within 1.5 v h of e^(2n) h0, v the speed of the impact before
        // it (measured 0.17 v h for the first).
        const double impact_speed = std::sqrt(2.0 * 9.81 * h0) * std::pow(e, double(n - 1));
        EXPECT_NEAR(apexes[n - 1], h0 * std::pow(e, 2.0 * double(n)), 1.5 * impact_speed * dt) << "apex " << n;
    }
}

// A box set on the ground stays put: no jitter, no sinking (speed below 1 mm/s, penetration
// below 1 mm after 10 s), and its four bottom corners share its weight.
// Sleeping off: what is checked is the contacts' impulses on a resting box after 10 s, and a box
// at rest that long would be asleep, with no contacts solved (sleep.h; tests/physics/sleep_test.cpp).
TEST(Ground, BoxSetOnTheGroundStaysPut) {
    World world = world_of("{\"sleeping\": false, \"rigid_bodies\": [{\"name\": \"crate\", \"shape\": \"box\", "
                           "\"size\": [1, 0.6, 0.4], \"mass\": 10, \"position\": [0.3, -0.2, 0.2]}]}");
    world.run(500);
    const RigidMotion m = world.rigid_motion(0);
    EXPECT_LT(length(m.v), 1e-3);
    EXPECT_LT(length(m.omega) * 0.6, 1e-3);  // its corners' speed from turning
    EXPECT_LT(0.2 - m.x.z, 1e-3);            // penetration of the bottom face
    EXPECT_LT(m.x.z - 0.2, 1e-6);            // and not floating above it
    EXPECT_LT(std::hypot(m.x.x - 0.3, m.x.y + 0.2), 1e-6);
    ASSERT_EQ(world.contacts().size(), 4u);
    // The four corners carry the weight's impulse of a step, m g h, between them, with no net
    // torque about the centre of mass (how they share it is not unique: three would do). To
    // 1e-9 of m g h: the solver's passes converge on a resting box at once, warm started.
    Vec3d total, torque;
    for (const RigidContact& c : world.contacts()) {
        total += c.normal * c.normal_impulse;
        torque += cross(c.point - m.x, c.normal * c.normal_impulse);
    }
    const double weight_impulse = 10.0 * 9.81f * double(0.02f);
    EXPECT_NEAR(total.z, weight_impulse, 1e-9 * weight_impulse);
    EXPECT_LT(length(torque), 1e-9 * weight_impulse);
}

// A box dropped flat lands on four corners at once; solved together, the impulses cancel each
// other's torques and the box does not start to turn.
TEST(Ground, BoxLandingFlatDoesNotTurn) {
    World world = world_of("{\"restitution\": 0.4, \"rigid_bodies\": [{\"name\": \"crate\", \"shape\": \"box\","
                           " \"size\": [1, 0.6, 0.4], \"mass\": 10, \"position\": [0, 0, 1.0]}]}");
    double fastest_turn = 0.0, highest_after = 0.0;
    bool landed = false;
    for (int t = 0; t < 150; ++t) {
        world.tick();
        const RigidMotion m = world.rigid_motion(0);
        fastest_turn = std::max(fastest_turn, length(m.omega));
        if (!world.contacts().empty()) landed = true;
        if (landed) highest_after = std::max(highest_after, m.x.z);
    }
    ASSERT_TRUE(landed);
    // Symmetric corners, solved together: what the solver's passes leave unbalanced turns it
    // at 4e-6 rad/s at most (measured; its corners at 2 um/s against a 3.7 m/s landing). Each
    // of these faults turned it at 0.01 to 0.3 rad/s and left it rocking: measuring each
    // corner's approach after the others' warm start, bouncing corner by corner at the
    // resting threshold, warm starting from the bounce, four restitution passes instead of ten.
    EXPECT_LT(fastest_turn, 1e-5);
    // It bounced (e = 0.4) and came down again, flat.
    EXPECT_GT(highest_after, 0.2 + 0.01);
}

// --- Springs between bodies (Eq. 21, 22, 33) -------------------------------------------------

// Two boxes joined by a stretched spring between off-centre points, in empty space: the
// forces are equal and opposite along the line of the two points, so the total P and the total
// L about the origin (x x P + L of each) are conserved, while the torques r x F spin both.
TEST(Links, OffCentreSpringConservesMomentumAndSpinsBoth) {
    World world = world_of(
        "{\"gravity\": [0, 0, 0], \"ground\": false, \"rigid_bodies\": ["
        "{\"name\": \"a\", \"shape\": \"box\", \"size\": [0.6, 0.4, 0.2], \"mass\": 2, \"position\": [-2, 0, 0],"
        " \"velocity\": [0.1, 0.2, 0]},"
        "{\"name\": \"b\", \"shape\": \"box\", \"size\": [0.4, 0.4, 0.4], \"mass\": 3, \"position\": [2, 0.5, 0]}],"
        " \"springs\": [{\"a\": {\"body\": \"a\", \"point\": [0.3, 0.2, 0.1]}, \"b\": {\"body\": \"b\", \"point\": [-0.2, 0.1, -0.2]},"
        " \"stiffness\": 30, \"damping\": 0.5, \"rest_length\": 3.0}]}");  // 0.54 m stretched: they never touch
    const Vec3d P0 = world.momentum(), L0 = world.angular_momentum();
    world.run(250);
    ASSERT_EQ(world.status(), Status::Ok);
    // Symplectic Euler conserves both exactly in exact arithmetic (the forces of one
    // evaluation are added to both bodies); rounding of doubles over 250 steps: 1e-12.
    EXPECT_LT(length(world.momentum() - P0), 1e-12);
    EXPECT_LT(length(world.angular_momentum() - L0), 1e-12);
    EXPECT_GT(length(world.rigid_motion(0).omega), 0.1);
    EXPECT_GT(length(world.rigid_motion(1).omega), 0.1);
}

// A rod hanging from a spring at one end starts to turn with angular acceleration tau / J:
// the spring pulls at r from the centre of mass with the torque r x F (Eq. 27, 33).
TEST(Links, SpringAtAPointTurnsTheBodyWithTauOverJ) {
    // A rod 1 m long along x, 1 kg: J about y is m (a^2 + c^2) / 12 with a = 1, c = 0.02.
    // Its end (0.5, 0, 0) is pulled toward (0.5, 0, 1) by k (l - l0) = 10 N upward (l0 = 0).
    World world = world_of(
        "{\"gravity\": [0, 0, 0], \"ground\": false, \"integrator\": \"explicit_euler\", \"auto_substeps\": false,"
        " \"rigid_bodies\": [{\"name\": \"rod\", \"shape\": \"box\", \"size\": [1, 0.02, 0.02], \"mass\": 1}], \"springs\": [{\"a\": {\"point\": "
        "[0.5, 0, 1]}, \"b\": {\"body\": \"rod\", \"point\": [0.5, 0, 0]}, \"stiffness\": 10, \"rest_length\": 0}]}");
    world.tick();
    // Explicit Euler: L after one step is exactly h tau, tau = r x F = (0.5, 0, 0) x (0, 0, 10).
    const double J = (1.0 + 0.0004) / 12.0;
    const RigidMotion m = world.rigid_motion(0);
    const double h = 0.02f;  // the tick as the world holds it: a float
    EXPECT_NEAR(m.L.y, h * -5.0, 1e-15);
    EXPECT_NEAR(m.omega.y, h * -5.0 / J, 1e-12);
    EXPECT_NEAR(m.v.z, h * 10.0, 1e-15);  // and the centre of mass goes up with F / m
}

// A stiff spring between bodies is a mode like the soft body's fastest: its ends oscillate at
// omega^2 = k (1/m_a_eff + 1/m_b_eff), and the explicit step is stable only while h omega < 2.
// The stability estimate counts it, so auto_substeps covers it, and past it the world stops
// with the message that says what to change (exit 3).
TEST(Links, StiffSpringCountsInTheStabilityEstimateAndDivergesWithTheMessage) {
    // A 0.1 kg ball on a spring to a world point through its centre of mass (no turning),
    // stretched 0.1 m past its 0.5 m: omega^2 = k / m = 1e4 / 0.1, h omega = 0.02 x 316 = 6.3,
    // far past 2.
    const auto with = [&](const std::string& keys) {
        return world_of("{\"gravity\": [0, 0, 0], \"ground\": false, " + keys +
                        " \"rigid_bodies\": [{\"name\": \"b\", \"shape\": \"sphere\", \"radius\": 0.05, \"mass\": 0.1,"
                        " \"position\": [0.6, 0, 0]}], \"springs\": [{\"a\": {\"point\": [0, 0, 0]}, \"b\": {\"body\": \"b\"},"
                        " \"stiffness\": 10000, \"rest_length\": 0.5}]}");
    };
    World fixed_step = with("\"auto_substeps\": false,");
    const Stability s = fixed_step.stability();
    EXPECT_NEAR(s.omega_max, std::sqrt(1e4 / 0.1), 1e-9);
    EXPECT_FALSE(s.stable);
    // h omega < 2 with a 12% margin on omega: 316 x 0.02 / n < 2 / 1.118 gives n >= 4.
    EXPECT_EQ(s.substeps_needed, 4);
    fixed_step.run(200);
    EXPECT_EQ(fixed_step.status(), Status::Diverged);
    EXPECT_NE(fixed_step.divergence().find("substeps to at least 4"), std::string::npos) << fixed_step.divergence();
    // With the substeps it asks for, it oscillates for ever without growing. Symplectic Euler
    // keeps x^2 - h x v + v^2 / omega^2 exactly for a linear spring, an ellipse whose reach in x
    // is A / sqrt(1 - (h omega / 2)^2): 0.1 m becomes 0.163 m at h omega = 1.58. To 1e-3 m:
    // the ticks sample the ellipse near, not at, its ends.
    World automatic = with("\"auto_substeps\": true,");
    EXPECT_EQ(automatic.substeps_in_use(), 4);
    const double h_omega = 0.02f / 4.0 * std::sqrt(1e4 / 0.1);
    const double reach = 0.1 / std::sqrt(1.0 - h_omega * h_omega / 4.0);
    double lowest = 1.0, highest = 0.0;
    for (int t = 0; t < 500; ++t) {
        automatic.tick();
        lowest = std::min(lowest, automatic.rigid_motion(0).x.x);
        highest = std::max(highest, automatic.rigid_motion(0).x.x);
    }
    EXPECT_EQ(automatic.status(), Status::Ok);
    EXPECT_NEAR(lowest, 0.5 - reach, 1e-3);
    EXPECT_NEAR(highest, 0.5 + reach, 1e-3);
}

// A fixed body is scenery: gravity, springs and contacts leave it where it is.
TEST(Links, FixedBodyNeverMoves) {
    World world = world_of(
        "{\"rigid_bodies\": [{\"name\": \"post\", \"shape\": \"box\", \"size\": [0.2, 0.2, 2], \"position\": [0, 0, 3],"
        " \"fixed\": true, \"velocity\": [1, 0, 0], \"angular_velocity\": [0, 1, 0]},"
        " {\"name\": \"weight\", \"shape\": \"sphere\", \"radius\": 0.1, \"position\": [1, 0, 4]}],"
        " \"springs\": [{\"a\": {\"body\": \"post\", \"point\": [0, 0, 1]}, \"b\": {\"body\": \"weight\"}, \"stiffness\": 50}]}");
    world.run(200);
    const RigidMotion m = world.rigid_motion(0);
    EXPECT_EQ(m.x, (Vec3d{0, 0, 3}));
    EXPECT_EQ(m.q, Quat{});
    EXPECT_EQ(m.P, Vec3d{});
    EXPECT_EQ(m.L, Vec3d{});
    EXPECT_GT(length(world.rigid_motion(1).v), 0.1);  // the weight swings
}

// --- Determinism -----------------------------------------------------------------------------

// A mixed scene (a soft body of more than two kernel blocks, rigid bodies on the ground, a
// spring between a rigid body and a particle) gives the same bits at any thread count.
TEST(RigidDeterminism, MixedSceneHashIsTheSameAtAnyThreadCount) {
    const std::string scene =
        "{\"stiffness\": 5, \"initial_velocity\": [0.3, 0, 0], \"rigid_bodies\": ["
        "{\"name\": \"crate\", \"shape\": \"box\", \"size\": [0.5, 0.5, 0.5], \"position\": [3, 0, 1], \"rotation\": [10, 20, 30],"
        " \"angular_velocity\": [1, 2, 3]},"
        "{\"name\": \"drum\", \"shape\": \"cylinder\", \"radius\": 0.3, \"height\": 0.5, \"position\": [-3, 0, 1], \"velocity\": [0, 1, 2]}],"
        " \"springs\": [{\"a\": {\"body\": \"crate\", \"point\": [0.25, 0, 0]}, \"b\": {\"body\": \"body\", \"vertex\": 7},"
        " \"stiffness\": 20, \"damping\": 0.2}]}";
    const auto hash_after = [&](int threads) {
        // The scene's rigid bodies, and a soft body of 550 random points (three kernel blocks).
        WorldDef def = (parse_scene(scene, "mixed.json"));
        def.soft_bodies.push_back(flat_body_of(scene, points(random_cloud(550, 31, 1.5f))));
        World world(std::move(def), WorldOptions{threads});
        world.run(150);
        EXPECT_EQ(world.status(), Status::Ok);
        return world.state_hash();
    };
    const std::uint64_t one = hash_after(1);
    EXPECT_EQ(one, hash_after(2));
    EXPECT_EQ(one, hash_after(3));
    EXPECT_EQ(one, hash_after(1));
}

// The hash covers the rigid bodies: a change of one part in 1e15 in one initial velocity shows.
TEST(RigidDeterminism, HashSeesTheRigidState) {
    const auto hash_of = [](const char* vz) {
        World world = world_of(std::string("{\"rigid_bodies\": [{\"name\": \"b\", \"shape\": \"sphere\", \"radius\": 0.2,"
                                           " \"position\": [0, 0, 1], \"velocity\": [0, 0, ") + vz + "]}]}");
        world.run(10);
        return world.state_hash();
    };
    EXPECT_NE(hash_of("1.0"), hash_of("1.000000000000001"));
}

}  // namespace
}  // namespace softbody::test

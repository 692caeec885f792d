// Contacts on scenes nobody tuned (contact_solver.h): under every integrator nothing explodes
// and contacts never add energy; bounces turn at the surface; overlaps are pushed apart
// gently; thin, small, dense and fast bodies neither tunnel nor gain energy; and a fuzzer of
// seeded random scenes (random:SEED, physics/generated.h) checks all of it by the hundred.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "physics/generated.h"
#include "physics/scene_io.h"
#include "test_support.h"

namespace softbody::test {
namespace {

std::string with_integrator(std::string json, const char* integrator) {
    return "{\"integrator\": \"" + std::string(integrator) + "\", " + json.substr(1);
}

// The scale of a world's energy: what is in play (kinetic, and weight times height above the
// ground), for tolerances relative to it.
double energy_scale(World& world) {
    const Energy e = world.energy();
    return e.kinetic + std::abs(e.gravity) + e.elastic;
}

// --- Every integrator -------------------------------------------------------------------------

// The two bodies: a flat cylinder (radius 0.207 m, height 0.092 m, 484 kg/m^3) at
// 15.4 m/s into a spinning 0.84 x 0.74 x 0.93 m box (4,732 kg/m^3) in the air. RK4 diverged in
// tick 28 and explicit Euler in tick 22 when contacts were solved inside their stages; verlet
// and symplectic Euler ran it. Now all four run 10 s, and the three that keep energy in free
// flight never end a tick with more than they started with. Tolerance: 1e-6 of the energy in
// play, RK4's own error in free rotation at the substeps it takes (h w <= 0.1 rad: about 1e-7 a
// step); explicit Euler gains in free rotation by itself (Listing 9), so only its run is checked.
const char* const kCylinderIntoBox =
    "{\"rigid_bodies\": ["
    "{\"name\": \"coin\", \"shape\": \"cylinder\", \"radius\": 0.207, \"height\": 0.092, \"density\": 484,"
    " \"position\": [-1.6, 0.05, 3.0], \"rotation\": [80, 0, 0], \"velocity\": [15.4, 0, 0]},"
    "{\"name\": \"box\", \"shape\": \"box\", \"size\": [0.84, 0.74, 0.93], \"density\": 4732,"
    " \"position\": [0, 0, 3.0], \"angular_velocity\": [2, -3, 4]}]}";

TEST(EveryIntegrator, CylinderIntoASpinningBoxRunsAndNeverGainsEnergy) {
    for (const char* integrator : kIntegrators) {
        World world = world_of(with_integrator(kCylinderIntoBox, integrator));
        const double E0 = world.energy().total(), tolerance = 1e-6 * energy_scale(world);
        bool hit = false;
        double highest = -1e300;
        for (int t = 0; t < 500; ++t) {
            world.tick();
            ASSERT_EQ(world.status(), Status::Ok) << integrator << " tick " << t << ": " << world.divergence();
            hit = hit || std::abs(world.rigid_motion(1).v.x) > 0.1;  // only the cylinder pushes it along x
            highest = std::max(highest, world.energy().total() - E0);
        }
        EXPECT_TRUE(hit) << integrator << ": the cylinder should hit the box";
        if (keeps_energy(integrator)) {
            EXPECT_LE(highest, tolerance) << integrator;
        }
    }
}

// --- Bounces at the surface -------------------------------------------------------------------

struct Bounce {
    double lowest = 1e300;  // lowest gap between the ball and the surface at a tick's end, m
    double leave = 0.0;     // its speed the tick after it turned, m/s
    double apex = -1e300;   // the highest gap after it turned, m
};

// A ball of radius r and density rho thrown straight down at v onto the ground (surface at 0) or
// onto a fixed slab (its top at 1 m), its centre starting `gap` above touching.
Bounce drop(const char* integrator, bool slab, double r, double density, double v, double gap, double e) {
    const double surface = slab ? 1.0 : 0.0;
    char json[1024];
    std::snprintf(json, sizeof json,
                  "{\"integrator\": \"%s\", \"restitution\": %g, \"ground\": %s, \"rigid_bodies\": ["
                  "{\"name\": \"ball\", \"shape\": \"sphere\", \"radius\": %.17g, \"density\": %g, \"position\": [0, 0, %.17g],"
                  " \"velocity\": [0, 0, %g]}%s]}",
                  integrator, e, slab ? "false" : "true", r, density, surface + r + gap, -v,
                  slab ? ", {\"name\": \"slab\", \"shape\": \"box\", \"size\": [2, 2, 0.005], \"fixed\": true,"
                         " \"position\": [0, 0, 0.9975]}"
                       : "");
    World world = world_of(json);
    Bounce out;
    bool turned = false;
    for (int t = 0; t < 1000 && world.status() == Status::Ok; ++t) {
        world.tick();
        const RigidMotion m = world.rigid_motion(0);
        const double above = m.x.z - r - surface;
        if (!turned) {
            out.lowest = std::min(out.lowest, above);
            if (m.v.z > 0.0) {
                turned = true;
                out.leave = m.v.z;
            }
        } else {
            out.apex = std::max(out.apex, above);
            if (m.v.z < 0.0) break;
        }
    }
    return out;
}

// The same ball launched up from touching at speed u with nothing under it: the apex the
// integrator's own free flight gives (symplectic Euler's runs u h / 2 low at a tick of h,
// explicit Euler's as high; RK4's is exact): what a bounce at the surface at u must reach.
double flight_apex(const char* integrator, double u) {
    char json[512];
    std::snprintf(json, sizeof json,
                  "{\"integrator\": \"%s\", \"ground\": false, \"rigid_bodies\": ["
                  "{\"name\": \"ball\", \"shape\": \"sphere\", \"radius\": 0.05, \"mass\": 1, \"velocity\": [0, 0, %.17g]}]}",
                  integrator, u);
    World world = world_of(json);
    double apex = 0.0;
    for (int t = 0; t < 1000; ++t) {
        world.tick();
        if (world.rigid_motion(0).v.z < 0.0) break;
        apex = std::max(apex, world.rigid_motion(0).x.z);
    }
    return apex;
}

// Balls at 3 to 20 m/s onto the ground and onto a 5 mm slab, started so that the last tick
// before contact leaves gaps from 0 to 3/4 of a tick's travel: at every tick's end the centre
// is never more than 1 mm below touching, and the ball turns back within 1 mm of it (it bounced
// at the surface, not above it: before, verlet turned a 0.1 m ball 5.6 mm up at 3 m/s and 37 mm
// at 10 m/s). It leaves at e times the speed it met the surface with, sqrt(v^2 + 2 g gap) (to
// 5%), and its apex is within 5% of the height the same integrator carries a ball launched from
// the surface at that speed.
TEST(BouncesAtTheSurface, BallsTurnWithinAMillimetreOfTouchingAndLeaveAtE) {
    const double e = 0.8, g = 9.81f;
    for (const char* integrator : kIntegrators) {
        for (const bool slab : {false, true}) {
            for (const double v : {3.0, 5.0, 7.0, 10.0, 20.0}) {
                for (int phase = 0; phase < 4; ++phase) {
                    const double gap = 0.3 + v * 0.02 * phase / 4.0;
                    const Bounce b = drop(integrator, slab, 0.05, 1000.0, v, gap, e);
                    const std::string what = std::string(integrator) + (slab ? " slab " : " ground ") + std::to_string(v) +
                                             " m/s, phase " + std::to_string(phase);
                    EXPECT_GT(b.lowest, -1e-3) << what;
                    EXPECT_LT(b.lowest, 1e-3) << what;
                    const double arrive = std::sqrt(v * v + 2.0 * g * gap);
                    EXPECT_NEAR(b.leave, e * arrive, 0.05 * e * arrive) << what;
                    const double want = flight_apex(integrator, e * arrive);
                    EXPECT_NEAR(b.apex, want, 0.05 * want) << what;
                }
            }
        }
    }
}

// A 1 cm steel ball (7,800 kg/m^3) at 20 m/s onto a 5 mm fixed plate, e = 1: it touches the
// plate before it turns (within 1 mm), never passes through it, and leaves no faster than it
// arrived, under each integrator.
TEST(BouncesAtTheSurface, SteelBallAtTwentyMetresASecondTouchesAThinPlateAndLeavesNoFaster) {
    for (const char* integrator : kIntegrators) {
        for (int phase = 0; phase < 4; ++phase) {
            const double gap = 0.2 + 20.0 * 0.02 * phase / 4.0;
            const Bounce b = drop(integrator, true, 0.005, 7800.0, 20.0, gap, 1.0);
            const std::string what = std::string(integrator) + ", phase " + std::to_string(phase);
            EXPECT_GT(b.lowest, -1e-3) << what;  // not into the plate, let alone through it
            EXPECT_LT(b.lowest, 1e-3) << what;
            const double arrive = std::sqrt(20.0 * 20.0 + 2.0 * 9.81 * gap);
            EXPECT_LE(b.leave, arrive * (1.0 + 1e-9)) << what;
            EXPECT_GT(b.leave, 0.95 * arrive) << what;  // and it did bounce, e = 1
        }
    }
}

// --- Overlaps pushed apart gently -------------------------------------------------------------

// Two unit boxes spawned half inside each other, in the air without gravity: they come apart at
// no more than the solver's push speed (1 m/s, ContactSettings::push_speed) between them, and
// are left at rest (the relax takes the push's velocity back): not launched.
TEST(Overlaps, BoxesSpawnedHalfInsideEachOtherSeparateAtAtMostTheSpeedOfThePush) {
    for (const char* integrator : kIntegrators) {
        World world = world_of(with_integrator(
            "{\"gravity\": [0, 0, 0], \"ground\": false, \"rigid_bodies\": ["
            "{\"name\": \"a\", \"shape\": \"box\", \"size\": [1, 1, 1], \"mass\": 10, \"position\": [0, 0, 0]},"
            "{\"name\": \"b\", \"shape\": \"box\", \"size\": [1, 1, 1], \"mass\": 10, \"position\": [0.5, 0.1, 0]}]}",
            integrator));
        double fastest = 0.0;
        for (int t = 0; t < 250; ++t) {
            world.tick();
            ASSERT_EQ(world.status(), Status::Ok) << integrator;
            fastest = std::max(fastest, length(world.rigid_motion(1).v - world.rigid_motion(0).v));
        }
        EXPECT_LE(fastest, 1.0 + 1e-9) << integrator;
        // Apart (within the push's last step: the push, off their centres in y, also turned them
        // a little, so their faces meet at a tilt), and at rest.
        for (const RigidContact& c : world.contacts()) EXPECT_GT(c.separation, -1e-3) << integrator;
        EXPECT_LT(length(world.rigid_motion(1).v - world.rigid_motion(0).v), 1e-3) << integrator;
        EXPECT_LT(length(world.rigid_motion(1).omega - world.rigid_motion(0).omega), 1e-3) << integrator;
    }
}

// --- Thin, small, dense and fast --------------------------------------------------------------

// A coin (2 mm thick, 1 cm across), a pencil (15 cm by 7 mm) and a 1 cm ball of lead, each
// thrown at 20 m/s, spinning, at a 5 mm fixed plate, e = 1: none passes through it (every
// tick's end above it while over it), and under each integrator that keeps energy in free
// flight none leaves faster than the energy it brought allows and the world's energy never
// rises. (Spin thrown into sideways motion carries some off the plate's edge: the plate is wide.)
TEST(ThinSmallDenseFast, CoinPencilAndLeadBallDoNotTunnelNorGainEnergy) {
    const char* const bodies[] = {
        "{\"name\": \"coin\", \"shape\": \"cylinder\", \"radius\": 0.005, \"height\": 0.002, \"density\": 8900,"
        " \"rotation\": [30, 10, 0], \"angular_velocity\": [20, 5, 0]",
        "{\"name\": \"pencil\", \"shape\": \"box\", \"size\": [0.15, 0.007, 0.007], \"density\": 600,"
        " \"rotation\": [0, 40, 20], \"angular_velocity\": [0, 20, 3]",
        "{\"name\": \"lead\", \"shape\": \"sphere\", \"radius\": 0.005, \"density\": 11340, \"angular_velocity\": [0, 20, 0]",
    };
    for (const char* integrator : kIntegrators) {
        for (const char* body : bodies) {
            const std::string json = "{\"integrator\": \"" + std::string(integrator) +
                                     "\", \"restitution\": 1, \"ground\": false, \"rigid_bodies\": [" + body +
                                     ", \"position\": [0, 0, 1.5], \"velocity\": [1, 0, -20]},"
                                     "{\"name\": \"plate\", \"shape\": \"box\", \"size\": [20, 20, 0.005], \"fixed\": true,"
                                     " \"position\": [0, 0, 0.9975]}]}";
            World world = world_of(json);
            const double E0 = world.energy().total(), tolerance = 1e-6 * energy_scale(world);
            const double most = std::sqrt(2.0 * (world.energy().kinetic + world.rigid_body(0).mass * 9.81 * 1.5) /
                                          world.rigid_body(0).mass);
            double highest = -1e300;
            for (int t = 0; t < 100; ++t) {
                world.tick();
                if (!keeps_energy(integrator) && world.status() != Status::Ok) {
                    // Explicit Euler spins the pencil up by itself in free flight (Listing 9)
                    // until it diverges: reported, with the last good state kept.
                    EXPECT_FALSE(world.divergence().empty()) << integrator << " " << body;
                    break;
                }
                ASSERT_EQ(world.status(), Status::Ok) << integrator << " " << body;
                const Vec3d x = world.rigid_motion(0).x;
                if (std::abs(x.x) < 10.0 && std::abs(x.y) < 10.0) {  // over the plate (spin throws it sideways)
                    EXPECT_GT(x.z, 1.0) << integrator << " " << body << " tick " << t;
                }
                highest = std::max(highest, world.energy().total() - E0);
                if (keeps_energy(integrator)) {
                    EXPECT_LE(length(world.rigid_motion(0).v), most) << integrator << " " << body;
                }
            }
            if (keeps_energy(integrator)) {
                EXPECT_LE(highest, tolerance) << integrator << " " << body;
            }
        }
    }
}

// --- Contacts found again only for bodies with contacts --------------------------------------

// A box spinning at 30 rad/s high in the air, 10 m from a crate sliding to rest on the ground:
// it turns 0.6 rad a tick, but meets nothing within its margin, so nothing need be found again
// within the tick (World::contact_intervals). The crate's contacts are found once a tick as they
// would be alone: its state, bit for bit, that of the crate alone, tick after tick.
TEST(FastTurns, ABoxSpinningInTheAirLeavesAnotherBodysContactsAlone) {
    const std::string crate = "{\"name\": \"crate\", \"shape\": \"box\", \"size\": [1, 0.6, 0.4], \"mass\": 10,"
                              " \"position\": [0, 0, 0.2], \"velocity\": [1.5, 0.5, 0], \"angular_velocity\": [0, 0, 2]}";
    World alone = world_of("{\"rigid_bodies\": [" + crate + "]}");
    World both = world_of("{\"rigid_bodies\": [" + crate +
                          ", {\"name\": \"spinner\", \"shape\": \"box\", \"size\": [0.5, 0.3, 0.1], \"mass\": 3,"
                          " \"position\": [10, 0, 30], \"angular_velocity\": [30, 10, 5]}]}");
    for (int t = 0; t < 60; ++t) {
        alone.tick();
        both.tick();
        ASSERT_GT(length(both.rigid_motion(1).omega), 20.0);  // still spinning fast, still in the air
        ASSERT_GT(both.rigid_motion(1).x.z, 5.0);
        for (int k = 0; k < rigid::kStateSize; ++k) {
            ASSERT_EQ(both.rigid_state(0)[k], alone.rigid_state(0)[k]) << "tick " << t << ", state " << k;
        }
    }
    EXPECT_LT(length(alone.rigid_motion(0).v), 0.01);  // the crate came to rest on the ground
}

// How often a spinning body's contacts are found: once a tick while it turns no more than its
// shape allows in the tick (CollisionShape::contact_turn), else in as many parts as that takes,
// each found where the last left it: ceil(w dt / turn). A 40 cm cube standing on the ground,
// spinning about the vertical on friction 0 (nothing slows it), may turn 0.2 rad: at 8, 12 and
// 27 rad/s it turns 0.16, 0.24 and 0.54 rad a tick. A cylinder (32 sides) may turn 0.1 rad.
TEST(FastTurns, ContactsFoundAgainOnlyPastTheShapesTurn) {
    const auto finds = [](const std::string& body, int spin) {
        World world = world_of("{\"rigid_bodies\": [{\"name\": \"b\", " + body +
                               ", \"mass\": 5, \"friction\": 0, \"angular_velocity\": [0, 0, " + std::to_string(spin) + "]}]}");
        world.tick();
        world.tick();
        EXPECT_NEAR(world.rigid_motion(0).omega.z, spin, 1e-9 * spin);
        return world.contact_finds();
    };
    const std::string cube = "\"shape\": \"box\", \"size\": [0.4, 0.4, 0.4], \"position\": [0, 0, 0.2]";
    const std::string cylinder = "\"shape\": \"cylinder\", \"radius\": 0.2, \"height\": 0.4, \"position\": [0, 0, 0.2]";
    EXPECT_EQ(finds(cube, 8), 1);
    EXPECT_EQ(finds(cube, 12), 2);
    EXPECT_EQ(finds(cube, 27), 3);
    EXPECT_EQ(finds(cylinder, 4), 1);
    EXPECT_EQ(finds(cylinder, 8), 2);
    EXPECT_EQ(finds(cylinder, 27), 6);
}

// --- What contacts do to the energy, shown ----------------------------------------------------

// A box resting on the ground: its contacts do no work (the gravity a substep brings, the contact
// takes back: contact_solver.h). A ball bouncing with e = 0.5: over its first bounce the contacts
// take 1 - e^2 of the kinetic energy it met the ground with; and never give more than they took.
TEST(ContactEnergy, RestingContactDoesNoWorkAndABounceTakesOneMinusESquared) {
    World rest = world_of("{\"rigid_bodies\": [{\"name\": \"crate\", \"shape\": \"box\", \"size\": [1, 0.6, 0.4],"
                          " \"mass\": 10, \"position\": [0, 0, 0.2]}]}");
    rest.run(50);  // settled
    double work = 0.0;
    for (int t = 0; t < 100; ++t) {
        rest.tick();
        work += rest.contact_energy().total;
    }
    EXPECT_NEAR(work, 0.0, 1e-6);

    World ball = world_of("{\"restitution\": 0.5, \"integrator\": \"rk4\", \"rigid_bodies\": [{\"name\": \"ball\","
                          " \"shape\": \"sphere\", \"radius\": 0.1, \"mass\": 2, \"position\": [0, 0, 1.1]}]}");
    double taken = 0.0, restitution = 0.0;
    for (int t = 0; t < 40; ++t) {  // down 1 m (0.45 s) and back up part of the way
        ball.tick();
        taken += ball.contact_energy().total;
        restitution += ball.contact_energy().restitution;
    }
    const double met = 2.0 * 9.81 * 1.0;  // m g h: 1/2 m v^2 at the ground
    EXPECT_NEAR(taken, -(1.0 - 0.25) * met, 0.01 * met);
    EXPECT_NEAR(restitution, 0.25 * met, 0.01 * met);  // what the bounce gave back: e^2 of it
}

// --- The fuzzer -------------------------------------------------------------------------------

// Seeded random scenes (random:SEED: two to eight boxes, balls and cylinders 5 cm to 5 m, 100
// to 20,000 kg/m^3, thrown at up to 20 m/s and spun at up to 20 rad/s, restitution 0 to 1 (a
// quarter exactly 1), friction 0 to 2, up to three fixed obstacles in the air), a fixed seed
// range so every machine runs the same, 5 s each under verlet, symplectic Euler and RK4:
//   - no divergence;
//   - no body faster than the scene's energy can make it: sqrt(2 E / m), E the kinetic energy at
//     the start plus every body's weight times its height above the ground (its start speed
//     plus free fall, and what any other body could hand it: a light ball struck by a heavy box
//     may leave faster than either started, as Eq. 38 says it should);
//   - the total energy, checked at every tick's end, never above its start by more than 1e-6
//     of the energy in play (1e-5 under RK4: its own error in free rotation, at h w <= 0.1 rad a
//     substep, swings the energy by up to 1.5e-6 of it in flight, measured over 800 seeds).
// Explicit Euler gains energy in free rotation by itself: for it, only that it runs or stops
// with a divergence in one line (the CLI test checks the exit code 3).
// Under the sanitizers (six to eight times slower: 60 s for the first 20) only those 20 seeds:
// there they look for memory errors in the same code; the plain build runs all 200.
TEST(ContactFuzz, RandomScenesNeverDivergeNorGainEnergy) {
    constexpr int kSeeds = SOFTBODY_CONTACT_FUZZ_SEEDS;
    int failures = 0;
    for (int seed = 1; seed <= kSeeds; ++seed) {
        for (const char* integrator : kIntegrators) {
            Scene scene = generated_scene("random:" + std::to_string(seed));
            scene.settings.integrator = *integrator_from_string(integrator);
            World world((scene));
            const std::string what = "random:" + std::to_string(seed) + " " + integrator;
            if (!keeps_energy(integrator)) {
                world.run(250);
                if (world.status() != Status::Ok) {
                    EXPECT_EQ(world.divergence().find('\n'), std::string::npos) << what;
                    EXPECT_FALSE(world.divergence().empty()) << what;
                }
                continue;
            }
            const Energy e0 = world.energy();
            const double E0 = e0.total(), tolerance = (integrator == std::string("rk4") ? 1e-5 : 1e-6) * energy_scale(world);
            double budget = e0.kinetic;  // energy any one body could end up with (ground at 0)
            for (std::size_t b = 0; b < world.rigid_body_count(); ++b) {
                if (!world.rigid_body(b).fixed) budget += world.rigid_body(b).mass * 9.81 * world.rigid_motion(b).x.z;
            }
            for (int t = 0; t < 250; ++t) {
                world.tick();
                if (world.status() != Status::Ok) {
                    ADD_FAILURE() << what << ": " << world.divergence();
                    ++failures;
                    break;
                }
                const double rise = world.energy().total() - E0;
                if (rise > tolerance) {
                    ADD_FAILURE() << what << ": the energy rose by " << rise << " J at tick " << t;
                    ++failures;
                    break;
                }
                bool fast = false;
                for (std::size_t b = 0; b < world.rigid_body_count() && !fast; ++b) {
                    const RigidBody& body = world.rigid_body(b);
                    if (body.fixed) continue;
                    const double most = std::sqrt(2.0 * budget / body.mass) * (1.0 + 1e-9);
                    if (length(world.rigid_motion(b).v) > most) {
                        ADD_FAILURE() << what << ": '" << body.name << "' at " << length(world.rigid_motion(b).v)
                                      << " m/s, more than the scene's energy allows (" << most << ") at tick " << t;
                        fast = true;
                    }
                }
                if (fast) {
                    ++failures;
                    break;
                }
            }
        }
    }
    EXPECT_EQ(failures, 0);
}

}  // namespace
}  // namespace softbody::test

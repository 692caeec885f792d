// Determinism: the same run gives the same bits, whatever the number of threads. The mesh has
// more than two blocks of PairForceKernel::kBlock particles, so the pair loop is cut into six
// tiles that threads share out differently from run to run, and each particle's force is a sum
// of three tiles' partial forces: enough terms for a change in the order of summation to show
// in the bits (two terms add the same either way).
#include <cmath>

#include "physics/generated.h"
#include "physics/pair_forces.h"
#include "physics/scene_io.h"
#include "test_support.h"

namespace softbody::test {
namespace {

constexpr std::size_t kParticles = 550;  // three blocks of 256: six tiles

// Listing 8's constants with the ground, friction and drag (every code path), but half the
// stiffness: N (k h^2 + 2 c h) = 3.3 < 4 m keeps 550 particles stable at one substep.
FlatKeys determinism_params() {
    FlatKeys p = listing8_params();
    p.stiffness = 5.0f;
    p.initial_velocity = {0.7f, -0.4f, 0.0f};
    return p;
}

std::uint64_t hash_after(int threads, int ticks) {
    static_assert(kParticles > 2 * PairForceKernel::kBlock);
    OneBodyWorld world(determinism_params(), points(random_cloud(kParticles, 31, 1.5f)), WorldOptions{threads});
    world.run(std::uint64_t(ticks));
    EXPECT_EQ(world.status(), Status::Ok);
    EXPECT_EQ(world.ticks(), std::uint64_t(ticks));
    return world.state_hash();
}

TEST(Determinism, SameHashTwice) {
    // Bit-for-bit: no tolerance. Floating point is deterministic for the same operations in
    // the same order; anything else (uninitialised memory, a race, an unordered sum) shows.
    EXPECT_EQ(hash_after(1, 150), hash_after(1, 150));
    EXPECT_EQ(hash_after(2, 150), hash_after(2, 150));
}

TEST(Determinism, SameHashAtOneAndTwoThreads) {
    const std::uint64_t one = hash_after(1, 150);
    EXPECT_EQ(one, hash_after(2, 150));
    EXPECT_EQ(one, hash_after(3, 150));
}

TEST(Determinism, HashSeesTheState) {
    // The hash must change as the state does, or the tests above prove nothing: one tick more,
    // one position one ulp away, or one velocity slightly different.
    EXPECT_NE(hash_after(1, 149), hash_after(1, 150));
    const std::vector<Vec3> cloud = random_cloud(10, 5);
    std::vector<Vec3> moved = cloud;
    moved[7].y = std::nextafter(moved[7].y, 10.0f);
    FlatKeys p = determinism_params();
    const OneBodyWorld a(p, points(cloud)), b(p, points(moved));
    p.initial_velocity.z += 1e-3f;
    const OneBodyWorld c(p, points(cloud));
    EXPECT_NE(a.state_hash(), b.state_hash());
    EXPECT_NE(a.state_hash(), c.state_hash());
}

TEST(Determinism, ChangingThreadsMidRunKeepsTheHash) {
    const FlatKeys p = determinism_params();
    const Mesh mesh = points(random_cloud(kParticles, 31, 1.5f));
    OneBodyWorld a(p, mesh, WorldOptions{1});
    OneBodyWorld b(p, mesh, WorldOptions{2});
    a.run(75);
    b.run(75);
    b.set_threads(1);
    a.set_threads(2);
    a.run(75);
    b.run(75);
    EXPECT_EQ(a.state_hash(), b.state_hash());
    EXPECT_EQ(a.state_hash(), hash_after(1, 150));
}

// Rigid bodies: the contact solver's slabs, each body's free step, the broad phase and the
// narrow phase share the threads (physics/README.md, "Contacts on both cores"). 600 boxes and balls piling
// into their bin for 1.5 s, some 900 to 1,000 contact points: hundreds of manifolds, past what one
// thread keeps to itself (kManifoldGrain a slab), so every thread count splits the work
// differently; and a pyramid at rest.
std::uint64_t rigid_hash_after(const char* scene, int threads, int ticks, std::size_t* contacts = nullptr) {
    World world((generated_scene(scene)), WorldOptions{threads});
    world.run(std::uint64_t(ticks));
    EXPECT_EQ(world.status(), Status::Ok);
    if (contacts) *contacts = world.contacts().size();
    return world.state_hash();
}

TEST(Determinism, RigidPileAndPyramidSameHashAtOneTwoAndThreeThreads) {
    std::size_t contacts = 0;
    const std::uint64_t pile = rigid_hash_after("boxes:600", 1, 75, &contacts);
    EXPECT_GT(contacts, 16u * 3u * 8u);  // busy: at 3 threads, several slabs of kManifoldGrain (16) each
    EXPECT_EQ(pile, rigid_hash_after("boxes:600", 2, 75));
    EXPECT_EQ(pile, rigid_hash_after("boxes:600", 3, 75));
    const std::uint64_t pyramid = rigid_hash_after("pyramid:10", 1, 20);
    EXPECT_EQ(pyramid, rigid_hash_after("pyramid:10", 2, 20));
    EXPECT_EQ(pyramid, rigid_hash_after("pyramid:10", 3, 20));
}

}  // namespace
}  // namespace softbody::test

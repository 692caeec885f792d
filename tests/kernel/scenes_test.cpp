// The generated bodies the bench times and the app opens by name (physics/generated.h): the
// torus and the lattice are what their names say, and a generated scene simulates every
// particle its name asks for, so `--scene cloud:5000` is the body `softbody bench` measures.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "physics/error.h"
#include "physics/generated.h"
#include "physics/scene_io.h"
#include "physics/world.h"

namespace softbody::test {
namespace {

TEST(GeneratedBodies, TorusHasRingsTimesSegmentsParticlesOnItsTube) {
    const Mesh torus = generated_mesh("torus:12x7");
    ASSERT_EQ(torus.particle_count(), 84u);
    EXPECT_EQ(torus.triangle_count(), 2u * 84u);  // closed: two triangles per quad, no border
    for (const Vec3& p : torus.positions) {
        // Distance from the centre line (the circle of radius 0.5 m in the xy plane) is the tube's 0.2 m.
        const float from_axis = std::sqrt(p.x * p.x + p.y * p.y);
        EXPECT_NEAR(std::hypot(from_axis - 0.5f, p.z), 0.2f, 1e-6f);
    }
    EXPECT_TRUE(is_generated("torus:100x100"));
    EXPECT_EQ(open_mesh("torus:12x7").positions, torus.positions);  // by name, from anywhere
}

TEST(GeneratedBodies, LatticeIsACubeOfGridPoints) {
    const Mesh lattice = generated_mesh("lattice:5");
    ASSERT_EQ(lattice.particle_count(), 125u);
    EXPECT_EQ(lattice.triangle_count(), 0u);
    for (const Vec3& p : lattice.positions) {
        for (float c : {p.x, p.y, p.z}) {
            EXPECT_LE(std::abs(c), 0.5f);
            EXPECT_NEAR(c * 4.0f, std::round(c * 4.0f), 1e-5f);  // on the 0.25 m grid
        }
    }
}

TEST(GeneratedBodies, BadTorusAndLatticeNamesAreRefused) {
    for (const char* name : {"torus:12", "torus:2x10", "torus:10x", "torus:axb", "lattice:1", "lattice:74"}) {
        EXPECT_THROW(generated_mesh(name), InputError) << name;
        EXPECT_THROW(load_scene(name), InputError) << name;
    }
}

// Above the default particle budget (3,000), a generated scene still simulates all of it.
TEST(GeneratedBodies, AGeneratedSceneSimulatesEveryParticle) {
    const Scene scene = load_scene("cloud:3100");
    EXPECT_TRUE(scene.settings.auto_substeps);
    World world((scene));
    EXPECT_EQ(world.soft_body(0).particle_count(), 3100u);
    const Scene torus = load_scene("torus:20x10");
    EXPECT_EQ(World(torus).soft_body(0).particle_count(), 200u);
}

}  // namespace
}  // namespace softbody::test

// Rigid bodies, springs and more soft bodies in scene files: what each key does, what a file
// that is wrong gets told (one line naming the body and the key), `--set NAME.KEY`, and saving
// a scene keeps every body.
#include <cmath>

#include "physics/error.h"
#include "physics/scene_io.h"
#include "test_support.h"

namespace softbody::test {
namespace {

// The scene, its rigid bodies made as a world makes them (what they refuse, refused here).
WorldDef def_of(const std::string& json, const std::string& origin = "scene.json") {
    WorldDef def = parse_scene(json, origin);
    for (const RigidBodyDef& body : def.rigid_bodies) (void)make_rigid_body(body);
    return def;
}

std::string one_body(const std::string& keys) {
    return "{\"rigid_bodies\": [{\"name\": \"crate\", " + keys + "}]}";
}

// --- What the keys make ------------------------------------------------------------------------

TEST(RigidScene, PrimitivesGetTableOneMassProperties) {
    // Density 1000 by default: a 1 x 2 x 0.5 box is 1 m^3, 1000 kg; Table 1: J_xx = m (b^2 + c^2) / 12.
    const WorldDef box = def_of(one_body("\"shape\": \"box\", \"size\": [1, 2, 0.5]"));
    ASSERT_EQ(box.rigid_bodies.size(), 1u);
    const RigidBody b = make_rigid_body(box.rigid_bodies[0]);
    EXPECT_NEAR(b.mass, 1000.0, 1e-9);
    EXPECT_NEAR(b.J_body.m[0][0], 1000.0 * (4.0 + 0.25) / 12.0, 1e-9);
    EXPECT_NEAR(b.J_body.m[1][1], 1000.0 * (1.0 + 0.25) / 12.0, 1e-9);
    EXPECT_NEAR(b.J_body.m[2][2], 1000.0 * (1.0 + 4.0) / 12.0, 1e-9);
    EXPECT_NEAR(b.J_body.m[0][1], 0.0, 1e-12);
    // "mass" instead: the same shape of tensor, scaled.
    const WorldDef sphere = def_of(one_body("\"shape\": \"sphere\", \"radius\": 0.5, \"mass\": 3"));
    const RigidBody s = make_rigid_body(sphere.rigid_bodies[0]);
    EXPECT_DOUBLE_EQ(s.mass, 3.0);
    EXPECT_NEAR(s.J_body.m[1][1], 0.4 * 3.0 * 0.25, 1e-12);  // 2/5 m r^2
    // A cylinder's axis is its z.
    const WorldDef cylinder = def_of(one_body("\"shape\": \"cylinder\", \"radius\": 0.2, \"height\": 1, \"mass\": 2"));
    const RigidBody c = make_rigid_body(cylinder.rigid_bodies[0]);
    EXPECT_NEAR(c.J_body.m[2][2], 0.5 * 2.0 * 0.04, 1e-12);
    EXPECT_NEAR(c.J_body.m[0][0], 2.0 * (3.0 * 0.04 + 1.0) / 12.0, 1e-12);
}

TEST(RigidScene, PositionOrientationAndVelocitiesSetTheThirteenNumbers) {
    const WorldDef def = def_of(one_body("\"shape\": \"box\", \"size\": [1, 1, 1], \"mass\": 2, \"position\": [1, 2, 3],"
                                         " \"rotation\": [0, 0, 90], \"velocity\": [0.5, 0, 0], \"angular_velocity\": [0, 0, 3]"));
    const auto s = make_rigid_body(def.rigid_bodies[0]).initial;
    EXPECT_DOUBLE_EQ(s[rigid::X + 2], 3.0);
    EXPECT_DOUBLE_EQ(s[rigid::P], 1.0);  // m v
    // A unit cube's J = m / 6 on each axis, so L = J w = (0, 0, 1) whatever the orientation.
    EXPECT_NEAR(s[rigid::L + 2], 2.0 / 6.0 * 3.0, 1e-12);
    // 90 degrees about z: q = (cos 45, 0, 0, sin 45).
    EXPECT_NEAR(s[rigid::Q], std::sqrt(0.5), 1e-12);
    EXPECT_NEAR(s[rigid::Q + 3], std::sqrt(0.5), 1e-12);
}

TEST(RigidScene, NonUnitQuaternionIsNormalisedAndSaidSo) {
    World world(def_of(one_body("\"shape\": \"sphere\", \"radius\": 1, \"orientation\": [2, 0, 0, 0]")));
    EXPECT_DOUBLE_EQ(world.rigid_motion(0).q.w, 1.0);
    ASSERT_EQ(world.notes().size(), 1u);
    EXPECT_NE(world.notes()[0].find("'crate'"), std::string::npos);
    EXPECT_NE(world.notes()[0].find("normalised"), std::string::npos);
}

TEST(RigidScene, MeshBodyIsCentredOnItsCentreOfMassAndKeepsItsPlace) {
    TempDir dir;
    // A unit cube from 0 to 1 on each axis: its centre of mass is (0.5, 0.5, 0.5).
    const std::string cube = dir.write("cube.obj",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
        "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n");
    const WorldDef def = def_of(one_body("\"shape\": \"mesh\", \"mesh\": \"cube.obj\", \"scale\": 2"), dir.file("s.json"));
    const RigidBody b = make_rigid_body(def.rigid_bodies[0]);
    EXPECT_FALSE(b.hull_mass_properties);
    EXPECT_NEAR(b.volume, 8.0, 1e-9);  // scaled by 2
    EXPECT_NEAR(b.initial[rigid::X], 1.0, 1e-9);  // the file's centre of mass, scaled
    EXPECT_NEAR(b.J_body.m[0][0], b.mass * (4.0 + 4.0) / 12.0, 1e-9 * b.mass);  // Table 1, sides of 2
    // Its hull is about the centre of mass: corners at +-1.
    for (const Vec3d& v : b.hull->vertices) EXPECT_NEAR(std::abs(v.x), 1.0, 1e-9);
    // An open mesh (the cube without its top) is taken by its hull, and the world says so.
    const std::string open = dir.write("open.obj",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
        "f 1 3 2\nf 1 4 3\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n");
    World world(def_of(one_body("\"shape\": \"mesh\", \"mesh\": \"open.obj\""), dir.file("s.json")));
    EXPECT_TRUE(world.rigid_body(0).hull_mass_properties);
    EXPECT_NEAR(world.rigid_body(0).volume, 1.0, 1e-9);
    ASSERT_EQ(world.notes().size(), 1u);
    EXPECT_NE(world.notes()[0].find("hull"), std::string::npos);
}

TEST(RigidScene, SceneWithRigidBodiesAndNoMeshHasNoSoftBody) {
    World world(def_of(one_body("\"shape\": \"box\", \"size\": [1, 1, 1]")));
    EXPECT_EQ(world.soft_body_count(), 0u);
    EXPECT_EQ(world.rigid_body_count(), 1u);
    world.run(10);
    EXPECT_EQ(world.status(), Status::Ok);
}

// min_z is the lowest point of any body's own shape, not of the sphere about it: a sphere's
// bottom, a box's lowest corner as it is turned (a unit cube turned 45 degrees about x stands
// on an edge sqrt(1/2) below its centre; its bounding sphere reaches sqrt(3)/2), a cylinder's
// lowest rim vertex, and a soft body's lowest particle, whichever is lowest.
TEST(RigidScene, MinZIsTheLowestPointOfTheShapesThemselves) {
    const auto min_z_of = [](const std::string& bodies) {
        return World(def_of("{\"gravity\": [0, 0, 0], \"rigid_bodies\": [" + bodies + "]}")).min_z();
    };
    EXPECT_NEAR(min_z_of("{\"name\": \"ball\", \"shape\": \"sphere\", \"radius\": 0.3, \"position\": [0, 0, 2]}"), 1.7,
                1e-6);
    EXPECT_NEAR(min_z_of("{\"name\": \"crate\", \"shape\": \"box\", \"size\": [1, 2, 0.5], \"position\": [0, 0, 1]}"),
                0.75, 1e-6);
    EXPECT_NEAR(min_z_of("{\"name\": \"cube\", \"shape\": \"box\", \"size\": [1, 1, 1], \"position\": [0, 0, 2],"
                         " \"rotation\": [45, 0, 0]}"),
                2.0 - std::sqrt(0.5), 1e-6);
    // Lying on its side (its axis turned from z to y): a rim vertex straight down, r below.
    EXPECT_NEAR(min_z_of("{\"name\": \"can\", \"shape\": \"cylinder\", \"radius\": 0.2, \"height\": 1,"
                         " \"position\": [0, 0, 0.5], \"rotation\": [90, 0, 0]}"),
                0.3, 1e-6);
    // Several bodies: the lowest of them; a soft body's particles count too.
    EXPECT_NEAR(min_z_of("{\"name\": \"a\", \"shape\": \"sphere\", \"radius\": 0.5, \"position\": [0, 0, 3]},"
                         "{\"name\": \"b\", \"shape\": \"box\", \"size\": [4, 4, 0.2], \"position\": [0, 0, 1.5]}"),
                1.4, 1e-6);
    const World mixed(def_of("{\"mesh\": \"cloud:50\", \"init_height\": 0.2, \"rigid_bodies\": [{\"name\": \"ball\","
                             " \"shape\": \"sphere\", \"radius\": 0.3, \"position\": [3, 0, 2]}]}"));
    float lowest_particle = mixed.soft_body(0).x[0].z;
    for (std::size_t i = 0; i < mixed.soft_body(0).particle_count(); ++i) lowest_particle = std::min(lowest_particle, mixed.soft_body(0).x[i].z);
    EXPECT_EQ(mixed.min_z(), lowest_particle);
}

// Boxes and balls settled in their bin on the ground: nothing is below the ground but what the
// contacts let a body sink (0.2 mm is left to the position pass), and the bin's fixed walls
// stand on it. (Their bounding spheres reached 0.63 m below it.) At rest means every body
// asleep: while the last few still land, one may dip a millimetre or more as it hits the floor
// (at 3 s, with 18 of the 30 asleep, a box was 1.2 mm deep for one tick).
TEST(RigidScene, APileAtRestReportsTheGroundAsItsLowestPoint) {
    World world((load_scene("boxes:30")));
    for (int tick = 0; tick < 1000 && world.sleeping_count() < 30; ++tick) world.tick();
    ASSERT_EQ(world.status(), Status::Ok);
    ASSERT_EQ(world.sleeping_count(), 30u);
    EXPECT_NEAR(world.min_z(), 0.0, 1e-3);
}

// --- One line naming the body and the key ------------------------------------------------------

TEST(RigidScene, BadBodiesAreRefusedNamingBodyAndKey) {
    EXPECT_REFUSED_NAMING(def_of(one_body("\"shape\": \"pyramid\"")), "scene.json:1", "'crate'", "'shape'", "pyramid");
    EXPECT_REFUSED_NAMING(def_of(one_body("\"shape\": \"box\"")), "'crate'", "'size'");
    EXPECT_REFUSED_NAMING(def_of(one_body("\"shape\": \"sphere\"")), "'crate'", "'radius'");
    EXPECT_REFUSED_NAMING(def_of(one_body("\"shape\": \"cylinder\", \"radius\": 1")), "'crate'", "'height'");
    EXPECT_REFUSED_NAMING(def_of(one_body("\"shape\": \"mesh\"")), "'crate'", "'mesh'");
    EXPECT_REFUSED_NAMING(def_of(one_body("\"shape\": \"box\", \"size\": [1, 0, 1]")), "'crate'", "'size'");
    EXPECT_REFUSED_NAMING(def_of(one_body("\"shape\": \"sphere\", \"radius\": -1")), "'crate'", "'radius'");
    EXPECT_REFUSED_NAMING(def_of(one_body("\"shape\": \"sphere\", \"radius\": 1, \"mass\": 0")), "'crate'", "'mass'");
    EXPECT_REFUSED_NAMING(def_of(one_body("\"shape\": \"sphere\", \"radius\": 1, \"density\": -5")), "'crate'", "'density'");
    EXPECT_REFUSED_NAMING(def_of(one_body("\"shape\": \"sphere\", \"radius\": 1, \"mass\": 1, \"density\": 2")), "'crate'", "'mass'",
                          "'density'");
    EXPECT_REFUSED_NAMING(def_of(one_body("\"shape\": \"sphere\", \"radius\": 1, \"orientation\": [0, 0, 0, 0]")), "'crate'",
                          "'orientation'", "zero quaternion");
    EXPECT_REFUSED_NAMING(def_of(one_body("\"shape\": \"sphere\", \"radius\": 1, \"orientation\": [1, 0, 0, 0], \"rotation\": [0, 0, 1]")),
                          "'crate'", "'orientation'", "'rotation'");
    EXPECT_REFUSED_NAMING(def_of(one_body("\"shape\": \"box\", \"size\": [1, 1, 1], \"radius\": 2")), "'crate'", "'radius'", "box");
    EXPECT_REFUSED_NAMING(def_of(one_body("\"shape\": \"box\", \"size\": [1, 1, 1], \"colour\": 2")), "'crate'", "'colour'");
    EXPECT_REFUSED_NAMING(def_of(one_body("\"shape\": \"box\", \"size\": \"big\"")), "'crate'", "'size'");
    EXPECT_REFUSED_NAMING(def_of(one_body("\"shape\": \"box\", \"size\": [1, 1, 1], \"fixed\": 1")), "'crate'", "'fixed'");
    EXPECT_REFUSED_NAMING(def_of("{\"rigid_bodies\": [{\"shape\": \"box\", \"size\": [1, 1, 1]}]}"), "scene.json:1", "\"name\"");
    EXPECT_REFUSED_NAMING(def_of("{\"rigid_bodies\": 3}"), "rigid_bodies", "array");
}

// In a file of many bodies, a line each, an error points at the line of the body and key it is
// in: the last of 2,000, the 1,000th (a key it does not take), a soft body after them, and the
// 1,500th of 2,000 springs.
TEST(RigidScene, InAFileOfThousandsTheErrorNamesItsLine) {
    const auto file = [](int bad_box, const std::string& bad_key, bool soft_after) {
        std::string json = "{\"rigid_bodies\": [\n";
        for (int i = 1; i <= 2000; ++i) {
            json += "  {\"name\": \"box" + std::to_string(i) + "\", \"shape\": \"box\", \"size\": [1, 1, 1], " +
                    (i == bad_box ? bad_key : "\"mass\": 1") + "}" + (i < 2000 ? ",\n" : "\n");
        }
        json += "]";
        if (soft_after) json += ",\n\"soft_bodies\": [\n  {\"name\": \"ball\", \"mesh\": \"ball:1\", \"stiffness\": -3}\n]";
        return json + "}\n";
    };
    EXPECT_REFUSED_NAMING(def_of(file(2000, "\"mass\": -1", false)), "scene.json:2001:", "'box2000'", "'mass'");
    EXPECT_REFUSED_NAMING(def_of(file(1000, "\"colour\": 2", false)), "scene.json:1001:", "'box1000'", "'colour'");
    EXPECT_REFUSED_NAMING(def_of(file(0, "", true)), "scene.json:2004:", "'ball'", "'stiffness'");

    // And of 2,000 springs, a line each, the 1,500th with an end of two numbers.
    std::string springs = "{\"rigid_bodies\": [{\"name\": \"p\", \"shape\": \"sphere\", \"radius\": 0.1}],\n\"springs\": [\n";
    for (int i = 1; i <= 2000; ++i) {
        springs += std::string("  {\"a\": {\"body\": \"p\"}, \"b\": {\"point\": ") + (i == 1500 ? "[0, 0]" : "[0, 0, 1]") +
                   "}, \"stiffness\": 1}" + (i < 2000 ? ",\n" : "\n");
    }
    EXPECT_REFUSED_NAMING(def_of(springs + "]}\n"), "scene.json:1502: spring end 'b'", "\"point\"");
}

TEST(RigidScene, FlatAndMissingMeshesAreRefusedNamingTheBody) {
    TempDir dir;
    dir.write("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
    EXPECT_REFUSED_NAMING(def_of(one_body("\"shape\": \"mesh\", \"mesh\": \"quad.obj\""), dir.file("s.json")), "'crate'", "quad.obj",
                          "flat");
    EXPECT_REFUSED_NAMING(def_of(one_body("\"shape\": \"mesh\", \"mesh\": \"gone.obj\""), dir.file("s.json")), "'crate'", "gone.obj");
}

TEST(RigidScene, NamesAreUniqueAcrossEveryBody) {
    const std::string text =
        "{\"mesh\": \"a.obj\", \"rigid_bodies\": [{\"name\": \"body\", \"shape\": \"sphere\", \"radius\": 1}]}";
    EXPECT_REFUSED_NAMING(parse_scene(text, "s.json"), "s.json", "'body'", "unique");
    EXPECT_REFUSED_NAMING(parse_scene("{\"rigid_bodies\": [{\"name\": \"a\", \"shape\": \"sphere\", \"radius\": 1},"
                                      " {\"name\": \"a\", \"shape\": \"sphere\", \"radius\": 2}]}", "s.json"),
                          "'a'", "unique");
}

TEST(RigidScene, BadSpringsAreRefusedNamingTheSpringAndEnd) {
    TempDir dir;
    dir.write("cube.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n");
    const std::string bodies = "\"rigid_bodies\": [{\"name\": \"plank\", \"shape\": \"box\", \"size\": [2, 0.2, 0.1]}]";
    const auto with = [&](const std::string& spring) {
        return def_of("{\"mesh\": \"cube.obj\", " + bodies + ", \"springs\": [" + spring + "]}", dir.file("scene.json"));
    };
    const auto world_with = [&](const std::string& spring) { World w(with(spring)); };
    EXPECT_REFUSED_NAMING(world_with("{\"a\": {\"body\": \"plonk\", \"point\": [0, 0, 0]}, \"b\": {\"point\": [0, 0, 1]}, \"stiffness\": 1}"),
                          "spring 1", "'a'", "'plonk'");
    EXPECT_REFUSED_NAMING(world_with("{\"a\": {\"body\": \"body\", \"vertex\": 8}, \"b\": {\"point\": [0, 0, 1]}, \"stiffness\": 1}"),
                          "spring 1", "'a'", "vertex 8", "8 vertices");
    EXPECT_REFUSED_NAMING(world_with("{\"a\": {\"body\": \"plank\", \"vertex\": 1}, \"b\": {\"point\": [0, 0, 1]}, \"stiffness\": 1}"),
                          "spring 1", "'plank'", "point");
    EXPECT_REFUSED_NAMING(world_with("{\"a\": {\"body\": \"body\", \"point\": [0, 0, 0]}, \"b\": {\"point\": [0, 0, 1]}, \"stiffness\": 1}"),
                          "spring 1", "'body'", "vertex");
    EXPECT_REFUSED_NAMING(with("{\"a\": {\"point\": [0, 0, 0]}, \"b\": {\"point\": [0, 0, 1]}}"), "scene.json", "stiffness");
    EXPECT_REFUSED_NAMING(with("{\"a\": {\"point\": [0, 0, 0]}, \"stiffness\": 1}"), "scene.json", "\"b\"");
    EXPECT_REFUSED_NAMING(with("{\"a\": {\"point\": [0, 0, 0], \"vertex\": 2}, \"b\": {\"point\": [0, 0, 1]}, \"stiffness\": 1}"),
                          "'a'", "not both");
    EXPECT_REFUSED_NAMING(with("{\"a\": {\"point\": [0, 0]}, \"b\": {\"point\": [0, 0, 1]}, \"stiffness\": 1}"), "'a'", "\"point\"");
    EXPECT_REFUSED_NAMING(with("{\"a\": {\"point\": [0, 0, 0]}, \"b\": {\"point\": [0, 0, 1]}, \"stiffness\": -1}"), "'stiffness'");
}

TEST(RigidScene, SpringRestLengthDefaultsToTheEndsDistance) {
    World world(def_of("{\"gravity\": [0, 0, 0], \"rigid_bodies\": [{\"name\": \"b\", \"shape\": \"sphere\", \"radius\": 0.1,"
                       " \"position\": [1, 0, 1]}], \"springs\": [{\"a\": {\"point\": [0, 0, 1]}, \"b\": {\"body\": \"b\","
                       " \"point\": [0.1, 0, 0]}, \"stiffness\": 5}]}"));
    ASSERT_EQ(world.links().size(), 1u);
    EXPECT_DOUBLE_EQ(world.links()[0].l0, 1.1);
    EXPECT_EQ(world.links()[0].c, 0.0);  // damping defaults to 0
    // At its rest length the spring pulls nothing: the body stays put.
    world.run(20);
    EXPECT_LT(length(world.rigid_motion(0).v), 1e-12);
}

// --- --set NAME.KEY ------------------------------------------------------------------------------

TEST(RigidScene, SetByNameChangesThatBodysKey) {
    Scene scene = parse_scene("{\"mesh\": \"a.obj\", \"rigid_bodies\": [{\"name\": \"plank\", \"shape\": \"box\", \"size\": [2, 0.3, 0.05]}]}",
                              "s.json");
    set_scene_key(scene, "plank.mass", "7");
    EXPECT_EQ(scene.rigid_bodies[0].mass, 7.0);
    set_scene_key(scene, "plank.fixed", "true");
    EXPECT_TRUE(scene.rigid_bodies[0].fixed);
    set_scene_key(scene, "body.stiffness", "33");
    EXPECT_EQ(scene.soft_bodies[0].stiffness, 33.0f);
    set_scene_key(scene, "gravity", "0,0,-1");
    EXPECT_EQ(scene.settings.gravity, (Vec3{0.0f, 0.0f, -1.0f}));
    EXPECT_REFUSED_NAMING(set_scene_key(scene, "plonk.mass", "7"), "'plonk'", "plank");
    EXPECT_REFUSED_NAMING(set_scene_key(scene, "plank.mass", "-7"), "'plank'", "'mass'");
    EXPECT_REFUSED_NAMING(set_scene_key(scene, "plank.wobble", "1"), "'plank'", "'wobble'");
    EXPECT_REFUSED_NAMING(set_scene_key(scene, "body.dt", "0.01"), "'dt'", "world key");
}

// --- Saving keeps every body ---------------------------------------------------------------------

TEST(RigidScene, SaveAndLoadRoundTripKeepsEveryBodyAndSpring) {
    TempDir dir;
    const std::string mesh = dir.write("cube.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
    Scene scene = parse_scene(
        "{\"mesh\": \"cube.obj\", \"stiffness\": 12.5, \"soft_bodies\": [{\"name\": \"jelly\", \"mesh\": \"cube.obj\","
        " \"init_height\": 3, \"particle_mass\": 0.2}], \"rigid_bodies\": [{\"name\": \"plank\", \"shape\": \"box\","
        " \"size\": [2, 0.3, 0.05], \"mass\": 5, \"position\": [0, 0, 1], \"rotation\": [10, 20, 30], \"velocity\": [0.1, 0.2, 0.3],"
        " \"angular_velocity\": [1, 2, 3], \"restitution\": 0.25, \"friction\": 0.125, \"drag_coefficient\": 0.3},"
        " {\"name\": \"hull\", \"shape\": \"mesh\", \"mesh\": \"cube.obj\", \"scale\": 0.5, \"density\": 700, \"fixed\": true}],"
        " \"springs\": [{\"a\": {\"body\": \"plank\", \"point\": [1, 0, 0]}, \"b\": {\"body\": \"body\", \"vertex\": 2},"
        " \"stiffness\": 50, \"damping\": 0.5, \"rest_length\": 0.4}, {\"a\": {\"point\": [0, 0, 3]}, \"b\": {\"body\": \"jelly\","
        " \"vertex\": 0}, \"stiffness\": 10}]}",
        dir.file("original.json"));
    const std::string path = dir.file("saved/scene.json");
    std::filesystem::create_directories(dir.file("saved"));
    save_scene(path, scene, Overwrite::No);
    EXPECT_EQ(load_scene(path), scene);  // the mesh paths resolve to the same files
    // Stored relative to the saved scene, so a folder of presets can move.
    EXPECT_NE(read_text(path).find("\"../cube.obj\""), std::string::npos) << read_text(path);
    // And it simulates.
    World world((load_scene(path)));
    EXPECT_EQ(world.soft_body_count(), 2u);
    EXPECT_EQ(world.rigid_body_count(), 2u);
    EXPECT_EQ(world.links().size(), 2u);
}

// A soft body of "soft_bodies" takes only body keys.
TEST(RigidScene, SoftBodiesTakeBodyKeysOnly) {
    EXPECT_REFUSED_NAMING(parse_scene("{\"soft_bodies\": [{\"name\": \"j\", \"mesh\": \"a.obj\", \"dt\": 0.01}]}", "s.json"),
                          "s.json:1", "'j'", "'dt'", "world key");
    EXPECT_REFUSED_NAMING(parse_scene("{\"soft_bodies\": [{\"name\": \"j\"}]}", "s.json"), "'j'", "\"mesh\"");
}

}  // namespace
}  // namespace softbody::test

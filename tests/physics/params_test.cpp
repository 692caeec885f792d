// Parameters and scene files: every bad input is refused with a message that names the key
// (and, for a file, the file and line), and saving never clobbers a file by accident.
#include <cmath>
#include <filesystem>
#include <limits>

#include "physics/error.h"
#include "physics/scene_io.h"
#include "test_support.h"

namespace softbody::test {
namespace {

namespace fs = std::filesystem;

TEST(Params, DefaultsAreListing8s) {
    const Params p;
    EXPECT_EQ(p.particle_mass, 1.0f);
    EXPECT_EQ(p.stiffness, 10.0f);
    EXPECT_EQ(p.damping, 0.1f);
    EXPECT_EQ(p.dt, 0.02f);
    EXPECT_EQ(p.gravity, (Vec3{0.0f, 0.0f, -9.81f}));
    EXPECT_EQ(p.integrator, Integrator::Verlet);
    EXPECT_NO_THROW(validate(p));
    // Where the project departs from Listing 8's literal loop, for a user's first run: substeps
    // enough for stability, a particle budget, and the file's axes and units kept (a mesh brought
    // without keys is fitted by fit_brought_mesh, not by these defaults).
    EXPECT_TRUE(p.auto_substeps);
    EXPECT_EQ(p.max_particles, 3000);
    EXPECT_EQ(p.scale, 1.0f);
    EXPECT_EQ(p.up_axis, "z");
}

TEST(Params, WordsStandForZeroAndAxesAreChecked) {
    Params p;
    set_param(p, "scale", "auto");
    EXPECT_EQ(p.scale, 0.0f);
    EXPECT_EQ(param_text(p, "scale"), "auto");
    set_param(p, "max_particles", "all");
    EXPECT_EQ(p.max_particles, 0);
    EXPECT_EQ(param_text(p, "max_particles"), "all");
    EXPECT_NO_THROW(validate(p));
    EXPECT_REFUSED_NAMING(set_param(p, "max_particles", "3"), "'max_particles'", "between 4 and 20000", "or all");
    EXPECT_REFUSED_NAMING(set_param(p, "scale", "big"), "'scale'", "or auto");
    set_param(p, "up_axis", "-x");
    EXPECT_EQ(p.up_axis, "-x");
    EXPECT_REFUSED_NAMING(set_param(p, "up_axis", "w"), "'up_axis'", "x, y, z, -x, -y or -z");
    EXPECT_EQ(p.up_axis, "-x");
}

TEST(Params, UnknownKeyIsNamedWithAHint) {
    Params p;
    EXPECT_REFUSED_NAMING(set_param(p, "stifness", "10"), "'stifness'", "did you mean 'stiffness'");
    EXPECT_REFUSED_NAMING(set_param(p, "wobble", "1"), "unknown parameter 'wobble'");
    EXPECT_EQ(p, Params{});  // nothing changed
}

TEST(Params, NotANumberIsRefused) {
    Params p;
    for (const char* text : {"nan", "NaN", "inf", "-inf", "1e39", "", "ten", "10 N/m", "0x10"}) {
        EXPECT_REFUSED_NAMING(set_param(p, "stiffness", text), "'stiffness'");
    }
    EXPECT_REFUSED_NAMING(set_param(p, "gravity", "0,0,nan"), "'gravity'");
    EXPECT_REFUSED_NAMING(set_param(p, "gravity", "0,-9.81"), "'gravity'");
    EXPECT_REFUSED_NAMING(set_param(p, "initial_velocity", "1,2,3,4"), "'initial_velocity'");
    EXPECT_EQ(p, Params{});

    // validate() catches NaN however it got into the struct.
    for (float Params::*field : {&Params::stiffness, &Params::damping, &Params::particle_mass, &Params::dt,
                                 &Params::static_friction, &Params::restitution, &Params::scale}) {
        Params bad;
        bad.*field = std::numeric_limits<float>::quiet_NaN();
        EXPECT_THROW(validate(bad), InputError);
    }
    Params bad;
    bad.gravity.y = std::numeric_limits<float>::infinity();
    EXPECT_REFUSED_NAMING(validate(bad), "'gravity'");
}

TEST(Params, OutOfRangeValuesAreNamed) {
    Params p;
    EXPECT_REFUSED_NAMING(set_param(p, "particle_mass", "-1"), "'particle_mass'");
    EXPECT_REFUSED_NAMING(set_param(p, "particle_mass", "0"), "'particle_mass'");
    EXPECT_REFUSED_NAMING(set_param(p, "dt", "0"), "'dt'");
    EXPECT_REFUSED_NAMING(set_param(p, "dt", "-0.01"), "'dt'");
    EXPECT_REFUSED_NAMING(set_param(p, "substeps", "0"), "'substeps'");
    EXPECT_REFUSED_NAMING(set_param(p, "substeps", "-2"), "'substeps'");
    EXPECT_REFUSED_NAMING(set_param(p, "substeps", "1.5"), "'substeps'");
    EXPECT_REFUSED_NAMING(set_param(p, "static_friction", "-0.1"), "'static_friction'");
    EXPECT_REFUSED_NAMING(set_param(p, "static_friction", "2.5"), "'static_friction'");
    EXPECT_REFUSED_NAMING(set_param(p, "dynamic_friction", "-1"), "'dynamic_friction'");
    EXPECT_REFUSED_NAMING(set_param(p, "restitution", "1.5"), "'restitution'");
    EXPECT_REFUSED_NAMING(set_param(p, "stiffness", "-10"), "'stiffness'");
    EXPECT_REFUSED_NAMING(set_param(p, "damping", "-0.1"), "'damping'");
    EXPECT_REFUSED_NAMING(set_param(p, "ground", "maybe"), "'ground'");
    EXPECT_REFUSED_NAMING(set_param(p, "integrator", "leapfrog"), "'integrator'");
    EXPECT_REFUSED_NAMING(set_param(p, "pinned", "1,-2"), "'pinned'");
    EXPECT_EQ(p, Params{});

    // The edges that are allowed.
    EXPECT_NO_THROW(set_param(p, "static_friction", "0"));
    EXPECT_NO_THROW(set_param(p, "restitution", "1"));
    EXPECT_NO_THROW(set_param(p, "substeps", "1"));

    // validate() applies the same ranges to a struct filled in by code.
    Params bad;
    bad.particle_mass = -1.0f;
    EXPECT_REFUSED_NAMING(validate(bad), "'particle_mass'");
    bad = Params{};
    bad.dt = 0.0f;
    EXPECT_REFUSED_NAMING(validate(bad), "'dt'");
    bad = Params{};
    bad.substeps = 0;
    EXPECT_REFUSED_NAMING(validate(bad), "'substeps'");
    bad = Params{};
    bad.dynamic_friction = 3.0f;
    EXPECT_REFUSED_NAMING(validate(bad), "'dynamic_friction'");
}

TEST(Params, WorldRefusesBadParamsAndPins) {
    Params bad;
    bad.dt = -1.0f;
    EXPECT_REFUSED_NAMING(World w(bad, points(cube_corners())), "'dt'");
    Params pins;
    pins.pinned = {8};  // the cube has vertices 0..7
    EXPECT_REFUSED_NAMING(World w(pins, points(cube_corners())), "'pinned'", "8");
    World world(Params{}, points(cube_corners()));
    EXPECT_REFUSED_NAMING(world.set_params(bad), "'dt'");
    EXPECT_EQ(world.params(), Params{});
}

TEST(Params, TextRoundTripsForEveryKey) {
    Params p;
    p.mesh = "a mesh.obj";
    p.gravity = {0.5f, -1.25f, -9.81f};
    p.pinned = {3, 1, 4};
    p.integrator = Integrator::RK4;
    p.stiffness = 12.3456789f;
    for (const ParamInfo& info : param_table()) {
        Params copy;
        set_param(copy, info.key, param_text(p, info.key));
        EXPECT_EQ(param_text(copy, info.key), param_text(p, info.key)) << info.key;
    }
}

// --- Scene files (JSON) ---------------------------------------------------------------------

TEST(Scene, UnknownKeyNamesFileLineAndKey) {
    const std::string text = "{\n  \"dt\": 0.01,\n  \"stifness\": 5\n}\n";
    EXPECT_REFUSED_NAMING(parse_scene(text, "scene.json"), "scene.json:3", "'stifness'", "'stiffness'");
}

TEST(Scene, WrongTypesAreNamed) {
    struct Case {
        const char* json;
        const char* key;
    };
    for (const Case c : {Case{"{\"stiffness\": \"10\"}", "'stiffness'"}, Case{"{\"substeps\": 2.5}", "'substeps'"},
                         Case{"{\"ground\": \"yes\"}", "'ground'"}, Case{"{\"ground\": 1}", "'ground'"},
                         Case{"{\"gravity\": [0, -9.81]}", "'gravity'"}, Case{"{\"gravity\": \"0,0,-9.81\"}", "'gravity'"},
                         Case{"{\"pinned\": 3}", "'pinned'"}, Case{"{\"pinned\": [1, 2.5]}", "'pinned'"},
                         Case{"{\"pinned\": [1, -2]}", "'pinned'"}, Case{"{\"mesh\": 5}", "'mesh'"},
                         Case{"{\"integrator\": \"leapfrog\"}", "'integrator'"}, Case{"{\"dt\": null}", "'dt'"},
                         Case{"{\"dt\": 0}", "'dt'"}, Case{"{\"particle_mass\": -1}", "'particle_mass'"},
                         Case{"{\"substeps\": 0}", "'substeps'"}, Case{"{\"static_friction\": 3}", "'static_friction'"},
                         Case{"{\"stiffness\": 1e39}", "'stiffness'"}}) {
        EXPECT_REFUSED_NAMING(parse_scene(c.json, "s.json"), "s.json:1", c.key);
    }
}

TEST(Scene, MalformedJsonGivesTheLine) {
    // NaN is not JSON; neither is a second decimal point or a missing brace.
    EXPECT_REFUSED_NAMING(parse_scene("{\n  \"dt\": 0.02,\n  \"stiffness\": NaN\n}\n", "a.json"), "a.json:3:",
                          "malformed JSON");
    EXPECT_REFUSED_NAMING(parse_scene("{\n\n\n  \"dt\": 0.0.2\n}\n", "b.json"), "b.json:4:", "malformed JSON");
    EXPECT_REFUSED_NAMING(parse_scene("{\n  \"dt\": 0.02\n", "c.json"), "c.json:", "malformed JSON");
    EXPECT_REFUSED_NAMING(parse_scene("", "d.json"), "d.json:1:", "malformed JSON");
    EXPECT_REFUSED_NAMING(parse_scene("[1, 2]", "e.json"), "e.json", "JSON object");
}

TEST(Scene, KeysOverrideTheBaseAndMeshIsRelativeToTheFile) {
    Params base;
    base.stiffness = 42.0f;
    const Params p = parse_scene("{\"dt\": 0.01, \"mesh\": \"../meshes/a.obj\", \"gravity\": [0, 0, -1]}",
                                 "/scenes/here/s.json", base)
                         .params;
    EXPECT_EQ(p.dt, 0.01f);
    EXPECT_EQ(p.stiffness, 42.0f);  // not in the file: the base's
    EXPECT_EQ(p.gravity, (Vec3{0.0f, 0.0f, -1.0f}));
    EXPECT_EQ(p.mesh, "/scenes/meshes/a.obj");
}

TEST(Scene, LoadNamesMissingFilesAndFolders) {
    TempDir dir;
    EXPECT_REFUSED_NAMING(load_scene(dir.file("absent.json")), "absent.json");
    EXPECT_REFUSED_NAMING(load_scene(dir.path().string()), "folder");
    const std::string path = dir.write("bad.json", "{\n  \"dt\": -1\n}\n");
    EXPECT_REFUSED_NAMING(load_scene(path), "bad.json:2", "'dt'");
}

TEST(Scene, SaveAndLoadRoundTrip) {
    TempDir dir;
    Params p;
    p.mesh = dir.file("mesh.obj");
    p.stiffness = 12.5f;
    p.gravity = {0.1f, 0.2f, -9.81f};
    p.pinned = {0, 5};
    p.integrator = Integrator::SymplecticEuler;
    p.auto_substeps = true;
    const std::string path = dir.file("scene.json");
    save_scene(path, p, Overwrite::No);
    EXPECT_EQ(load_scene(path), p);
    // The mesh is stored relative to the scene, so the folder can move.
    EXPECT_NE(read_text(path).find("\"mesh.obj\""), std::string::npos) << read_text(path);
}

TEST(Scene, SaveNeverOverwritesUnlessAsked) {
    TempDir dir;
    const std::string path = dir.write("scene.json", "old contents\n");
    Params p;
    p.stiffness = 20.0f;
    EXPECT_REFUSED_NAMING(save_scene(path, p, Overwrite::No), "scene.json", "already exists");
    EXPECT_EQ(read_text(path), "old contents\n");
    save_scene(path, p, Overwrite::Yes);
    EXPECT_EQ(load_scene(path).params.stiffness, 20.0f);
    // No temporary files left beside it.
    int files = 0;
    for (const auto& entry : fs::directory_iterator(dir.path())) {
        ++files;
        EXPECT_EQ(entry.path().filename(), "scene.json");
    }
    EXPECT_EQ(files, 1);
    // A folder is not a file to save to, and a missing folder is reported.
    EXPECT_REFUSED_NAMING(save_scene(dir.path().string(), p, Overwrite::Yes), "folder");
    EXPECT_REFUSED_NAMING(save_scene(dir.file("no/such/folder/s.json"), p, Overwrite::Yes), "s.json");
    EXPECT_FALSE(fs::exists(dir.file("no")));
}

// Atomic replacement: the new contents go to a new file that is then renamed over the old
// name. A second hard link to the old file therefore keeps the old contents; writing in
// place (truncate, then write) would change both, and a crash half-way would leave a
// half-written scene.
TEST(Scene, SaveReplacesAtomically) {
    TempDir dir;
    const std::string path = dir.write("scene.json", "{\"stiffness\": 1}\n");
    fs::create_hard_link(path, dir.file("old-link.json"));
    Params p;
    p.stiffness = 20.0f;
    save_scene(path, p, Overwrite::Yes);
    EXPECT_EQ(read_text(dir.file("old-link.json")), "{\"stiffness\": 1}\n");
    EXPECT_EQ(load_scene(path).params.stiffness, 20.0f);
}

}  // namespace
}  // namespace softbody::test

// The table of keys and scene files: every bad input is refused with a message that names the
// key (and, for a file, the file and line), every key reads back what it wrote, the old flat
// form reads as the new one, and saving never clobbers a file by accident.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "physics/error.h"
#include "physics/scene_io.h"
#include "test_support.h"

namespace softbody::test {
namespace {

namespace fs = std::filesystem;

const KeyInfo& body_key(std::string_view name) { return *find_key(KeyOwner::SoftBody, name); }

// Sets a soft body's or the world's key from text, as `--set` reads it.
template <class D>
void set_text(D& def, KeyOwner owner, std::string_view key, std::string_view text) {
    const KeyInfo* info = find_key(owner, key);
    if (!info) throw InputError("unknown key '" + std::string(key) + "'");
    set_key(def, *info, parse_key_text(*info, text));
}
void set_body(SoftBodyDef& def, std::string_view key, std::string_view text) { set_text(def, KeyOwner::SoftBody, key, text); }
void set_world(WorldSettings& def, std::string_view key, std::string_view text) { set_text(def, KeyOwner::World, key, text); }

TEST(Keys, DefaultsAreListing8s) {
    const WorldSettings w;
    const SoftBodyDef b;
    EXPECT_EQ(b.particle_mass, 1.0f);
    EXPECT_EQ(b.stiffness, 10.0f);
    EXPECT_EQ(b.damping, 0.1f);
    EXPECT_EQ(w.dt, 0.02f);
    EXPECT_EQ(w.gravity, (Vec3{0.0f, 0.0f, -9.81f}));
    EXPECT_EQ(w.integrator, Integrator::Verlet);
    EXPECT_NO_THROW(validate(w));
    EXPECT_NO_THROW(validate(b));
    // Where the project departs from Listing 8's literal loop, for a user's first run: substeps
    // enough for stability, a particle budget, and the file's axes and units kept (a mesh brought
    // without keys is fitted by fit_brought_mesh, not by these defaults).
    EXPECT_TRUE(w.auto_substeps);
    EXPECT_EQ(b.max_particles, 3000);
    EXPECT_EQ(b.scale, 1.0f);
    EXPECT_EQ(b.up_axis, "z");
}

// Every line of the table: a meaning, a default within its own range (an alias has none), and
// no two keys of one owner with one name.
TEST(Keys, EveryKeyIsDescribedAndItsDefaultIsValid) {
    for (const KeyInfo& info : key_table()) {
        const std::string what = std::string(to_string(info.owner)) + " " + std::string(info.name);
        EXPECT_FALSE(info.meaning.empty()) << what;
        EXPECT_EQ(find_key(info.owner, info.name), &info) << what << ": named twice";
        if (!info.alias) {
            EXPECT_NO_THROW(check_key(info, default_value(info))) << what;
        }
        if (info.slider_max > info.slider_min) {
            EXPECT_GE(info.slider_min, info.min) << what;
            EXPECT_LE(info.slider_max, info.max) << what;
        }
        // A plain-words label for the panel (not the key's name again), and presets that are valid values.
        if (!info.alias) {
            EXPECT_FALSE(info.label.empty()) << what;
            EXPECT_NE(info.label, info.name) << what;
        }
        for (const KeyPreset& preset : info.presets) {
            EXPECT_NO_THROW(check_key(info, parse_key_text(info, preset.text))) << what << " preset " << preset.name;
        }
    }
    // Gravity's presets are the surfaces' gravity, down.
    const KeyInfo& gravity = *find_key(KeyOwner::World, "gravity");
    ASSERT_FALSE(gravity.presets.empty());
    const auto down = [&](std::string_view name) {
        for (const KeyPreset& p : gravity.presets) {
            if (p.name == name) return -std::get<Vec3d>(parse_key_text(gravity, p.text)).z;
        }
        return 0.0;
    };
    EXPECT_NEAR(down("Earth"), 9.81, 1e-5);  // as floats hold them
    EXPECT_NEAR(down("Moon"), 1.62, 1e-5);
    EXPECT_NEAR(down("Jupiter"), 24.79, 1e-5);
    for (KeyOwner owner : {KeyOwner::World, KeyOwner::SoftBody, KeyOwner::RigidBody, KeyOwner::Spring}) {
        EXPECT_FALSE(keys_of(owner).empty());
    }
}

TEST(Keys, WordsStandForZeroAndAxesAreChecked) {
    SoftBodyDef p;
    set_body(p, "scale", "auto");
    EXPECT_EQ(p.scale, 0.0f);
    EXPECT_EQ(key_text(body_key("scale"), get_key(p, body_key("scale"))), "auto");
    set_body(p, "max_particles", "all");
    EXPECT_EQ(p.max_particles, 0);
    EXPECT_EQ(key_text(body_key("max_particles"), get_key(p, body_key("max_particles"))), "all");
    EXPECT_NO_THROW(validate(p));
    EXPECT_REFUSED_NAMING(set_body(p, "max_particles", "3"), "'max_particles'", "between 4 and 20000", "or all");
    EXPECT_REFUSED_NAMING(set_body(p, "scale", "big"), "'scale'", "or auto");
    set_body(p, "up_axis", "-x");
    EXPECT_EQ(p.up_axis, "-x");
    EXPECT_REFUSED_NAMING(set_body(p, "up_axis", "w"), "'up_axis'", "x, y, z, -x, -y or -z");
    EXPECT_EQ(p.up_axis, "-x");
}

TEST(Keys, UnknownKeyIsNamedWithAHint) {
    EXPECT_REFUSED_NAMING(resolve_key("stifness", ThingNames{{"body"}, {}, {}}), "'stifness'", "did you mean 'stiffness'");
    EXPECT_REFUSED_NAMING(resolve_key("wobble", ThingNames{}), "unknown key 'wobble'");
    EXPECT_REFUSED_NAMING(resolve_key("bob.wobble", ThingNames{{}, {"bob"}, {}}), "rigid body 'bob'", "unknown key 'wobble'");
    EXPECT_REFUSED_NAMING(resolve_key("spring.stifness", ThingNames{{}, {}, {"spring"}}), "spring 'spring'", "'stiffness'");
    EXPECT_REFUSED_NAMING(resolve_key("nobody.mass", ThingNames{{}, {"bob"}, {}}), "nothing is named 'nobody'", "bob");
}

// A key a soft body has, in a world without one: named, with the named things that have it.
TEST(Keys, ASoftBodysKeyWithoutASoftBodyPointsAtTheNamedOnes) {
    EXPECT_REFUSED_NAMING(resolve_key("stiffness", ThingNames{{}, {"bob"}, {"spring"}}), "'stiffness'", "no soft body",
                          "spring.stiffness");
    // With soft bodies it names every one of them.
    EXPECT_EQ(resolve_key("stiffness", ThingNames{{"a", "b"}, {}, {}}).size(), 2u);
}

TEST(Keys, NotANumberIsRefused) {
    SoftBodyDef p;
    WorldSettings w;
    for (const char* text : {"nan", "NaN", "inf", "-inf", "1e39", "", "ten", "10 N/m", "0x10"}) {
        EXPECT_REFUSED_NAMING(set_body(p, "stiffness", text), "'stiffness'");
    }
    EXPECT_REFUSED_NAMING(set_world(w, "gravity", "0,0,nan"), "'gravity'");
    EXPECT_REFUSED_NAMING(set_world(w, "gravity", "0,-9.81"), "'gravity'");
    EXPECT_REFUSED_NAMING(set_body(p, "initial_velocity", "1,2,3,4"), "'initial_velocity'");
    EXPECT_EQ(p, SoftBodyDef{});
    EXPECT_EQ(w, WorldSettings{});

    // validate() catches NaN however it got into the struct.
    for (float SoftBodyDef::*field : {&SoftBodyDef::stiffness, &SoftBodyDef::damping, &SoftBodyDef::particle_mass, &SoftBodyDef::scale}) {
        SoftBodyDef bad;
        bad.*field = std::numeric_limits<float>::quiet_NaN();
        EXPECT_THROW(validate(bad), InputError);
    }
    for (float WorldSettings::*field : {&WorldSettings::dt, &WorldSettings::static_friction, &WorldSettings::restitution}) {
        WorldSettings bad;
        bad.*field = std::numeric_limits<float>::quiet_NaN();
        EXPECT_THROW(validate(bad), InputError);
    }
    WorldSettings bad;
    bad.gravity.y = std::numeric_limits<float>::infinity();
    EXPECT_REFUSED_NAMING(validate(bad), "'gravity'");
}

TEST(Keys, OutOfRangeValuesAreNamed) {
    SoftBodyDef p;
    WorldSettings w;
    EXPECT_REFUSED_NAMING(set_body(p, "particle_mass", "-1"), "'particle_mass'");
    EXPECT_REFUSED_NAMING(set_body(p, "particle_mass", "0"), "'particle_mass'");
    EXPECT_REFUSED_NAMING(set_world(w, "dt", "0"), "'dt'");
    EXPECT_REFUSED_NAMING(set_world(w, "dt", "-0.01"), "'dt'");
    EXPECT_REFUSED_NAMING(set_world(w, "substeps", "0"), "'substeps'");
    EXPECT_REFUSED_NAMING(set_world(w, "substeps", "-2"), "'substeps'");
    EXPECT_REFUSED_NAMING(set_world(w, "substeps", "1.5"), "'substeps'");
    EXPECT_REFUSED_NAMING(set_world(w, "static_friction", "-0.1"), "'static_friction'");
    EXPECT_REFUSED_NAMING(set_world(w, "static_friction", "2.5"), "'static_friction'");
    EXPECT_REFUSED_NAMING(set_world(w, "dynamic_friction", "-1"), "'dynamic_friction'");
    EXPECT_REFUSED_NAMING(set_world(w, "restitution", "1.5"), "'restitution'");
    EXPECT_REFUSED_NAMING(set_body(p, "stiffness", "-10"), "'stiffness'");
    EXPECT_REFUSED_NAMING(set_body(p, "damping", "-0.1"), "'damping'");
    EXPECT_REFUSED_NAMING(set_world(w, "ground", "maybe"), "'ground'");
    EXPECT_REFUSED_NAMING(set_world(w, "integrator", "leapfrog"), "'integrator'");
    EXPECT_REFUSED_NAMING(set_body(p, "pinned", "1,-2"), "'pinned'");
    EXPECT_EQ(p, SoftBodyDef{});
    EXPECT_EQ(w, WorldSettings{});

    // The edges that are allowed.
    EXPECT_NO_THROW(set_world(w, "static_friction", "0"));
    EXPECT_NO_THROW(set_world(w, "restitution", "1"));
    EXPECT_NO_THROW(set_world(w, "substeps", "1"));

    // validate() applies the same ranges to a struct filled in by code, naming the thing.
    SoftBodyDef bad;
    bad.name = "jelly";
    bad.particle_mass = -1.0f;
    EXPECT_REFUSED_NAMING(validate(bad), "soft body 'jelly'", "'particle_mass'");
    WorldSettings bad_world;
    bad_world.dt = 0.0f;
    EXPECT_REFUSED_NAMING(validate(bad_world), "'dt'");
    bad_world = WorldSettings{};
    bad_world.substeps = 0;
    EXPECT_REFUSED_NAMING(validate(bad_world), "'substeps'");
    bad_world = WorldSettings{};
    bad_world.dynamic_friction = 3.0f;
    EXPECT_REFUSED_NAMING(validate(bad_world), "'dynamic_friction'");
    SpringDef spring;
    spring.name = "coil";
    spring.stiffness = -1.0;
    EXPECT_REFUSED_NAMING(validate(spring), "spring 'coil'", "'stiffness'");
}

TEST(Keys, WorldRefusesBadKeysAndPins) {
    FlatKeys bad;
    bad.dt = -1.0f;
    EXPECT_REFUSED_NAMING(OneBodyWorld w(bad, points(cube_corners())), "'dt'");
    FlatKeys pins;
    pins.pinned = {8};  // the cube has vertices 0..7
    EXPECT_REFUSED_NAMING(OneBodyWorld w(pins, points(cube_corners())), "'pinned'", "8");
    OneBodyWorld world(FlatKeys{}, points(cube_corners()));
    EXPECT_REFUSED_NAMING(set_flat(world, bad), "'dt'");
    EXPECT_EQ(world.settings(), WorldSettings{});
    EXPECT_REFUSED_NAMING(world.set_key_text("stiffness", "-3"), "'stiffness'");
    EXPECT_REFUSED_NAMING(world.set_key_text("body.dt", "0.01"), "world key");
    EXPECT_EQ(world.soft_body(0).def.stiffness, SoftBodyDef{}.stiffness);
}

// A key's text reads back as the same value, for every key of every owner, set to a value that
// is not its default where the key allows one.
TEST(Keys, TextRoundTripsForEveryKey) {
    for (const KeyInfo& info : key_table()) {
        if (info.alias) continue;
        KeyValue value = default_value(info);
        // Inside the range, off its ends and off round numbers.
        const double inside = info.min + 0.3456789 * (std::min(info.max, info.min + 100.0) - info.min);
        if (info.type == KeyType::Number && info.max > info.min) value = inside;
        if (info.type == KeyType::Vec3) value = Vec3d{inside, info.max, info.min + 0.5 * (std::min(info.max, info.min + 1.0) - info.min)};
        if (info.type == KeyType::IndexList) value = std::vector<std::uint32_t>{3, 1, 4};
        if (info.type == KeyType::Path) value = std::string("a mesh.obj");
        // Once read (rounded as the field will hold it), a value's text reads back the same.
        const KeyValue read = parse_key_text(info, key_text(info, value));
        const std::string text = key_text(info, read);
        EXPECT_EQ(parse_key_text(info, text), read) << info.name << " " << text;
    }
}

// `softbody keys` and the documents' tables come from the table: every key is in it, once.
TEST(Keys, TheMarkdownTablesHoldEveryKey) {
    const std::string markdown = keys_markdown();
    for (const KeyInfo& info : key_table()) {
        EXPECT_NE(markdown.find("| `" + std::string(info.name) + "` |"), std::string::npos) << info.name;
    }
    EXPECT_NE(keys_json().find("\"stiffness\""), std::string::npos);
    EXPECT_NE(keys_text().find("Keys of a spring"), std::string::npos);
}

// --- Scene files (JSON) ---------------------------------------------------------------------

TEST(Scene, UnknownKeyNamesFileLineAndKey) {
    const std::string text = "{\n  \"dt\": 0.01,\n  \"stifness\": 5\n}\n";
    EXPECT_REFUSED_NAMING(parse_scene(text, "scene.json"), "scene.json:3", "'stifness'", "'stiffness'");
    const std::string nested = "{\n  \"world\": {\n    \"dt\": 0.01,\n    \"gravty\": [0, 0, -1]\n  }\n}\n";
    EXPECT_REFUSED_NAMING(parse_scene(nested, "scene.json"), "scene.json:4", "'gravty'", "'gravity'");
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
                         Case{"{\"stiffness\": 1e39}", "'stiffness'"}, Case{"{\"world\": {\"dt\": -1}}", "'dt'"},
                         Case{"{\"world\": [1]}", "\"world\""}}) {
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

// The old flat form: the world's keys at the top level, and with a mesh the soft body "body".
TEST(Scene, TheFlatFormReadsAsAWorldBlockAndASoftBodyNamedBody) {
    const Scene flat = parse_scene("{\"dt\": 0.01, \"mesh\": \"../meshes/a.obj\", \"gravity\": [0, 0, -1], \"stiffness\": 42}",
                                   "/scenes/here/s.json");
    EXPECT_EQ(flat.settings.dt, 0.01f);
    EXPECT_EQ(flat.settings.gravity, (Vec3{0.0f, 0.0f, -1.0f}));
    ASSERT_EQ(flat.soft_bodies.size(), 1u);
    EXPECT_EQ(flat.soft_bodies[0].name, "body");
    EXPECT_EQ(flat.soft_bodies[0].stiffness, 42.0f);
    EXPECT_EQ(flat.soft_bodies[0].damping, SoftBodyDef{}.damping);  // not in the file: the default
    EXPECT_EQ(flat.soft_bodies[0].mesh, "/scenes/meshes/a.obj");      // relative to the file
    const Scene nested = parse_scene(
        "{\"world\": {\"dt\": 0.01, \"gravity\": [0, 0, -1]}, \"soft_bodies\": [{\"name\": \"body\", \"mesh\": \"../meshes/a.obj\","
        " \"stiffness\": 42}]}",
        "/scenes/here/s.json");
    EXPECT_EQ(nested, flat);
    // Both forms of the world's keys at once is a mistake, and said so.
    EXPECT_REFUSED_NAMING(parse_scene("{\"dt\": 0.01, \"world\": {\"gravity\": [0, 0, -1]}}", "s.json"), "s.json:1", "\"world\"",
                          "not both");
    // A soft body's key inside "world" is in the wrong place.
    EXPECT_REFUSED_NAMING(parse_scene("{\"world\": {\"stiffness\": 3}}", "s.json"), "s.json:1", "'stiffness'");
}

// A spring may have a name; its keys are then set as NAME.KEY, as a body's are.
TEST(Scene, NamedSpringsTakeTheirKeysByName) {
    Scene scene = parse_scene(
        "{\"rigid_bodies\": [{\"name\": \"bob\", \"shape\": \"sphere\", \"radius\": 0.1, \"mass\": 1, \"position\": [0, 0, 1]}],"
        " \"springs\": [{\"name\": \"coil\", \"a\": {\"point\": [0, 0, 2]}, \"b\": {\"body\": \"bob\"}, \"stiffness\": 40}]}",
        "s.json");
    ASSERT_EQ(scene.springs.size(), 1u);
    EXPECT_EQ(scene.springs[0].name, "coil");
    set_scene_key(scene, "coil.stiffness", "160");
    set_scene_key(scene, "coil.rest_length", "0.5");
    EXPECT_EQ(scene.springs[0].stiffness, 160.0);
    EXPECT_EQ(scene.springs[0].rest_length, 0.5);
    set_scene_key(scene, "coil.rest_length", "auto");
    EXPECT_FALSE(scene.springs[0].rest_length);
    EXPECT_REFUSED_NAMING(set_scene_key(scene, "coil.stiffness", "-1"), "'stiffness'");
    EXPECT_REFUSED_NAMING(set_scene_key(scene, "stiffness", "160"), "no soft body", "coil.stiffness");
    // Names are unique across bodies and springs.
    EXPECT_REFUSED_NAMING(parse_scene("{\"rigid_bodies\": [{\"name\": \"x\", \"shape\": \"sphere\", \"radius\": 1}],"
                                      " \"springs\": [{\"name\": \"x\", \"a\": {\"point\": [0, 0, 2]}, \"b\": {\"body\": \"x\"},"
                                      " \"stiffness\": 1}]}",
                                      "s.json"),
                          "'x'", "unique");
}

TEST(Scene, LoadNamesMissingFilesAndFolders) {
    TempDir dir;
    EXPECT_REFUSED_NAMING(load_scene(dir.file("absent.json")), "absent.json");
    EXPECT_REFUSED_NAMING(load_scene(dir.path().string()), "folder");
    const std::string path = dir.write("bad.json", "{\n  \"dt\": -1\n}\n");
    EXPECT_REFUSED_NAMING(load_scene(path), "bad.json:2", "'dt'");
}

Scene one_soft_body(const std::string& mesh) {
    Scene scene;
    SoftBodyDef body;
    body.name = "body";
    body.mesh = mesh;
    scene.soft_bodies.push_back(body);
    return scene;
}

TEST(Scene, SaveAndLoadRoundTrip) {
    TempDir dir;
    Scene scene = one_soft_body(dir.file("mesh.obj"));
    SoftBodyDef& p = scene.soft_bodies[0];
    p.stiffness = 12.5f;
    p.pinned = {0, 5};
    scene.settings.gravity = {0.1f, 0.2f, -9.81f};
    scene.settings.integrator = Integrator::SymplecticEuler;
    scene.settings.auto_substeps = true;
    const std::string path = dir.file("scene.json");
    save_scene(path, scene, Overwrite::No);
    EXPECT_EQ(load_scene(path), scene);
    // The mesh is stored relative to the scene, so the folder can move; the world's keys are
    // in their block.
    EXPECT_NE(read_text(path).find("\"mesh.obj\""), std::string::npos) << read_text(path);
    EXPECT_NE(read_text(path).find("\"world\""), std::string::npos) << read_text(path);
}

TEST(Scene, SaveNeverOverwritesUnlessAsked) {
    TempDir dir;
    const std::string path = dir.write("scene.json", "old contents\n");
    Scene scene = one_soft_body("cube:2");
    scene.soft_bodies[0].stiffness = 20.0f;
    EXPECT_REFUSED_NAMING(save_scene(path, scene, Overwrite::No), "scene.json", "already exists");
    EXPECT_EQ(read_text(path), "old contents\n");
    save_scene(path, scene, Overwrite::Yes);
    EXPECT_EQ(load_scene(path).soft_bodies[0].stiffness, 20.0f);
    // No temporary files left beside it.
    int files = 0;
    for (const auto& entry : fs::directory_iterator(dir.path())) {
        ++files;
        EXPECT_EQ(entry.path().filename(), "scene.json");
    }
    EXPECT_EQ(files, 1);
    // A folder is not a file to save to, and a missing folder is reported.
    EXPECT_REFUSED_NAMING(save_scene(dir.path().string(), scene, Overwrite::Yes), "folder");
    EXPECT_REFUSED_NAMING(save_scene(dir.file("no/such/folder/s.json"), scene, Overwrite::Yes), "s.json");
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
    Scene scene = one_soft_body("cube:2");
    scene.soft_bodies[0].stiffness = 20.0f;
    save_scene(path, scene, Overwrite::Yes);
    EXPECT_EQ(read_text(dir.file("old-link.json")), "{\"stiffness\": 1}\n");
    EXPECT_EQ(load_scene(path).soft_bodies[0].stiffness, 20.0f);
}

}  // namespace
}  // namespace softbody::test

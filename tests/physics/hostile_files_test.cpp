// Hostile files: whatever a file holds or is, loading it gives a clear error (one line naming
// the file) or a sensible result, and never a crash or a hang (a 60 s timeout each). The files are written
// to a temporary folder by the tests themselves.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "physics/error.h"
#include "physics/scene_io.h"
#include "test_support.h"

namespace softbody::test {
namespace {

namespace fs = std::filesystem;

// Runs a few ticks of the default parameters on a mesh: the body falls and stays finite.
void expect_simulates(const Mesh& mesh) {
    OneBodyWorld world(FlatKeys{}, mesh);
    world.run(100);
    EXPECT_EQ(world.status(), Status::Ok) << world.divergence();
    EXPECT_TRUE(all_finite(world));
}

// --- A huge face count -------------------------------------------------------------------

// 300,000 copies of one triangle: a sensible result (three particles).
TEST(HostileFiles, HugeFaceCountLoads) {
    TempDir dir;
    std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    for (int f = 0; f < 300'000; ++f) obj += "f 1 2 3\n";
    const Mesh mesh = load_mesh(dir.write("many.obj", obj));
    EXPECT_EQ(mesh.particle_count(), 3u);
    EXPECT_EQ(mesh.triangle_count(), 300'000u);
}

// Beyond kMaxTriangles a file is refused at the line that crosses it, before it is read in.
TEST(HostileFiles, MoreThanMaxTrianglesIsRefused) {
    TempDir dir;
    std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    obj.reserve(obj.size() + 8 * (kMaxTriangles + 1));
    for (std::size_t f = 0; f <= kMaxTriangles; ++f) obj += "f 1 2 3\n";
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("over.obj", obj)), "over.obj:1000004:", "1000000 triangles");

    // One OFF polygon of kMaxTriangles + 3 corners splits into one triangle too many.
    std::string off = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n" + std::to_string(kMaxTriangles + 3);
    for (std::size_t c = 0; c < kMaxTriangles + 3; ++c) off += c % 3 == 0 ? " 0" : c % 3 == 1 ? " 1" : " 2";
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("over.off", off + "\n")), "over.off:6:", "1000000 triangles");
}

// Counts that promise more than the file holds, or more than anything could: refused by the
// count or at the end of the file, without reserving memory for what was promised.
TEST(HostileFiles, HugeDeclaredCountsAreRefused) {
    TempDir dir;
    const std::string three = "0 0 0\n1 0 0\n0 1 0\n";
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("a.off", "OFF\n3 50000000 0\n" + three + "3 0 1 2\n")), "a.off:",
                          "1 of 50000000 faces");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("b.off", "OFF\n50000000 1 0\n" + three)), "b.off:", "3 of 50000000 vertices");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("c.off", "OFF\n3 9000000000 0\n" + three)), "c.off:2:", "out of range");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("d.off", "OFF\n99999999999999999999 1 0\n")), "d.off:2:", "counts");
}

// --- Faces with thousands of vertices -------------------------------------------------------

// A polygon's triangles take time linear in its corners (a fan), not quadratic: a
// 200,000-corner face would take about 80 s the quadratic way, and takes milliseconds (the
// 60 s timeout of these tests, tests/physics/CMakeLists.txt, catches the quadratic way).
TEST(HostileFiles, FacesWithThousandsOfVerticesLoadQuickly) {
    TempDir dir;
    constexpr int kCorners = 5000;
    std::string obj, off = "OFF\n" + std::to_string(kCorners) + " 1 0\n", face = "f", off_face = std::to_string(kCorners);
    for (int i = 0; i < kCorners; ++i) {
        const double a = 2.0 * kPi * i / kCorners;
        const std::string xyz = std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
        obj += "v " + xyz;
        off += xyz;
        face += " " + std::to_string(i + 1);
        off_face += " " + std::to_string(i);
    }
    const Mesh circle = load_mesh(dir.write("circle.obj", obj + face + "\n"));
    EXPECT_EQ(circle.particle_count(), std::size_t(kCorners));
    EXPECT_EQ(circle.triangle_count(), std::size_t(kCorners - 2));
    const Mesh circle_off = load_mesh(dir.write("circle.off", off + off_face + "\n"));
    EXPECT_EQ(circle_off.particle_count(), std::size_t(kCorners));
    EXPECT_EQ(circle_off.triangle_count(), std::size_t(kCorners - 2));

    // 200,000 corners going round one triangle: a third of the fan's triangles survive (the
    // others have two corners on one particle), and none is lost or invented.
    std::string big = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf";
    for (int c = 0; c < 200'000; ++c) big += c % 3 == 0 ? " 1" : c % 3 == 1 ? " 2" : " 3";
    const Mesh round = load_mesh(dir.write("round.obj", big + "\n"));
    EXPECT_EQ(round.particle_count(), 3u);
    EXPECT_GT(round.triangle_count(), 60'000u);
}

// A polygon that crosses itself keeps every one of its triangles (a clipper that looks for
// ears drops most of them).
TEST(HostileFiles, SelfCrossingPolygonKeepsAllItsTriangles) {
    TempDir dir;
    const std::string bow_tie = "v 0 0 0\nv 1 1 0\nv 1 0 0\nv 0 1 0\nv 0.5 2 0\nf 1 2 3 4 5\n";
    const Mesh mesh = load_mesh(dir.write("bow_tie.obj", bow_tie));
    EXPECT_EQ(mesh.triangle_count(), 3u);
}

// --- Deeply nested or enormous JSON ---------------------------------------------------------

TEST(HostileFiles, DeeplyNestedJsonIsRefused) {
    TempDir dir;
    const std::string deep_array = std::string(100'000, '[') + std::string(100'000, ']');
    EXPECT_REFUSED_NAMING(load_scene(dir.write("a.json", deep_array)), "a.json", "nested too deeply");
    std::string deep_object;
    for (int i = 0; i < 50'000; ++i) deep_object += "{\"pinned\":";
    deep_object += "0" + std::string(50'000, '}');
    EXPECT_REFUSED_NAMING(load_scene(dir.write("b.json", deep_object)), "b.json", "nested too deeply");
    // Unbalanced: only openings, as a truncated file would be.
    EXPECT_REFUSED_NAMING(parse_scene("{\"pinned\": " + std::string(100'000, '['), "c.json"), "c.json");
}

TEST(HostileFiles, EnormousJsonIsRefusedOrRead) {
    TempDir dir;
    // More than a megabyte: refused by its size, before parsing.
    const std::string huge = "{\"stiffness\": 10" + std::string(2 << 20, ' ') + "}";
    EXPECT_REFUSED_NAMING(load_scene(dir.write("huge.json", huge)), "huge.json", "too large");
    EXPECT_REFUSED_NAMING(parse_scene(huge, "huge.json"), "huge.json", "too large");

    // Just under: a long list of pins reads fine (World checks them against the mesh).
    std::string pins = "{\"mesh\": \"cube:2\", \"pinned\": [0";
    for (int i = 1; i < 150'000; ++i) pins += "," + std::to_string(i % 8);
    pins += "]}";
    ASSERT_LT(pins.size(), std::size_t(1) << 20);
    EXPECT_EQ(load_scene(dir.write("pins.json", pins)).soft_bodies[0].pinned.size(), 150'000u);

    // A key of most of a megabyte: named, cut short, on one line, and no slower than a
    // short one to look up ("did you mean" compares it with every key).
    const std::string key(900'000, 'k');
    EXPECT_REFUSED_NAMING(parse_scene("{\"" + key + "\": 1}", "key.json"), "key.json:1", "unknown key 'kkk", "...'");
    EXPECT_LT(error_of([&] { parse_scene("{\"" + key + "\": 1}", "key.json"); }).size(), 200u);
    // A key with a newline in it still makes a one-line message.
    EXPECT_REFUSED_NAMING(parse_scene("{\"a\\nb\": 1}", "nl.json"), "nl.json", "'a?b'");
}

// Numbers beyond double are malformed JSON, with the line they are on; beyond float, or beyond
// a whole number's range, they are values out of range for their key.
TEST(HostileFiles, JsonNumbersOutOfEveryRange) {
    EXPECT_REFUSED_NAMING(parse_scene("{\n  \"dt\": 0.02,\n  \"stiffness\": 1e400\n}\n", "a.json"), "a.json:3:",
                          "malformed JSON", "1e400");
    EXPECT_REFUSED_NAMING(parse_scene("{\"stiffness\": 1e39}", "b.json"), "b.json:1", "'stiffness'");
    EXPECT_REFUSED_NAMING(parse_scene("{\"substeps\": 18446744073709551615}", "c.json"), "c.json:1", "'substeps'",
                          "18446744073709551615");
    EXPECT_REFUSED_NAMING(parse_scene("{\"pinned\": [1, 99999999999999999999]}", "d.json"), "d.json:1", "'pinned'");
}

// --- A path that is a directory --------------------------------------------------------------

TEST(HostileFiles, FolderInsteadOfAFile) {
    TempDir dir;
    for (const char* name : {"mesh.obj", "mesh.off", "scene.json"}) fs::create_directory(dir.file(name));
    EXPECT_REFUSED_NAMING(load_mesh(dir.file("mesh.obj")), "mesh.obj", "is a folder");
    EXPECT_REFUSED_NAMING(load_mesh(dir.file("mesh.off")), "mesh.off", "is a folder");
    EXPECT_REFUSED_NAMING(load_scene(dir.file("scene.json")), "scene.json", "is a folder");
    EXPECT_REFUSED_NAMING(save_scene(dir.file("scene.json"), Scene{}, Overwrite::Yes), "scene.json", "folder");
    // Through a symbolic link too.
    fs::create_directory_symlink(dir.file("mesh.obj"), dir.file("link.obj"));
    EXPECT_REFUSED_NAMING(load_mesh(dir.file("link.obj")), "link.obj", "is a folder");
}

// --- A file that disappears, or cannot be read --------------------------------------------------

TEST(HostileFiles, FileThatDisappears) {
    TempDir dir;
    const std::string mesh = dir.write("gone.obj", "v 0 0 0\n");
    const std::string scene = dir.write("gone.json", "{}");
    fs::remove(mesh);
    fs::remove(scene);
    EXPECT_REFUSED_NAMING(load_mesh(mesh), "gone.obj", "cannot open", "No such file");
    EXPECT_REFUSED_NAMING(load_scene(scene), "gone.json", "cannot open", "No such file");
    // A link to a file that has gone.
    fs::create_symlink(dir.file("nowhere.obj"), dir.file("dangling.obj"));
    EXPECT_REFUSED_NAMING(load_mesh(dir.file("dangling.obj")), "dangling.obj", "cannot open");
    // A folder on the way that is a file.
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("file", "") + "/mesh.obj"), "mesh.obj", "cannot open");
}

// A pipe with no writer, a device with endless data: refused at once, never waited on or read.
TEST(HostileFiles, PipesAndDevicesAreNotFiles) {
    TempDir dir;
    ASSERT_EQ(::mkfifo(dir.file("pipe.obj").c_str(), 0644), 0);
    ASSERT_EQ(::mkfifo(dir.file("pipe.json").c_str(), 0644), 0);
    EXPECT_REFUSED_NAMING(load_mesh(dir.file("pipe.obj")), "pipe.obj", "not a regular file");
    EXPECT_REFUSED_NAMING(load_scene(dir.file("pipe.json")), "pipe.json", "not a regular file");
    if (fs::exists("/dev/zero")) {
        fs::create_symlink("/dev/zero", dir.file("zero.off"));
        EXPECT_REFUSED_NAMING(load_mesh(dir.file("zero.off")), "zero.off", "not a regular file");
    }
}

// Files of mode 000. Root reads them anyway, so as root they are read as the unprivileged user
// (as_unprivileged_user).
TEST(HostileFiles, UnreadableFile) {
    TempDir dir;
    const std::string mesh = dir.write("secret.obj", "v 0 0 0\n");
    const std::string scene = dir.write("secret.json", "{}");
    fs::permissions(mesh, fs::perms::none);
    fs::permissions(scene, fs::perms::none);
    const int code = as_unprivileged_user([&] {
        if (::access(mesh.c_str(), R_OK) == 0) return 77;  // CAP_DAC_OVERRIDE without being root
        const std::string mesh_fault =
            refusal_fault(error_of([&] { load_mesh(mesh); }), {"secret.obj", "cannot open", "Permission denied"});
        const std::string scene_fault =
            refusal_fault(error_of([&] { load_scene(scene); }), {"secret.json", "cannot open", "Permission denied"});
        std::fprintf(stderr, "load_mesh: %s\nload_scene: %s\n", mesh_fault.c_str(), scene_fault.c_str());
        return (mesh_fault.empty() ? 0 : 1) + (scene_fault.empty() ? 0 : 2);
    });
    if (code == 77) GTEST_SKIP() << "this process may read a file of mode 000 and cannot give that up";
    EXPECT_EQ(code, 0) << "1: the mesh, 2: the scene, 3: both were not refused as they should be (see stderr)";
}

// --- Degenerate meshes ----------------------------------------------------------------------

// Every vertex at one place: one particle (no zero-length springs), no triangles, and it falls.
TEST(HostileFiles, AllVerticesCoincident) {
    TempDir dir;
    std::string obj, off = "OFF\n100 98 0\n";
    for (int i = 0; i < 100; ++i) {
        obj += "v 1.5 -2 3\n";
        off += "1.5 -2 3\n";
    }
    for (int f = 0; f < 98; ++f) {
        obj += "f " + std::to_string(f + 1) + " " + std::to_string(f + 2) + " " + std::to_string(f + 3) + "\n";
        off += "3 " + std::to_string(f) + " " + std::to_string(f + 1) + " " + std::to_string(f + 2) + "\n";
    }
    for (const std::string& path : {dir.write("same.obj", obj), dir.write("same.off", off)}) {
        const Mesh mesh = load_mesh(path);
        EXPECT_EQ(mesh.particle_count(), 1u) << path;
        EXPECT_EQ(mesh.triangle_count(), 0u) << path;
        EXPECT_EQ(mesh.vertex_to_particle, std::vector<std::uint32_t>(100, 0)) << path;
        expect_simulates(mesh);
    }
}

TEST(HostileFiles, SinglePoint) {
    TempDir dir;
    const std::string obj = dir.write("point.obj", "v 0.25 0.5 1\n");
    const std::string off = dir.write("point.off", "OFF\n1 0 0\n0.25 0.5 1\n");
    for (const std::string& path : {obj, off}) {
        const Mesh mesh = load_mesh(path);
        ASSERT_EQ(mesh.particle_count(), 1u) << path;
        EXPECT_EQ(mesh.positions[0], (Vec3{0.25f, 0.5f, 1.0f}));
        OneBodyWorld world(FlatKeys{}, mesh);
        EXPECT_EQ(world.soft_body(0).spring_count(), 0u);
        world.run(200);  // 4 s: it falls 3 m and rests on the ground
        EXPECT_EQ(world.status(), Status::Ok) << world.divergence();
        EXPECT_NEAR(position(world, 0).z, 0.0f, 1e-4f);
    }
    // A point on its own, as a "p" element: the same.
    EXPECT_EQ(load_mesh(dir.write("p.obj", "v 0 0 0\np 1\n")).particle_count(), 1u);
    // Nothing at all is not a mesh.
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("none.off", "OFF\n0 0 0\n")), "none.off", "no vertices");
}

// Triangles with no area load (the renderer and the physics cope with them); triangles whose
// corners weld together are dropped.
TEST(HostileFiles, ZeroAreaAndDegenerateTriangles) {
    TempDir dir;
    // Three corners on a line: a triangle of zero area, kept.
    const Mesh line = load_mesh(dir.write("line.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n"));
    EXPECT_EQ(line.particle_count(), 3u);
    EXPECT_EQ(line.triangle_count(), 1u);
    expect_simulates(line);
    // A sliver far thinner than float can resolve against its length.
    const Mesh sliver = load_mesh(dir.write("sliver.obj", "v 0 0 0\nv 1 0 0\nv 0.5 1e-30 0\nf 1 2 3\n"));
    EXPECT_EQ(sliver.triangle_count(), 1u);
    expect_simulates(sliver);
    // Repeated corners, and corners that weld into one particle: dropped.
    const Mesh repeated = load_mesh(dir.write("repeat.obj", "v 0 0 0\nv 1 0 0\nv 1 1e-9 0\nf 1 1 2\nf 1 2 3\n"));
    EXPECT_EQ(repeated.particle_count(), 2u);
    EXPECT_EQ(repeated.triangle_count(), 0u);
    expect_simulates(repeated);
    const Mesh off = load_mesh(dir.write("repeat.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 0 0\n2 0 1\n"));
    EXPECT_EQ(off.particle_count(), 3u);
    EXPECT_EQ(off.triangle_count(), 0u);
}

// Coordinates at the ends of float's range: welded and triangulated without overflowing (the
// differences and the normals are taken in double there).
TEST(HostileFiles, CoordinatesAtTheEndsOfFloat) {
    TempDir dir;
    const Mesh huge = load_mesh(dir.write("huge.obj", "v -3e38 -3e38 0\nv 3e38 -3e38 0\nv 0 3e38 3e38\nf 1 2 3\n"));
    EXPECT_EQ(huge.particle_count(), 3u);
    EXPECT_EQ(huge.triangle_count(), 1u);
    const Mesh tiny = load_mesh(dir.write("tiny.obj", "v 0 0 0\nv 1e-38 0 0\nv 0 1e-38 0\nf 1 2 3\n"));
    EXPECT_EQ(tiny.particle_count(), 3u);
    EXPECT_EQ(tiny.triangle_count(), 1u);
    // Beyond float: refused with the line.
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("over.obj", "v 0 0 0\nv 4e38 0 0\n")), "over.obj:2:", "4e38");
}

// --- Names that are not UTF-8 ----------------------------------------------------------------

TEST(HostileFiles, NonUtf8Names) {
    TempDir dir;
    const std::string odd = "\xff\xfe";
    const std::string mesh_path = dir.write(odd + ".obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const Mesh mesh = load_mesh(mesh_path);
    EXPECT_EQ(mesh.particle_count(), 3u);
    EXPECT_EQ(mesh.source, mesh_path);  // the bytes as they are
    // A missing one is named with its bytes as they are.
    const std::string missing = odd + "-missing.off";
    EXPECT_REFUSED_NAMING(load_mesh(dir.file(missing)), missing.c_str(), "cannot open");
    // A scene file with such a name loads; its mesh path resolves beside it.
    const std::string folder = dir.file(odd);
    fs::create_directory(folder);
    const std::string scene = dir.write(odd + "/scene.json", "{\"mesh\": \"../" + std::string("a.obj") + "\"}");
    EXPECT_EQ(load_scene(scene).soft_bodies[0].mesh, dir.file("a.obj"));
    // Inside JSON, bytes that are not UTF-8 are malformed JSON, said so with the line.
    EXPECT_REFUSED_NAMING(parse_scene("{\n\"mesh\": \"" + odd + ".obj\"}", "bad.json"), "bad.json:2:", "malformed JSON");
    // A scene file cannot hold such a mesh path: saving says so and writes nothing.
    FlatKeys params;
    params.mesh = mesh_path;
    const std::string target = dir.file("preset.json");
    EXPECT_REFUSED_NAMING(save_scene(target, scene_of(params), Overwrite::No), "'mesh'", "UTF-8");
    EXPECT_FALSE(fs::exists(target));
    // But a scene file may itself have such a name.
    params.mesh = dir.file("a.obj");
    save_scene(dir.file(odd + ".json"), scene_of(params), Overwrite::No);
    EXPECT_EQ(load_scene(dir.file(odd + ".json")).soft_bodies[0].mesh, dir.file("a.obj"));
    // OBJ names and comments in any encoding are skipped.
    EXPECT_EQ(load_mesh(dir.write("names.obj", "# " + odd + "\no " + odd + "\ng " + odd + "\nusemtl " + odd +
                                                    "\nv 0 0 0\n"))
                  .particle_count(),
              1u);
}

// --- Other malformed lines ------------------------------------------------------------------

TEST(HostileFiles, OddObjLines) {
    TempDir dir;
    const std::string head = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    // A comment after a face's indices, or after a vertex, or on a line of its own: skipped
    // (the reader is never shown its words).
    EXPECT_EQ(load_mesh(dir.write("a.obj", head + "f 1 2 3 # face 4 5 6\n")).triangle_count(), 1u);
    EXPECT_EQ(load_mesh(dir.write("b.obj", "v 0 0 0 # origin\n# note\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")).triangle_count(), 1u);
    // Four indices in one corner, a trailing slash, a number glued to a comment.
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("c.obj", head + "vt 0 0\nvn 0 0 1\nf 1/1/1/1 2 3\n")), "c.obj:6:",
                          "more than three");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("d.obj", head + "vn 0 0 1\nf 1//1/ 2 3\n")), "d.obj:5:");
    // A corner that ends with '/' names no texture coordinate or normal there: read as such
    // (the reader on its own would take the next corner's number for the missing index).
    for (const char* corner : {"1/", "1//", "1/1/"}) {
        const RawMesh raw = parse_obj_text(head + "vt 0 0\nvn 0 0 1\nf " + corner + " 2 3\n", "h.obj");
        ASSERT_EQ(raw.triangle_corners.size(), 3u) << corner;
        EXPECT_EQ(raw.triangle_corners[0], (Corner{0, -1, corner == std::string("1/1/") ? 0 : -1})) << corner;
        EXPECT_EQ(raw.triangle_corners[1], (Corner{1, -1, -1})) << corner;
        EXPECT_TRUE(raw.warnings.empty()) << corner;
    }
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("e.obj", "v 0 0 0#x\n")), "e.obj:1:", "0#x");
    // Old Mac line ends (a lone CR) are line ends, as the reader sees them.
    EXPECT_EQ(load_mesh(dir.write("f.obj", "v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 3\r")).triangle_count(), 1u);
    // Control bytes in a bad token do not break the message onto two lines.
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("g.obj", std::string("v 0 0 \x01\x02\x1b[2J\n"))), "g.obj:1:");
    // Binary junk.
    std::string junk;
    for (int i = 0; i < 4096; ++i) junk += static_cast<char>((i * 7919) & 0xff);
    EXPECT_FALSE(error_of([&] { load_mesh(dir.write("junk.obj", junk)); }).empty());
    EXPECT_FALSE(error_of([&] { load_mesh(dir.write("junk.off", junk)); }).empty());
}

}  // namespace
}  // namespace softbody::test

// Meshes: welding the duplicates that exporters write at UV seams into single particles, and
// refusing broken files with a message that names the file (and line).
#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <sstream>

#include "generated_meshes.h"
#include "physics/error.h"
#include "physics/shape_meshes.h"
#include "test_support.h"

namespace softbody::test {
namespace {

// --- Welding ----------------------------------------------------------------------------------

// A square in two triangles, written as an exporter does at a UV seam: each triangle has its
// own three vertices, so corners 3 and 4 repeat corners 1 and 3 at the same places.
TEST(Weld, SeamDuplicatesBecomeOneParticle) {
    const std::string obj =
        "v 0 0 0\nv 1 0 0\nv 1 1 0\n"
        "v 0 0 0\nv 1 1 0\nv 0 1 0\n"
        "vt 0 0\nvt 0.5 0\nvt 0.5 0.5\nvt 0.5 0\nvt 1 0.5\nvt 0.5 1\n"
        "f 1/1 2/2 3/3\nf 4/4 5/5 6/6\n";
    const Mesh mesh = build_mesh(parse_obj_text(obj, "seam.obj"), "seam.obj");
    ASSERT_EQ(mesh.particle_count(), 4u);
    EXPECT_EQ(mesh.vertex_to_particle, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
    EXPECT_EQ(mesh.triangle_count(), 2u);
    // Both triangles survive, on the right particles, and each corner keeps its own UV
    // (six render vertices: the seam is still a seam for the texture).
    EXPECT_EQ(mesh.render_vertices.size(), 6u);
    std::vector<std::uint32_t> corners;
    for (std::uint32_t r : mesh.triangles) corners.push_back(mesh.render_vertices[r].particle);
    EXPECT_EQ(corners, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
    EXPECT_TRUE(mesh.has_uvs);
}

// A cube written face by face (24 vertices, 4 per face, as with per-face normals or UVs)
// welds to its 8 corners, and each vertex maps onto the particle at its own position.
TEST(Weld, CubeWithPerFaceVerticesHasEightParticles) {
    std::ostringstream obj;
    const int faces[6][4][3] = {
        {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}},
        {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, {{0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}},
        {{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}}, {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}}};
    for (const auto& face : faces) {
        for (const auto& corner : face) obj << "v " << corner[0] << " " << corner[1] << " " << corner[2] << "\n";
    }
    for (int f = 0; f < 6; ++f) obj << "f " << 4 * f + 1 << " " << 4 * f + 2 << " " << 4 * f + 3 << " " << 4 * f + 4 << "\n";
    const RawMesh raw = parse_obj_text(obj.str(), "cube.obj");
    ASSERT_EQ(raw.positions.size(), 24u);
    const Mesh mesh = build_mesh(raw, "cube.obj");
    EXPECT_EQ(mesh.particle_count(), 8u);
    EXPECT_EQ(mesh.triangle_count(), 12u);  // quads split in two
    ASSERT_EQ(mesh.vertex_to_particle.size(), 24u);
    for (std::size_t v = 0; v < 24; ++v) {
        EXPECT_EQ(mesh.positions[mesh.vertex_to_particle[v]], raw.positions[v]) << "vertex " << v;
    }
}

// Coincident vertices never become two particles: exact repeats, -0 against +0, and copies
// within the weld distance (1e-6 of the bounding-box diagonal) on either side of any grid
// cell boundary. Points farther apart than that stay apart.
TEST(Weld, CoincidentVerticesNeverBecomeTwoParticles) {
    const std::vector<Vec3> originals = random_cloud(300, 41, 10.0f);
    float diagonal_sq = 0.0f;
    {
        Vec3 lo = originals[0], hi = originals[0];
        for (const Vec3& p : originals) {
            lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
            hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
        }
        diagonal_sq = dot(hi - lo, hi - lo);
    }
    // Copies are jittered by up to a quarter of the weld distance (1e-6 of the 35 m diagonal:
    // 8.7e-6 m), which is still nine ulps at positions of 10 m: real, not rounded away.
    const float jitter = 0.25f * 1e-6f * std::sqrt(diagonal_sq);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    RawMesh raw;
    std::vector<std::size_t> original_of;
    for (int copy = 0; copy < 4; ++copy) {
        for (std::size_t i = 0; i < originals.size(); ++i) {
            Vec3 p = originals[i];
            // Copies 1 and 3 are jittered; copy 2 repeats the original exactly.
            if (copy % 2 == 1) p = p + Vec3{unit(rng), unit(rng), unit(rng)} * (jitter / std::sqrt(3.0f));
            raw.positions.push_back(p);
            original_of.push_back(i);
        }
    }
    raw.positions.push_back({0.0f, 0.0f, 0.0f});
    raw.positions.push_back({-0.0f, 0.0f, -0.0f});
    const Mesh mesh = build_mesh(raw, "copies");
    EXPECT_EQ(mesh.particle_count(), originals.size() + 1);
    for (std::size_t v = 0; v < original_of.size(); ++v) {
        ASSERT_EQ(mesh.vertex_to_particle[v], mesh.vertex_to_particle[original_of[v]]) << "vertex " << v;
        ASSERT_EQ(mesh.vertex_to_particle[v], original_of[v]);  // first-seen order
    }
    EXPECT_EQ(mesh.vertex_to_particle[raw.positions.size() - 1], mesh.vertex_to_particle[raw.positions.size() - 2]);

    // Two points 10 weld distances apart are two particles.
    const Mesh apart = points({{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {1.0f + 1e-5f, 0.0f, 0.0f}});
    EXPECT_EQ(apart.particle_count(), 3u);
}

// A whole mesh of duplicates of one point welds to one particle (and no springs of length 0).
TEST(Weld, AllVerticesAtOnePointAreOneParticle) {
    const Mesh mesh = points({{1.0f, 2.0f, 3.0f}, {1.0f, 2.0f, 3.0f}, {1.0f, 2.0f, 3.0f}});
    EXPECT_EQ(mesh.particle_count(), 1u);
    EXPECT_EQ(mesh.vertex_to_particle, (std::vector<std::uint32_t>{0, 0, 0}));
}

TEST(Weld, TrianglesThatCollapseAreDropped) {
    const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 0 0\nf 1 2 3\nf 1 2 4\n";
    const Mesh mesh = build_mesh(parse_obj_text(obj, "t.obj"), "t.obj");
    EXPECT_EQ(mesh.particle_count(), 3u);
    EXPECT_EQ(mesh.triangle_count(), 1u);
}

// sphere_mesh scales one welded unit sphere instead of welding each radius's vertices: it must be
// exactly what welding them gives, at every level and at radii from below the weld's rescaling
// (1e-3 across) to far above it.
TEST(Weld, ASphereIsItsVerticesWeldedAtEveryRadius) {
    for (int level = 0; level <= kMostSphereSubdivisions; ++level) {
        for (const double radius : {1e-5, 0.1, 0.137, 0.2, 1.0, 3.7, 2.5e7}) {
            const Mesh fast = sphere_mesh(radius, level);
            const Mesh welded = build_mesh(sphere_raw_mesh(radius, level), fast.source);
            SCOPED_TRACE("level " + std::to_string(level) + ", radius " + std::to_string(radius));
            EXPECT_EQ(fast.particle_count(), 10u * (1u << (2 * level)) + 2u);
            ASSERT_EQ(fast.positions.size(), welded.positions.size());
            for (std::size_t i = 0; i < fast.positions.size(); ++i) {
                EXPECT_EQ(fast.positions[i].x, welded.positions[i].x);
                EXPECT_EQ(fast.positions[i].y, welded.positions[i].y);
                EXPECT_EQ(fast.positions[i].z, welded.positions[i].z);
            }
            EXPECT_EQ(fast.vertex_to_particle, welded.vertex_to_particle);
            EXPECT_EQ(fast.triangles, welded.triangles);
            EXPECT_EQ(fast.normal_slot_count, welded.normal_slot_count);
            ASSERT_EQ(fast.render_vertices.size(), welded.render_vertices.size());
            for (std::size_t i = 0; i < fast.render_vertices.size(); ++i) {
                EXPECT_EQ(fast.render_vertices[i].particle, welded.render_vertices[i].particle);
                EXPECT_EQ(fast.render_vertices[i].normal_slot, welded.render_vertices[i].normal_slot);
            }
            EXPECT_EQ(fast.has_uvs, welded.has_uvs);
            EXPECT_TRUE(fast.warnings.empty());
        }
    }
}

// --- Loading ------------------------------------------------------------------------------------

TEST(LoadMesh, PointCloudWithoutFacesIsValid) {
    TempDir dir;
    const std::string path = dir.write("cloud.obj", "# points\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0 0 0\n");
    const Mesh mesh = load_mesh(path);
    EXPECT_EQ(mesh.particle_count(), 4u);
    EXPECT_EQ(mesh.triangle_count(), 0u);
    EXPECT_EQ(mesh.source, path);
    OneBodyWorld world(FlatKeys{}, mesh);
    EXPECT_EQ(world.soft_body(0).spring_count(), 6u);
    const std::string off = dir.write("cloud.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n");
    EXPECT_EQ(load_mesh(off).particle_count(), 3u);
}

TEST(LoadMesh, MissingFileAndFolderAreNamed) {
    TempDir dir;
    EXPECT_REFUSED_NAMING(load_mesh(dir.file("absent.obj")), "absent.obj", "cannot open");
    std::filesystem::create_directory(dir.file("folder.obj"));
    EXPECT_REFUSED_NAMING(load_mesh(dir.file("folder.obj")), "folder.obj", "folder");
    const std::string other = dir.write("mesh.stl", "solid\n");
    EXPECT_REFUSED_NAMING(load_mesh(other), "mesh.stl", ".stl");
}

TEST(LoadMesh, EmptyFilesAreRefused) {
    TempDir dir;
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("empty.obj", "")), "empty.obj", "no vertices");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("comments.obj", "# nothing\n\n")), "comments.obj", "no vertices");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("empty.off", "")), "empty.off", "empty");
}

TEST(LoadMesh, MalformedObjNumberGivesFileAndLine) {
    TempDir dir;
    for (const char* bad : {"abc", "nan", "inf", "1e39", "1.2.3", "--1"}) {
        const std::string path = dir.write("bad.obj", std::string("v 0 0 0\n# a comment\nv 1 ") + bad + " 0\nv 0 1 0\n");
        EXPECT_REFUSED_NAMING(load_mesh(path), "bad.obj:3:", bad);
    }
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("short.obj", "v 0 0 0\nv 1 0\n")), "short.obj:2:");
    // After the numbers, a comment's words are not numbers; glued to one, they are.
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("glued.obj", "v 0 0 0\nv 1 0 0#x\n")), "glued.obj:2:", "0#x");
    // A normal or texture coordinate with no numbers at all: the reader would not count it,
    // and every later index would name the wrong one.
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("empty_vn.obj", "v 0 0 0\nvn\n")), "empty_vn.obj:2:", "'vn'");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("empty_vt.obj", "v 0 0 0\nvt\n")), "empty_vt.obj:2:", "'vt'");
}

TEST(LoadMesh, FaceIndexOutOfRangeGivesTheLine) {
    TempDir dir;
    const std::string head = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("a.obj", head + "f 1 2 3\nf 1 2 4\n")), "a.obj:5:", "'4'");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("b.obj", head + "f 0 1 2\n")), "b.obj:4:", "'0'");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("c.obj", head + "f -4 1 2\n")), "c.obj:4:", "'-4'");
    // A texture-coordinate or normal index that is not a whole number: the file is not what
    // it seems (one that names nothing is forgiven: see Leniency below).
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("d.obj", head + "f 1/x 2 3\n")), "d.obj:4:", "'x'");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("d2.obj", head + "f 1//1.5 2 3\n")), "d2.obj:4:", "'1.5'");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("e.obj", head + "f 1 2\n")), "e.obj:4:");
    // A face may only use vertices defined before it.
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("f.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n")), "f.obj:3:");
    // Negative indices count back from the last vertex: fine when in range.
    EXPECT_EQ(load_mesh(dir.write("g.obj", head + "f -3 -2 -1\n")).triangle_count(), 1u);
}

TEST(LoadMesh, OffHeaderOnItsOwnLineOrWithTheCounts) {
    TempDir dir;
    // The usual layout: "OFF" alone, then "vertices faces edges".
    const std::string own_line = "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 1 3\n";
    const Mesh a = load_mesh(dir.write("a.off", own_line));
    EXPECT_EQ(a.particle_count(), 4u);
    EXPECT_EQ(a.triangle_count(), 2u);
    EXPECT_EQ(a.positions[3], (Vec3{0.0f, 0.0f, 1.0f}));
    const Mesh b = load_mesh(dir.write("b.off", "OFF 4 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n4 0 1 2 3\n"));
    EXPECT_EQ(b.particle_count(), 4u);
    EXPECT_EQ(b.triangle_count(), 2u);  // a quad, split in two
    const Mesh c = load_mesh(dir.write("c.off", "# comment\nOFF\n\n# counts\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
    EXPECT_EQ(c.particle_count(), 3u);
    EXPECT_EQ(c.triangle_count(), 1u);
}

TEST(LoadMesh, MalformedOffGivesTheLine) {
    TempDir dir;
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("a.off", "PLY\n3 1 0\n")), "a.off:1:", "OFF");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("b.off", "OFF\nthree 1 0\n")), "b.off:2:", "counts");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("c.off", "OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n")), "c.off:4:");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("d.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n")), "d.off:", "2 of 3 vertices");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("e.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n")), "e.off:6:",
                          "'3'");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("f.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n")), "f.off:6:");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("g.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n")), "g.off:", "0 of 1 faces");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("h.off", "OFF\n-3 1 0\n")), "h.off:2:");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("i.off", "OFF\n")), "i.off:", "counts");
}

// --- Leniency: what only the drawing uses is forgiven, with a warning -----------------------

// The positions, triangles (on particles) and warnings of a file: what the physics sees.
struct Loaded {
    std::vector<Vec3> positions;
    std::vector<std::uint32_t> triangle_particles;
    std::vector<std::string> warnings;
};
Loaded load(const std::string& path) {
    const Mesh mesh = load_mesh(path);
    Loaded out{mesh.positions, {}, mesh.warnings};
    for (std::uint32_t r : mesh.triangles) out.triangle_particles.push_back(mesh.render_vertices[r].particle);
    return out;
}

// Faces that name normals the file never defines (as files cut out of a larger one do) keep
// their positions and triangles: the same as the file without those references, plus one
// warning line for the whole file that names the first fault and counts the others.
TEST(Leniency, DanglingNormalIndicesKeepPositionsWithOneWarning) {
    TempDir dir;
    const std::string head = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";
    const Loaded clean = load(dir.write("clean.obj", head + "f 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n"));
    const Loaded dangling = load(dir.write("dangling.obj", head + "f 1//7 2//8 3//9\nf 1 2 4\nf 1//7 3//7 4//1\nf 2 3 4\n"));
    EXPECT_EQ(dangling.positions, clean.positions);
    EXPECT_EQ(dangling.triangle_particles, clean.triangle_particles);
    EXPECT_TRUE(clean.warnings.empty());
    ASSERT_EQ(dangling.warnings.size(), 1u);
    const std::string& warning = dangling.warnings[0];
    EXPECT_NE(warning.find("dangling.obj:5:"), std::string::npos) << warning;
    EXPECT_NE(warning.find("normal index '7'"), std::string::npos) << warning;
    EXPECT_NE(warning.find("0 defined"), std::string::npos) << warning;
    EXPECT_NE(warning.find("(5 more like it)"), std::string::npos) << warning;  // 6 corners in all
    EXPECT_EQ(warning.find('\n'), std::string::npos) << "one line";

    // Some normals defined, others not: the defined ones are kept, the others dropped.
    const RawMesh raw = parse_obj_text(head + "vn 0 0 1\nf 1//1 2//2 3//-1\n", "some.obj");
    ASSERT_EQ(raw.triangle_corners.size(), 3u);
    EXPECT_EQ(raw.triangle_corners[0].normal, 0);
    EXPECT_EQ(raw.triangle_corners[1].normal, -1);
    EXPECT_EQ(raw.triangle_corners[2].normal, 0);
    ASSERT_EQ(raw.warnings.size(), 1u);
    EXPECT_NE(raw.warnings[0].find("some.obj:6: face normal index '2' does not refer to one of the 1"), std::string::npos)
        << raw.warnings[0];
    // Indices far beyond any count (or int) are dangling too, not a crash in the reader.
    const RawMesh huge = parse_obj_text(head + "f 1//99999999999999999999 2/-5 3//0\n", "huge.obj");
    EXPECT_EQ(huge.triangle_corners[0], (Corner{0, -1, -1}));
    EXPECT_EQ(huge.triangle_corners[1], (Corner{1, -1, -1}));
    EXPECT_EQ(huge.triangle_corners[2], (Corner{2, -1, -1}));
    EXPECT_EQ(huge.warnings.size(), 2u);  // normals, texture coordinates
}

// The same for texture coordinates, and for normals and texture coordinates whose numbers are
// not finite (exporters write "nan" for the normal of a face with no area): the corners that
// use them go without, everything else stays.
TEST(Leniency, BadNormalsAndTextureCoordinatesAreDropped) {
    const std::string text =
        "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
        "vn 0 0 1\nvn nan nan nan\nvn -nan(ind) 0 0\nvn -1.#IND00 0 0\nvn 1 0\nvn 0 1e99999999999 0\n"
        "vt 0.5\nvt 0.5 0.5 0\nvt inf 0\n"
        "f 1/1/1 2/3/2 3/2/3\nf 1/4/4 2//5 3/7/7\n";
    const RawMesh raw = parse_obj_text(text, "bad.obj");
    ASSERT_EQ(raw.normals.size(), 6u);  // every line kept, so indices still match
    ASSERT_EQ(raw.uvs.size(), 3u);
    EXPECT_EQ(raw.normals[0], (Vec3{0.0f, 0.0f, 1.0f}));
    for (std::size_t n = 1; n < raw.normals.size(); ++n) EXPECT_EQ(raw.normals[n], Vec3{}) << n;
    const std::vector<Corner> expected = {{0, 0, 0}, {1, -1, -1}, {2, -1, 1}, {0, -1, -1}, {1, -1, -1}, {2, -1, -1}};
    EXPECT_EQ(raw.triangle_corners, expected);
    ASSERT_EQ(raw.warnings.size(), 4u);  // dangling normals, bad normals, dangling and bad texture coordinates
    EXPECT_NE(raw.warnings[0].find("bad.obj:14: face normal index '7'"), std::string::npos) << raw.warnings[0];
    EXPECT_NE(raw.warnings[1].find("bad.obj:5: normal 'nan' is not a finite number"), std::string::npos) << raw.warnings[1];
    EXPECT_NE(raw.warnings[1].find("(4 more like it)"), std::string::npos) << raw.warnings[1];
    EXPECT_NE(raw.warnings[2].find("bad.obj:14: face texture coordinate index '4'"), std::string::npos) << raw.warnings[2];
    EXPECT_NE(raw.warnings[3].find("bad.obj:12: texture coordinate 'inf'"), std::string::npos) << raw.warnings[3];
    // Welding and the normals built from it cope: every slot's normal is recomputed or the file's.
    const Mesh mesh = build_mesh(raw, "bad.obj");
    EXPECT_EQ(mesh.triangle_count(), 2u);
    EXPECT_EQ(mesh.warnings, raw.warnings);
}

// What real files hold and other readers take in their stride: material files that are named
// but absent, object, group and smoothing lines, polylines, texture coordinates with one to
// three numbers, vertex colours, Windows and old Mac line ends, trailing spaces and tabs, a
// comment after a face, a UTF-8 byte-order mark. The positions and triangles are exactly
// those of the plain file, with no warning.
TEST(Leniency, EverydayObjQuirksLoadAsThePlainFile) {
    TempDir dir;
    const Loaded plain = load(dir.write("plain.obj", "v 0 0 0\nv 2 0 0\nv 0 3 0\nv 0 0 4\nf 1 2 3\nf 1 2 4 3\n"));
    const std::string quirky =
        "\xEF\xBB\xBF# exported\r\n"
        "mtllib no_such_file.mtl\r\n"
        "mtllib  \r\n"
        "o body\r\ng part one\r\ns off\r\ns 1\r\nusemtl not_defined_anywhere\r\n"
        "v 0 0 0 1\r\nv 2 0 0 0.5 0.5 0.5\t\r\nv 0 3 0   \r\nv 0 0 4 # top\r\n"
        "vt 0.5\r\nvt 0.5 0.25\r\nvt 0.5 0.25 0\r\nvn 0 0 1\r\n"
        "l 1 2\r\np 4\r\n"
        "f 1/1/1 2/2/1 3/3/1 # the base\r\n"
        "f 1/1 2/2 4/3 3/1\t \r\n";
    const Loaded loaded = load(dir.write("quirky.obj", quirky));
    EXPECT_EQ(loaded.positions, plain.positions);
    EXPECT_EQ(loaded.triangle_particles, plain.triangle_particles);
    EXPECT_TRUE(loaded.warnings.empty()) << loaded.warnings[0];
    // The same with old Mac line ends.
    std::string mac = quirky;
    mac.erase(std::remove(mac.begin(), mac.end(), '\n'), mac.end());
    EXPECT_EQ(load(dir.write("mac.obj", mac)).positions, plain.positions);
    // A byte-order mark before a vertex line does not hide that vertex.
    EXPECT_EQ(load(dir.write("bom.obj", "\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")).positions.size(), 3u);
}

// What moves or loses a particle is still refused, with the file and line.
TEST(Leniency, WhatWouldMoveAParticleIsStillRefused) {
    TempDir dir;
    const std::string head = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("a.obj", head + "vn 0 0 1\nf 1//1 2//1 9//1\n")), "a.obj:5:", "'9'");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("b.obj", head + "v 0 nan 1\n")), "b.obj:4:", "'nan'");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("c.obj", head + "v 0 0 0e99999999999\n")), "c.obj:4:", "exponent");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("d.obj", head + "f 1 2 3 4\n")), "d.obj:4:", "'4'");
    // UTF-16 (here with its byte-order mark): every other byte is zero.
    std::string utf16 = "\xFF\xFE";
    for (const char c : head) utf16 += std::string{c, '\0'};
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("e.obj", utf16)), "e.obj", "UTF-16");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("e.off", "\xFE\xFF" + std::string("\0O\0F\0F", 6))), "e.off", "UTF-16");
}

// OFF's variants: colour, normal and texture columns after a vertex's x y z, colours after a
// face's indices, the keyword optional, a byte-order mark. All give the plain file's positions.
TEST(Leniency, OffVariantsLoadAsThePlainFile) {
    TempDir dir;
    const Loaded plain = load(dir.write("plain.off", "OFF\n4 2 0\n0 0 0\n2 0 0\n0 3 0\n0 0 4\n3 0 1 2\n4 0 1 3 2\n"));
    const std::vector<std::pair<std::string, std::string>> variants = {
        {"coff.off", "COFF\n4 2 0\n0 0 0 255 0 0 255\n2 0 0 0 255 0 255\n0 3 0 0 0 255 255\n0 0 4 1 1 1 1\n"
                     "3 0 1 2 255 0 0\n4 0 1 3 2 0.5 0.5 0.5 1\n"},
        {"noff.off", "NOFF\n4 2 6\n0 0 0 0 0 -1\n2 0 0 1 0 0\n0 3 0 0 1 0\n0 0 4 0 0 1\n3 0 1 2\n4 0 1 3 2\n"},
        {"stcnoff.off", "STCNOFF 4 2 6\n0 0 0 0 0 -1 1 0 0 0 0\n2 0 0 1 0 0 1 0 0 1 0\n0 3 0 0 1 0 1 0 0 0 1\n"
                        "0 0 4 0 0 1 1 0 0 1 1\n3 0 1 2 3\n4 0 1 3 2\n"},
        {"keywordless.off", "# no keyword, as in many old files\n4 2 6\n0 0 0\n2 0 0\n0 3 0\n0 0 4\n3 0 1 2 1\n4 0 1 3 2\n"},
        {"crlf.off", "\xEF\xBB\xBFOFF\r\n4 2 0\r\n0 0 0 \r\n2 0 0\t\r\n0 3 0\r\n0 0 4\r\n3 0 1 2\r\n4 0 1 3 2\r\n"},
    };
    for (const auto& [name, text] : variants) {
        const Loaded loaded = load(dir.write(name, text));
        EXPECT_EQ(loaded.positions, plain.positions) << name;
        EXPECT_EQ(loaded.triangle_particles, plain.triangle_particles) << name;
        EXPECT_TRUE(loaded.warnings.empty()) << name;
    }
    // A fourth coordinate (4-D or homogeneous: 4OFF, nOFF) would move every particle, and a
    // binary file is not text: refused, saying so.
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("4d.off", "4OFF\n3 1 0\n0 0 0 1\n1 0 0 2\n0 1 0 1\n3 0 1 2\n")), "4d.off:1:",
                          "'4OFF'", "more than three coordinates");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("nd.off", "CnOFF\n4\n3 1 0\n")), "nd.off:1:", "more than three");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("bin.off", "OFF BINARY\n")), "bin.off:1:", "binary");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("what.off", "XOFF\n3 1 0\n")), "what.off:1:", "'XOFF'");
}

// --- Bodies as users bring them (generated_meshes.h) -------------------------------------------

// The extent of a mesh along each axis.
Vec3 extent(const Mesh& mesh) {
    Vec3 lo = mesh.positions[0], hi = lo;
    for (const Vec3& p : mesh.positions) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    return hi - lo;
}

// A standing figure (a capsule 1.8 m tall, 0.5 m across) in millimetres written y-up, in
// kilometres written z-up, and with normal indices that name nothing: each loads, with its
// size in its own units and its height along its own up axis (the loader changes neither:
// scale and rotation are parameters), and only the dangling normals give a warning. Sizes to
// 1e-6 relative: the text holds 9 significant digits and the extent is a float difference.
TEST(GeneratedMeshes, EachLoadsInItsUnitsAndUpAxis) {
    TempDir dir;
    struct Case {
        std::string name, text;
        UpAxis up;
        double unit;  // metres per mesh unit
        std::size_t warnings;
    };
    const std::vector<Case> cases = {
        {"figure_mm_yup.obj", to_obj(scaled(capsule(0.25, 1.8, UpAxis::Y), 1000.0)), UpAxis::Y, 0.001, 0},
        {"figure_km_zup.off", to_off(scaled(capsule(0.25, 1.8, UpAxis::Z), 0.001)), UpAxis::Z, 1000.0, 0},
        {"figure_km_yup.obj", to_obj(scaled(capsule(0.25, 1.8, UpAxis::Y), 0.001)), UpAxis::Y, 1000.0, 0},
        {"figure_dangling.obj", to_obj(scaled(capsule(0.25, 1.8, UpAxis::Z), 1000.0), {.dangling_normals = true}),
         UpAxis::Z, 0.001, 1},
    };
    for (const Case& c : cases) {
        const Mesh mesh = load_mesh(dir.write(c.name, c.text));
        EXPECT_EQ(mesh.particle_count(), 24u * 23u + 2u) << c.name;  // 23 rings of 24, two poles
        EXPECT_EQ(mesh.warnings.size(), c.warnings) << c.name;
        const Vec3 size = extent(mesh);
        const double height = c.up == UpAxis::Y ? size.y : size.z;
        const double across = c.up == UpAxis::Y ? size.z : size.y;
        EXPECT_NEAR(height * c.unit, 1.8, 1.8e-6) << c.name;
        EXPECT_NEAR(size.x * c.unit, 0.5, 0.5e-6) << c.name;
        EXPECT_LT(across * c.unit, 0.5 * (1 + 1e-6)) << c.name;  // 24 segments: 0.5 cos(7.5 deg) one way
        EXPECT_GT(height, 3.0 * std::max(double(size.x), across)) << c.name << ": the up axis is the tallest";
    }
    // The dangling normals do not move a particle: the same positions as the plain file.
    EXPECT_EQ(load_mesh(dir.file("figure_dangling.obj")).positions,
              load_mesh(dir.write("plain.obj", to_obj(scaled(capsule(0.25, 1.8, UpAxis::Z), 1000.0)))).positions);
    // Above a particle budget: a 12,000-vertex torus, as OBJ and as OFF, welded to no fewer.
    const PolyMesh ring = torus(1.0, 0.3, 120, 100);
    EXPECT_EQ(load_mesh(dir.write("torus.obj", to_obj(ring))).particle_count(), 12000u);
    EXPECT_EQ(load_mesh(dir.write("torus.off", to_off(ring))).particle_count(), 12000u);
}

// More distinct vertices than kMaxMeshParticles are refused (more than kMaxParticles load: the
// simulation reduces them, mesh_reduce.h).
TEST(LoadMesh, TooManyParticlesIsRefused) {
    TempDir dir;
    auto grid = [](std::size_t n) {
        std::string text;
        for (std::size_t i = 0; i < n; ++i) {
            text += "v " + std::to_string(i % 1000) + " " + std::to_string(i / 1000) + " 0\n";
        }
        return text;
    };
    // The most, plus one more vertex that welds to an existing particle: duplicates do not count.
    EXPECT_EQ(load_mesh(dir.write("max.obj", grid(kMaxMeshParticles) + "v 0 0 0\n")).particle_count(), kMaxMeshParticles);
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("over.obj", grid(kMaxMeshParticles + 1))), "over.obj",
                          std::to_string(kMaxMeshParticles).c_str());
    // Above kMaxParticles, below kMaxMeshParticles: loads.
    EXPECT_EQ(load_mesh(dir.write("more.obj", grid(kMaxParticles + 1))).particle_count(), kMaxParticles + 1);
}

}  // namespace
}  // namespace softbody::test

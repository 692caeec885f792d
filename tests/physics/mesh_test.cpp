// Meshes: welding the duplicates that exporters write at UV seams into single particles, and
// refusing broken files with a message that names the file (and line).
#include <cmath>
#include <random>
#include <set>
#include <sstream>

#include "physics/error.h"
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

// --- Loading ------------------------------------------------------------------------------------

TEST(LoadMesh, PointCloudWithoutFacesIsValid) {
    TempDir dir;
    const std::string path = dir.write("cloud.obj", "# points\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0 0 0\n");
    const Mesh mesh = load_mesh(path);
    EXPECT_EQ(mesh.particle_count(), 4u);
    EXPECT_EQ(mesh.triangle_count(), 0u);
    EXPECT_EQ(mesh.source, path);
    World world(Params{}, mesh);
    EXPECT_EQ(world.spring_count(), 6u);
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
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("normal.obj", "v 0 0 0\nvn 0 nan 1\n")), "normal.obj:2:");
}

TEST(LoadMesh, FaceIndexOutOfRangeGivesTheLine) {
    TempDir dir;
    const std::string head = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("a.obj", head + "f 1 2 3\nf 1 2 4\n")), "a.obj:5:", "'4'");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("b.obj", head + "f 0 1 2\n")), "b.obj:4:", "'0'");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("c.obj", head + "f -4 1 2\n")), "c.obj:4:", "'-4'");
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("d.obj", head + "f 1/5 2 3\n")), "d.obj:4:");
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

TEST(LoadMesh, TooManyParticlesIsRefused) {
    TempDir dir;
    auto grid = [](std::size_t n) {
        std::string text;
        for (std::size_t i = 0; i < n; ++i) {
            text += "v " + std::to_string(i % 200) + " " + std::to_string(i / 200) + " 0\n";
        }
        return text;
    };
    EXPECT_EQ(load_mesh(dir.write("max.obj", grid(kMaxParticles))).particle_count(), kMaxParticles);
    EXPECT_REFUSED_NAMING(load_mesh(dir.write("over.obj", grid(kMaxParticles + 1))), "over.obj", "20000");
    // Duplicates do not count: 20,001 vertices that weld to 20,000 particles are fine.
    EXPECT_EQ(load_mesh(dir.write("dup.obj", grid(kMaxParticles) + "v 0 0 0\n")).particle_count(), kMaxParticles);
}

}  // namespace
}  // namespace softbody::test

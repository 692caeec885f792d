// The renderer's CPU side, without GL: normals recomputed from a deformed mesh, interpolation,
// the springs sample, the camera, shader includes, the shadow map's reach on the floor, PNG files
// and the image comparison.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>

#include <glm/gtc/matrix_transform.hpp>

#include "overlays.h"
#include "physics/mesh.h"
#include "render/camera.h"
#include "render/deform.h"
#include "render/image.h"
#include "render/shader.h"
#include "shadow_footprint.h"

namespace softbody::render {
namespace {

const std::string kMeshes = SOFTBODY_ASSETS_DIR "/meshes/";

std::vector<glm::vec3> particles_of(const Mesh& mesh, glm::vec3 scale = glm::vec3(1.0f)) {
    std::vector<glm::vec3> p;
    for (const Vec3& v : mesh.positions) p.emplace_back(v.x * scale.x, v.y * scale.y, v.z * scale.z);
    return p;
}

// Each triangle's own (flat) normal, for checking which vertices must share it.
glm::vec3 face_normal(const Mesh& mesh, const std::vector<glm::vec3>& x, std::size_t t) {
    const auto& rv = mesh.render_vertices;
    const glm::vec3 a = x[rv[mesh.triangles[3 * t]].particle];
    const glm::vec3 b = x[rv[mesh.triangles[3 * t + 1]].particle];
    const glm::vec3 c = x[rv[mesh.triangles[3 * t + 2]].particle];
    return glm::normalize(glm::cross(b - a, c - a));
}

TEST(DeformedSurface, CubeKeepsHardEdgesWhenSquashed) {
    const Mesh mesh = load_mesh(kMeshes + "cube.obj");
    DeformedSurface surface;
    for (const glm::vec3 scale : {glm::vec3(1.0f), glm::vec3(1.3f, 1.3f, 0.4f)}) {
        const auto x = particles_of(mesh, scale);
        surface.update(mesh, x);
        ASSERT_EQ(surface.vertices().size(), mesh.render_vertices.size());
        for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
            const glm::vec3 n = face_normal(mesh, x, t);
            for (int c = 0; c < 3; ++c) {
                const SurfaceVertex& v = surface.vertices()[mesh.triangles[3 * t + c]];
                EXPECT_GT(glm::dot(v.normal, n), 0.9999f) << "a cube corner's normal must be its face's";
                EXPECT_EQ(v.position, x[mesh.render_vertices[mesh.triangles[3 * t + c]].particle]);
            }
        }
    }
}

TEST(DeformedSurface, SphereStaysSmoothAndFollowsTheSquash) {
    const Mesh mesh = load_mesh(kMeshes + "sphere.off");
    DeformedSurface surface;
    // Round: every normal points out from the centre.
    auto x = particles_of(mesh);
    surface.update(mesh, x);
    for (const SurfaceVertex& v : surface.vertices()) EXPECT_GT(glm::dot(v.normal, glm::normalize(v.position)), 0.995f);
    // Squashed to an ellipsoid with semi-axes a, a, c: the normal is along (x/a^2, y/a^2, z/c^2).
    const float a = 0.6f, c = 0.3f;
    x = particles_of(mesh, glm::vec3(a / 0.5f, a / 0.5f, c / 0.5f));
    surface.update(mesh, x);
    for (const SurfaceVertex& v : surface.vertices()) {
        const glm::vec3 p = v.position;
        const glm::vec3 expected = glm::normalize(glm::vec3(p.x / (a * a), p.y / (a * a), p.z / (c * c)));
        EXPECT_GT(glm::dot(v.normal, expected), 0.97f);
        EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-5f);
    }
}

TEST(DeformedSurface, FlipInvertsEveryNormal) {
    const Mesh mesh = load_mesh(kMeshes + "sphere.off");
    const auto x = particles_of(mesh);
    DeformedSurface straight, flipped;
    straight.update(mesh, x);
    flipped.update(mesh, x, true);
    for (std::size_t i = 0; i < straight.vertices().size(); ++i) {
        EXPECT_EQ(flipped.vertices()[i].normal, -straight.vertices()[i].normal);
    }
}

TEST(DeformedSurface, CollapsedTrianglesGiveNoNaN) {
    const Mesh mesh = load_mesh(kMeshes + "cube.obj");
    const std::vector<glm::vec3> x(mesh.particle_count(), glm::vec3(1.0f, 2.0f, 3.0f));
    DeformedSurface surface;
    surface.update(mesh, x);
    for (const SurfaceVertex& v : surface.vertices()) EXPECT_TRUE(std::isfinite(v.normal.x + v.normal.y + v.normal.z));
}

TEST(Interpolation, DrawsBetweenTheLastTwoTicks) {
    const Mesh mesh = load_mesh(kMeshes + "cube.obj");
    const std::size_t n = mesh.particle_count();
    std::vector<float> px(n, 0.0f), py(n, 0.0f), pz(n, 1.0f), cx(n, 4.0f), cy(n, 0.0f), cz(n, 2.0f);
    BodyView body;
    body.mesh = &mesh;
    body.positions = {cx.data(), cy.data(), cz.data(), n};
    body.previous_positions = {px.data(), py.data(), pz.data(), n};
    body.alpha = 0.25f;
    std::vector<glm::vec3> out;
    interpolate_positions(body, glm::vec3(0.0f, 0.0f, 0.01f), out);
    ASSERT_EQ(out.size(), n);
    EXPECT_FLOAT_EQ(out[0].x, 1.0f);
    EXPECT_FLOAT_EQ(out[0].z, 1.25f + 0.01f);
    body.alpha = 1.0f;
    interpolate_positions(body, glm::vec3(0.0f), out);
    EXPECT_FLOAT_EQ(out[0].x, 4.0f);
    body.positions.size = n - 1;
    EXPECT_THROW(interpolate_positions(body, glm::vec3(0.0f), out), std::invalid_argument);
}

TEST(SpringSample, SmallBodiesShowEverySpring) {
    const Mesh mesh = load_mesh(kMeshes + "cube.obj");
    const auto springs = sample_springs(mesh, 80);
    EXPECT_EQ(springs.size(), 28u);  // 8 particles: 8 * 7 / 2
}

TEST(SpringSample, LargeBodiesGetAFixedReadableSample) {
    const Mesh mesh = load_mesh(kMeshes + "sphere.off");
    const auto a = sample_springs(mesh, 80);
    const auto b = sample_springs(mesh, 80);
    ASSERT_EQ(a.size(), b.size());
    std::set<std::pair<std::uint32_t, std::uint32_t>> seen;
    std::size_t surface = 0;
    for (std::size_t k = 0; k < a.size(); ++k) {
        EXPECT_EQ(a[k].i, b[k].i);
        EXPECT_EQ(a[k].j, b[k].j);
        EXPECT_LT(a[k].i, a[k].j);
        EXPECT_LT(a[k].j, mesh.particle_count());
        EXPECT_TRUE(seen.insert({a[k].i, a[k].j}).second) << "no spring twice";
        surface += a[k].surface;
    }
    EXPECT_EQ(surface, 480u);  // every edge of a 162-vertex geodesic sphere (V + F - 2)
    EXPECT_EQ(a.size() - surface, 80u);  // the budget asked for
}

TEST(Camera, FramingFitsTheSphere) {
    Camera camera;
    camera.frame(glm::vec3(1.0f, 2.0f, 3.0f), 0.5f, 4.0f / 3.0f, 1.0f);
    EXPECT_NEAR(glm::length(camera.eye() - camera.target), camera.distance, 1e-4f);
    // Touching: the sphere's radius seen from the eye is exactly half the vertical field of view.
    EXPECT_NEAR(std::asin(0.5f / camera.distance), 0.5f * camera.fov_y, 1e-4f);
    camera.orbit(0.0f, 10.0f);
    EXPECT_LT(camera.pitch, 1.5708f);
    const glm::vec3 before = camera.target;
    camera.pan(1.0f, 0.0f);
    EXPECT_NEAR(glm::length(camera.target - before), 1.0f, 1e-5f);
    EXPECT_NEAR(camera.right().z, 0.0f, 1e-6f);
}

TEST(Shaders, IncludesAreExpandedWithLineMarkers) {
    const ExpandedShader body = expand_shader("body.frag.glsl");
    EXPECT_EQ(body.text.find("#include"), std::string::npos);
    EXPECT_NE(body.text.find("#line 1 1"), std::string::npos);
    ASSERT_EQ(body.files.size(), 2u);
    EXPECT_EQ(body.files[1], "lighting.glsl");
    EXPECT_THROW(expand_shader("missing.glsl"), ShaderError);
}

Image gradient(int w, int h) {
    Image image(w, h);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            std::uint8_t* p = image.pixel(x, y);
            p[0] = static_cast<std::uint8_t>(x * 255 / w);
            p[1] = static_cast<std::uint8_t>(y * 255 / h);
            p[2] = 128;
            p[3] = 255;
        }
    }
    return image;
}

// A sun map as the renderer makes one: orthographic along the sun's rays, about a sphere of
// radius r at c, to [0,1]^3.
glm::mat4 sun_map(glm::vec3 sun, glm::vec3 c, float r) {
    const glm::vec3 up = std::abs(sun.z) > 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1);
    const glm::mat4 view = glm::lookAt(c + sun * (r + 1.0f), c, up);
    const glm::mat4 to_unit = glm::translate(glm::mat4(1.0f), glm::vec3(0.5f)) * glm::scale(glm::mat4(1.0f), glm::vec3(0.5f));
    return to_unit * glm::ortho(-r, r, -r, r, 0.5f, 4.0f * r + 10.0f) * view;
}

// Every floor point whose lookup lands in the map's square is inside the rectangle (the floor
// outside it is drawn without lookups), and the rectangle is not much larger than the square's
// shadow on the floor: checked on a grid of points over a region four times as wide.
TEST(ShadowFootprint, HoldsEveryPointTheMapReachesAndLittleMore) {
    const float lift = 0.3f;  // larger than the renderer's, so that leaving it out would show
    for (const glm::vec3 sun : {glm::normalize(glm::vec3(0.45f, -0.35f, 0.82f)), glm::normalize(glm::vec3(-1.0f, 0.2f, 0.3f)),
                                glm::vec3(0.0f, 0.0f, 1.0f)}) {
        for (const float height : {0.0f, -2.5f}) {
            const glm::vec3 c(1.5f, -0.7f, height + 1.2f);
            const float r = 1.3f;
            const glm::mat4 map = sun_map(sun, c, r);
            const std::optional<FloorRect> rect = shadow_footprint(map, height, lift);
            ASSERT_TRUE(rect.has_value());
            const float reach = 4.0f * (r + (c.z - height) / sun.z);
            glm::vec2 low(INFINITY), high(-INFINITY);
            int inside = 0;
            for (int i = 0; i <= 400; ++i) {
                for (int j = 0; j <= 400; ++j) {
                    const glm::vec2 p = glm::vec2(c) + reach * (glm::vec2(i, j) / 200.0f - 1.0f);
                    const glm::vec4 uv = map * glm::vec4(p, height + lift, 1.0f);
                    if (uv.x < 0.0f || uv.x > 1.0f || uv.y < 0.0f || uv.y > 1.0f) continue;
                    ++inside;
                    low = glm::min(low, p);
                    high = glm::max(high, p);
                    EXPECT_LE(std::abs(p.x - rect->centre.x), rect->half_size.x) << p.x << " " << p.y;
                    EXPECT_LE(std::abs(p.y - rect->centre.y), rect->half_size.y) << p.x << " " << p.y;
                }
            }
            ASSERT_GT(inside, 100) << "the map's square reaches the floor";
            // The grid's spacing (reach / 200) plus the 1 % margin.
            const glm::vec2 most = 0.5f * (high - low) * 1.02f + glm::vec2(reach / 200.0f + 2e-3f);
            EXPECT_LE(rect->half_size.x, most.x);
            EXPECT_LE(rect->half_size.y, most.y);
        }
    }
    // The sun along the floor: the map's square reaches no bounded part of it.
    EXPECT_FALSE(shadow_footprint(sun_map(glm::vec3(1, 0, 0), glm::vec3(0, 0, 1), 1.0f), 0.0f, lift).has_value());
}

TEST(ShadowFootprint, OverlapOfTwoRectangles) {
    const std::optional<FloorRect> both = overlap({{0, 0}, {2, 1}}, {{1.5f, 0.5f}, {1, 1}});
    ASSERT_TRUE(both.has_value());
    EXPECT_FLOAT_EQ(both->centre.x, 1.25f);
    EXPECT_FLOAT_EQ(both->half_size.x, 0.75f);
    EXPECT_FLOAT_EQ(both->centre.y, 0.25f);
    EXPECT_FLOAT_EQ(both->half_size.y, 0.75f);
    EXPECT_FALSE(overlap({{0, 0}, {1, 1}}, {{3, 0}, {1, 1}}).has_value());
}

TEST(ImageCompare, IdenticalAndNoisyImagesMatch) {
    const CompareThresholds t;
    const Image a = gradient(320, 240);
    EXPECT_TRUE(images_match(compare_images(a, a, t), t));
    Image noisy = a;  // +-2 everywhere, as rounding on another CPU could give at most
    for (std::size_t i = 0; i < noisy.rgba.size(); i += 8) noisy.rgba[i] = static_cast<std::uint8_t>(noisy.rgba[i] ^ 1);
    const auto d = compare_images(noisy, a, t);
    EXPECT_TRUE(images_match(d, t));
    EXPECT_EQ(d.differing_pixels, 0);
}

TEST(ImageCompare, EachThresholdCatchesItsKindOfChange) {
    const CompareThresholds t;
    const Image a = gradient(320, 240);
    // A uniform shift below the per-pixel threshold: only the mean sees it.
    Image shifted = a;
    for (std::size_t i = 0; i < shifted.rgba.size(); i += 4) shifted.rgba[i + 2] = 140;
    auto d = compare_images(shifted, a, t);
    EXPECT_EQ(d.differing_pixels, 0);
    EXPECT_FALSE(images_match(d, t));
    // A small patch changed a lot: the mean barely moves, the fraction of differing pixels does.
    Image patch = a;
    for (int y = 0; y < 12; ++y) {
        for (int x = 0; x < 12; ++x) patch.pixel(x, y)[2] = 255;
    }
    d = compare_images(patch, a, t);
    EXPECT_EQ(d.differing_pixels, 144);
    EXPECT_FALSE(images_match(d, t));
    // A different size never matches.
    EXPECT_FALSE(images_match(compare_images(gradient(320, 200), a, t), t));
}

TEST(ImageCompare, DiffImageMarksDifferingPixelsRed) {
    const CompareThresholds t;
    const Image a = gradient(64, 48);
    Image b = a;
    b.pixel(5, 7)[0] = static_cast<std::uint8_t>(b.pixel(5, 7)[0] + 100);
    const Image diff = difference_image(b, a, t);
    EXPECT_EQ(diff.pixel(5, 7)[0], 255);
    EXPECT_EQ(diff.pixel(5, 7)[1], 0);
    EXPECT_EQ(diff.pixel(6, 7)[0], diff.pixel(6, 7)[1]);  // unchanged: grey
}

TEST(Png, RoundTripsAndWritesTheSameBytes) {
    const auto dir = std::filesystem::temp_directory_path() / "softbody_render_unit_png";
    std::filesystem::create_directories(dir);
    const Image a = gradient(100, 60);
    write_png((dir / "a.png").string(), a);
    write_png((dir / "b.png").string(), a);
    const Image back = read_png((dir / "a.png").string());
    EXPECT_EQ(back.width, 100);
    EXPECT_EQ(back.rgba, a.rgba);
    auto bytes = [](const std::filesystem::path& p) {
        std::ifstream in(p, std::ios::binary);
        return std::vector<char>(std::istreambuf_iterator<char>(in), {});
    };
    EXPECT_EQ(bytes(dir / "a.png"), bytes(dir / "b.png"));
    EXPECT_THROW(read_png((dir / "missing.png").string()), std::runtime_error);
    EXPECT_THROW(write_png((dir / "no" / "such" / "dir.png").string(), a), std::runtime_error);
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace softbody::render

// The renderer in a real (offscreen) GL context: shader errors name their file and carry the
// driver's log, drawing is repeatable, leaves GL as documented, and never changes the world.
#include <gtest/gtest.h>

#include <glad/gl.h>

#include <memory>

#include "body_view.h"
#include "offscreen_context.h"
#include "../physics/one_body_world.h"
#include "physics/world.h"
#include "render/renderer.h"
#include "render/shader.h"

namespace softbody {
using test::FlatKeys;
using test::OneBodyWorld;
namespace {

constexpr int kW = 160, kH = 120;

class RendererTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        context_ = std::make_unique<app::OffscreenContext>(kW, kH);
        renderer_ = std::make_unique<render::Renderer>(context_->loader());
    }
    static void TearDownTestSuite() {
        renderer_.reset();
        context_.reset();
    }
    static std::unique_ptr<app::OffscreenContext> context_;
    static std::unique_ptr<render::Renderer> renderer_;
};
std::unique_ptr<app::OffscreenContext> RendererTest::context_;
std::unique_ptr<render::Renderer> RendererTest::renderer_;

FlatKeys falling_cube() {
    FlatKeys p;
    p.mesh = SOFTBODY_ASSETS_DIR "/meshes/cube.obj";
    p.init_height = 1.0f;
    p.particle_mass = 0.1f;
    p.stiffness = 20.0f;
    return p;
}

render::Frame frame_of(const World& world, float alpha = 1.0f) {
    render::Frame frame;
    app::world_view(world, alpha, frame);
    frame.camera.frame({0.0f, 0.0f, 0.8f}, 1.2f, float(kW) / float(kH));
    return frame;
}

TEST_F(RendererTest, CompileErrorNamesTheFileAndCarriesTheDriverLog) {
    const std::string vs = "#version 330 core\nvoid main() { gl_Position = vec4(0.0); }\n";
    const std::string fs = "#version 330 core\nout vec4 c;\nvoid main() { c = vec4(undeclared_name); }\n";
    try {
        render::ShaderProgram::from_source("ok.vert.glsl", vs, "broken.frag.glsl", fs);
        FAIL() << "a broken shader must throw";
    } catch (const render::ShaderError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("broken.frag.glsl"), std::string::npos) << what;
        EXPECT_NE(what.find("failed to compile"), std::string::npos) << what;
        EXPECT_NE(what.find("undeclared_name"), std::string::npos) << "the driver's log: " << what;
    }
}

TEST_F(RendererTest, LinkErrorNamesBothFiles) {
    const std::string vs = "#version 330 core\nout vec3 v;\nvoid main() { v = vec3(1.0); gl_Position = vec4(0.0); }\n";
    const std::string fs = "#version 330 core\nin vec4 v;\nout vec4 c;\nvoid main() { c = v; }\n";
    try {
        render::ShaderProgram::from_source("a.vert.glsl", vs, "b.frag.glsl", fs);
        FAIL() << "mismatched stages must not link";
    } catch (const render::ShaderError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("a.vert.glsl + b.frag.glsl failed to link"), std::string::npos) << what;
    }
}

TEST_F(RendererTest, DrawingTwiceGivesTheSamePixels) {
    OneBodyWorld world(falling_cube(), load_mesh(falling_cube().mesh));
    world.run(10);
    renderer_->draw(frame_of(world), kW, kH);
    const render::Image a = renderer_->read_back();
    renderer_->draw(frame_of(world), kW, kH);
    const render::Image b = renderer_->read_back();
    ASSERT_EQ(a.width, kW);
    EXPECT_EQ(a.rgba, b.rgba);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(RendererTest, RenderingNeverChangesTheSimulation) {
    OneBodyWorld world(falling_cube(), load_mesh(falling_cube().mesh));
    world.run(20);
    const std::uint64_t before = world.state_hash();
    render::Frame frame = frame_of(world, 0.5f);
    frame.overlays = {true, true, true, true, true};
    renderer_->draw(frame, kW, kH);
    EXPECT_EQ(world.state_hash(), before);
}

TEST_F(RendererTest, LeavesGlStateAtTheDefaults) {
    OneBodyWorld world(falling_cube(), load_mesh(falling_cube().mesh));
    render::Frame frame = frame_of(world);
    frame.appearance.body = render::BodyStyle::Ghost;
    frame.overlays.springs = true;
    renderer_->draw(frame, kW, kH);
    EXPECT_FALSE(glIsEnabled(GL_BLEND));
    EXPECT_FALSE(glIsEnabled(GL_DEPTH_TEST));
    EXPECT_FALSE(glIsEnabled(GL_CULL_FACE));
    GLint program = -1, vao = -1, framebuffer = -1;
    glGetIntegerv(GL_CURRENT_PROGRAM, &program);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao);
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &framebuffer);
    EXPECT_EQ(program, 0);
    EXPECT_EQ(vao, 0);
    EXPECT_EQ(framebuffer, 0);
}

TEST_F(RendererTest, InterpolatesBetweenTicks) {
    OneBodyWorld world(falling_cube(), load_mesh(falling_cube().mesh));
    world.run(10);
    // alpha = 0 draws the previous tick: the same picture as a world one tick behind.
    OneBodyWorld behind(falling_cube(), load_mesh(falling_cube().mesh));
    behind.run(9);
    renderer_->draw(frame_of(behind), kW, kH);
    const render::Image previous = renderer_->read_back();
    renderer_->draw(frame_of(world, 0.0f), kW, kH);
    EXPECT_EQ(renderer_->read_back().rgba, previous.rgba);
    renderer_->draw(frame_of(world, 0.5f), kW, kH);
    EXPECT_NE(renderer_->read_back().rgba, previous.rgba);
}

TEST_F(RendererTest, APointCloudDrawsWithoutASurface) {
    FlatKeys p = falling_cube();
    p.mesh = SOFTBODY_SOURCE_DIR "/tests/render/meshes/lattice.off";
    OneBodyWorld world(p, load_mesh(p.mesh));
    render::Frame frame = frame_of(world);
    frame.overlays.particles = true;
    renderer_->draw(frame, kW, kH);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    const render::Image with_overlay = renderer_->read_back();
    // Hidden, nothing of the body shows; drawn as a solid body, its particles are the body,
    // with or without the particles overlay (a user's point cloud shows at the defaults).
    frame.overlays.particles = false;
    frame.appearance.body = render::BodyStyle::Hidden;
    renderer_->draw(frame, kW, kH);
    const render::Image empty = renderer_->read_back();
    frame.appearance.body = render::BodyStyle::Solid;
    renderer_->draw(frame, kW, kH);
    const render::Image plain = renderer_->read_back();
    EXPECT_NE(plain.rgba, empty.rgba) << "the particles must show";
    EXPECT_EQ(plain.rgba, with_overlay.rgba) << "the overlay adds nothing to a point cloud drawn as its particles";
}

}  // namespace
}  // namespace softbody

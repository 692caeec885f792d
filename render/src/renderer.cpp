// The frame, pass by pass (Renderer::draw, one function of State each):
//   1. each soft body's particles interpolated, normals recomputed, vertices streamed
//      (deform.h); each rigid body's fixed mesh uploaded once and its model matrix made
//      (prepare_soft, prepare_rigid); the overlays' lines and spheres (build_overlays)
//   2. the sun's shadow map: depth moments of the bodies (and overlay spheres), mipmapped
//      (draw_shadow_map)
//   3. multisampled (begin_scene): the floor (grid, soft shadows, contact darkening:
//      draw_ground; the shadow map read only where it reaches), the solid bodies
//      (draw_solid_bodies), the sky where nothing else is (draw_sky), the overlays and
//      see-through soft bodies, the always-visible markers (draw_overlays)
//   4. resolve the samples, copy to the caller's framebuffer (resolve)
#include "render/renderer.h"

#include <glad/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gl_util.h"
#include "overlays.h"
#include "render/deform.h"
#include "render/shader.h"
#include "shadow_footprint.h"

namespace softbody::render {

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The sun: high and to one side, so the shadow falls beside the body as well as under it.
const glm::vec3 kSunDirection = glm::normalize(glm::vec3(-0.62f, 0.05f, 0.78f));
constexpr int kShadowMapSize = 512;
constexpr float kSunAngularRadius = 0.06f;  // rad: a soft studio light rather than the real sun
constexpr glm::vec3 kFloorColor{0.64f, 0.63f, 0.60f};
constexpr float kGhostOpacity = 0.28f;

std::string gl_string(GLenum name) {
    const auto* text = reinterpret_cast<const char*>(glGetString(name));
    return text ? text : "";
}

void set(GLint location, const glm::mat4& m) { glUniformMatrix4fv(location, 1, GL_FALSE, glm::value_ptr(m)); }
void set(GLint location, const glm::mat3& m) { glUniformMatrix3fv(location, 1, GL_FALSE, glm::value_ptr(m)); }
void set(GLint location, const glm::vec3& v) { glUniform3fv(location, 1, glm::value_ptr(v)); }
void set(GLint location, const glm::vec2& v) { glUniform2fv(location, 1, glm::value_ptr(v)); }
void set(GLint location, float f) { glUniform1f(location, f); }
void set(GLint location, int i) { glUniform1i(location, i); }

// Power of ten (times 1, 2 or 5) near the body's diameter: the grid stays readable whether
// the body is a centimetre or ten metres across.
float grid_spacing(float radius) {
    const float target = std::max(2.0f * radius, 1e-3f);
    const float decade = std::pow(10.0f, std::floor(std::log10(target)));
    for (float step : {1.0f, 2.0f, 5.0f}) {
        if (decade * step >= target * 0.7f) return decade * step;
    }
    return decade * 10.0f;
}

}  // namespace

// One mesh on the GPU: its vertices (streamed every frame for a soft body, uploaded once for
// a rigid one), its triangles, and each vertex's material coordinates.
struct MeshGpu {
    gl::VertexArray vao;
    gl::Buffer vbo, ebo, material;
    const Mesh* mesh = nullptr;  // what the buffers hold (with its sizes, to notice a new mesh)
    std::size_t render_vertices = 0, indices = 0;
    bool closed = false;         // every edge shared by two triangles: back faces can be culled

    void create();
    // Uploads the triangles and material coordinates when `m` is not what the buffers hold;
    // returns whether it did.
    bool upload_topology(const Mesh& m);
    GLsizei index_count() const { return static_cast<GLsizei>(indices); }
};

// A soft body this frame: its particles, its recomputed surface, its shape.
struct SoftDraw {
    MeshGpu gpu;
    std::vector<glm::vec3> particles;
    std::vector<float> sx, sy, sz, fx, fy, fz;  // skinning: simulated particles in, full ones out
    std::vector<glm::vec3> full;                // a reduced body's full-resolution particles
    DeformedSurface surface;
    BodyShape shape;
    glm::vec3 color{1.0f};
    bool has_surface = false;
};

// A rigid body this frame: its fixed mesh, and where it is.
struct RigidDraw {
    MeshGpu gpu;
    DeformedSurface surface;  // computed once, in body axes
    glm::mat4 model{1.0f};
    glm::mat3 normal_matrix{1.0f};
    glm::vec3 low{0.0f}, high{0.0f};  // world bounding box
};

// The bodies of a frame as one shape: for fitting the sun's shadow map, sizing the grid, the
// haze and the markers, and darkening the floor under each body.
struct SceneShape {
    glm::vec3 centre{0.0f};
    float radius = 0.0f;      // of a sphere about `centre` holding every body
    float body_size = 1e-3f;  // the largest moving body's radius (at rest, for a soft body)
    std::vector<glm::vec3> occluder_centres, occluder_axes;
    bool any = false;
};

// What the passes of one frame share: the frame, the image's size, the camera's matrices.
struct FramePass {
    const Frame& frame;
    int width = 0, height = 0;
    float aspect = 1.0f;
    glm::mat4 view_projection{1.0f};
    glm::vec3 eye{0.0f};
};

// The sun's shadow map as the lit passes read it (set_lighting): off when there is nothing to
// cast a shadow, or shadows are turned off.
struct SunShadow {
    bool on = false;
    glm::mat4 matrix{1.0f};       // world to the map's texture coordinates and depth
    float penumbra_scale = 0.0f;  // the penumbra's width per unit of depth behind the occluder
    float normal_offset = 0.0f;   // how far a surface is lifted along its normal before the lookup
};

struct Renderer::State {
    RendererInfo info;
    DrawTimings timings;

    // The floor in two programs: `ground` where the sun's shadow map reaches, `ground_sunlit`
    // (no lookups) elsewhere.
    ShaderProgram sky, ground, ground_sunlit, body, shadow, sphere_shadow, line, sphere;
    gl::VertexArray empty_vao;  // for draws that make their vertices from gl_VertexID

    std::vector<SoftDraw> soft;
    std::vector<RigidDraw> rigid;

    // Overlays: one instance buffer each for lines and spheres.
    gl::VertexArray line_vao, sphere_vao;
    gl::Buffer line_vbo, sphere_vbo;

    // Multisampled target, and the single-sample one it resolves into.
    gl::Framebuffer msaa_fbo, resolve_fbo;
    gl::Renderbuffer msaa_color, msaa_depth, resolve_color;
    int fb_width = 0, fb_height = 0, fb_samples = 0;

    // Shadow map: depth moments, mipmapped (see lighting.glsl).
    gl::Framebuffer shadow_fbo;
    gl::Texture shadow_texture;
    gl::Renderbuffer shadow_depth;

    OverlayBuilder overlay_builder;
    OverlayGeometry overlays;

    void build_programs();
    void build_buffers();
    void ensure_targets(int width, int height, int samples);
    void prepare_soft(const Frame& frame);
    void prepare_rigid(const Frame& frame);
    void set_lighting(const ShaderProgram& program, const glm::vec3& eye, const glm::mat4& shadow_matrix,
                      bool shadows, float penumbra_scale, float normal_offset) const;
    void draw_lines(const std::vector<LineInstance>& lines, const glm::mat4& view_projection, int width, int height,
                    const glm::vec3& eye);
    void draw_spheres(const std::vector<SphereInstance>& spheres, const Camera& camera, float aspect,
                      const glm::mat4& shadow_matrix);

    // draw()'s passes, in the order it makes them.
    void build_overlays(const Frame& frame, const SceneShape& scene);
    SunShadow draw_shadow_map(const Appearance& look, const SceneShape& scene);
    void begin_scene(int width, int height, int samples);
    void draw_ground(const FramePass& pass, const SceneShape& scene, const SunShadow& sun);
    void draw_floor_rect(const ShaderProgram& program, const FramePass& pass, const SceneShape& scene, const SunShadow& sun,
                         const FloorRect& rect);
    void draw_body(const FramePass& pass, const SunShadow& sun, const MeshGpu& gpu, const glm::mat4& model,
                   const glm::mat3& normal_matrix, const glm::vec3& color, float size, float opacity, bool two_sided);
    void draw_soft_surfaces(const FramePass& pass, const SunShadow& sun, float opacity, bool two_sided);
    void draw_solid_bodies(const FramePass& pass, const SunShadow& sun);
    void draw_sky(const FramePass& pass);
    void draw_overlays(const FramePass& pass, const SunShadow& sun);
    void resolve(int width, int height, unsigned target_framebuffer);
};

Renderer::Renderer(Loader loader) : state_(std::make_unique<State>()) {
    const int version = gladLoadGL(reinterpret_cast<GLADloadfunc>(loader));
    if (version == 0) throw std::runtime_error("cannot load OpenGL functions from the current context");
    if (GLAD_VERSION_MAJOR(version) * 10 + GLAD_VERSION_MINOR(version) < 33) {
        throw std::runtime_error("OpenGL 3.3 core is needed, the context gives " +
                                 std::to_string(GLAD_VERSION_MAJOR(version)) + "." +
                                 std::to_string(GLAD_VERSION_MINOR(version)));
    }
    RendererInfo& info = state_->info;
    info.vendor = gl_string(GL_VENDOR);
    info.renderer = gl_string(GL_RENDERER);
    info.version = gl_string(GL_VERSION);
    info.glsl_version = gl_string(GL_SHADING_LANGUAGE_VERSION);
    glGetIntegerv(GL_MAX_SAMPLES, &info.max_samples);
    GLint renderbuffer = 0, viewport[2] = {0, 0};
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &renderbuffer);
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
    info.max_size = std::min({renderbuffer, viewport[0], viewport[1]});
    state_->build_programs();
    state_->build_buffers();
}

Renderer::~Renderer() = default;

const RendererInfo& Renderer::info() const { return state_->info; }
const DrawTimings& Renderer::timings() const { return state_->timings; }

void Renderer::State::build_programs() {
    sky = ShaderProgram("sky.vert.glsl", "sky.frag.glsl");
    ground = ShaderProgram("ground.vert.glsl", "ground.frag.glsl");
    ground_sunlit = ShaderProgram("ground.vert.glsl", "ground_sunlit.frag.glsl");
    body = ShaderProgram("body.vert.glsl", "body.frag.glsl");
    shadow = ShaderProgram("shadow.vert.glsl", "shadow.frag.glsl");
    sphere_shadow = ShaderProgram("sphere_shadow.vert.glsl", "sphere_shadow.frag.glsl");
    line = ShaderProgram("line.vert.glsl", "line.frag.glsl");
    sphere = ShaderProgram("sphere.vert.glsl", "sphere.frag.glsl");
}

void Renderer::State::build_buffers() {
    empty_vao = gl::make_vertex_array();
    line_vao = gl::make_vertex_array();
    line_vbo = gl::make_buffer();
    glBindVertexArray(line_vao.id());
    glBindBuffer(GL_ARRAY_BUFFER, line_vbo.id());
    const auto line_attribute = [](GLuint index, GLint size, std::size_t offset) {
        glEnableVertexAttribArray(index);
        glVertexAttribPointer(index, size, GL_FLOAT, GL_FALSE, sizeof(LineInstance), reinterpret_cast<void*>(offset));
        glVertexAttribDivisor(index, 1);
    };
    line_attribute(0, 3, offsetof(LineInstance, from));
    line_attribute(1, 3, offsetof(LineInstance, to));
    line_attribute(2, 4, offsetof(LineInstance, color));
    line_attribute(3, 1, offsetof(LineInstance, width));

    sphere_vao = gl::make_vertex_array();
    sphere_vbo = gl::make_buffer();
    glBindVertexArray(sphere_vao.id());
    glBindBuffer(GL_ARRAY_BUFFER, sphere_vbo.id());
    const auto sphere_attribute = [](GLuint index, GLint size, std::size_t offset) {
        glEnableVertexAttribArray(index);
        glVertexAttribPointer(index, size, GL_FLOAT, GL_FALSE, sizeof(SphereInstance), reinterpret_cast<void*>(offset));
        glVertexAttribDivisor(index, 1);
    };
    sphere_attribute(0, 3, offsetof(SphereInstance, centre));
    sphere_attribute(1, 1, offsetof(SphereInstance, radius));
    sphere_attribute(2, 4, offsetof(SphereInstance, color));
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);

    // Shadow map: moments (z, z^2) in a float texture with its mip levels, and a depth buffer
    // to keep the nearest surface.
    shadow_texture = gl::make_texture();
    glBindTexture(GL_TEXTURE_2D, shadow_texture.id());
    int levels = 1;
    while ((kShadowMapSize >> levels) > 0) ++levels;
    for (int level = 0; level < levels; ++level) {
        const int size = std::max(1, kShadowMapSize >> level);
        glTexImage2D(GL_TEXTURE_2D, level, GL_RG32F, size, size, 0, GL_RG, GL_FLOAT, nullptr);
    }
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, levels - 1);
    glBindTexture(GL_TEXTURE_2D, 0);
    shadow_depth = gl::make_renderbuffer();
    glBindRenderbuffer(GL_RENDERBUFFER, shadow_depth.id());
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, kShadowMapSize, kShadowMapSize);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    shadow_fbo = gl::make_framebuffer();
    glBindFramebuffer(GL_FRAMEBUFFER, shadow_fbo.id());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, shadow_texture.id(), 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, shadow_depth.id());
    gl::check_framebuffer(GL_FRAMEBUFFER, "shadow map");
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void Renderer::State::ensure_targets(int width, int height, int samples) {
    if (width == fb_width && height == fb_height && samples == fb_samples && msaa_fbo) return;
    msaa_fbo = gl::make_framebuffer();
    msaa_color = gl::make_renderbuffer();
    msaa_depth = gl::make_renderbuffer();
    glBindRenderbuffer(GL_RENDERBUFFER, msaa_color.id());
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, width, height);
    glBindRenderbuffer(GL_RENDERBUFFER, msaa_depth.id());
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH24_STENCIL8, width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, msaa_fbo.id());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, msaa_color.id());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, msaa_depth.id());
    gl::check_framebuffer(GL_FRAMEBUFFER, "scene framebuffer");

    resolve_fbo = gl::make_framebuffer();
    resolve_color = gl::make_renderbuffer();
    glBindRenderbuffer(GL_RENDERBUFFER, resolve_color.id());
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, resolve_fbo.id());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, resolve_color.id());
    gl::check_framebuffer(GL_FRAMEBUFFER, "resolve framebuffer");
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    fb_width = width;
    fb_height = height;
    fb_samples = samples;
}

void MeshGpu::create() {
    vao = gl::make_vertex_array();
    vbo = gl::make_buffer();
    ebo = gl::make_buffer();
    material = gl::make_buffer();
    glBindVertexArray(vao.id());
    glBindBuffer(GL_ARRAY_BUFFER, vbo.id());
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(SurfaceVertex), reinterpret_cast<void*>(offsetof(SurfaceVertex, position)));
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(SurfaceVertex), reinterpret_cast<void*>(offsetof(SurfaceVertex, normal)));
    glBindBuffer(GL_ARRAY_BUFFER, material.id());
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo.id());
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
}

bool MeshGpu::upload_topology(const Mesh& m) {
    if (!vao) create();
    if (mesh == &m && render_vertices == m.render_vertices.size() && indices == m.triangles.size()) return false;
    glBindVertexArray(vao.id());
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(m.triangles.size() * sizeof(std::uint32_t)),
                 m.triangles.data(), GL_STATIC_DRAW);
    glBindVertexArray(0);
    // Material coordinates: the mesh's own vertex positions about their centre, in units of the
    // mesh's radius. They move with the body, so a pattern drawn from them shows it roll.
    glm::dvec3 centre(0.0);
    for (const Vec3& p : m.positions) centre += glm::dvec3(p.x, p.y, p.z);
    centre /= double(std::max<std::size_t>(m.positions.size(), 1));
    double radius = 1e-9;
    for (const Vec3& p : m.positions) radius = std::max(radius, glm::length(glm::dvec3(p.x, p.y, p.z) - centre));
    std::vector<glm::vec3> coordinates(m.render_vertices.size());
    for (std::size_t i = 0; i < coordinates.size(); ++i) {
        const Vec3& p = m.positions[m.render_vertices[i].particle];
        coordinates[i] = glm::vec3((glm::dvec3(p.x, p.y, p.z) - centre) / radius);
    }
    glBindBuffer(GL_ARRAY_BUFFER, material.id());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(coordinates.size() * sizeof(glm::vec3)), coordinates.data(),
                 GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    // Closed: every edge (on particles) belongs to exactly two triangles.
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
    for (std::size_t k = 0; k + 2 < m.triangles.size(); k += 3) {
        for (std::size_t e = 0; e < 3; ++e) {
            std::uint32_t a = m.render_vertices[m.triangles[k + e]].particle;
            std::uint32_t b = m.render_vertices[m.triangles[k + (e + 1) % 3]].particle;
            ++edges[{std::min(a, b), std::max(a, b)}];
        }
    }
    closed = !edges.empty() && std::all_of(edges.begin(), edges.end(), [](const auto& e) { return e.second == 2; });
    mesh = &m;
    render_vertices = m.render_vertices.size();
    indices = m.triangles.size();
    return true;
}

// Each soft body's particles this frame, its shape, and its surface streamed to the GPU.
void Renderer::State::prepare_soft(const Frame& frame) {
    const auto start = Clock::now();
    const Appearance& look = frame.appearance;
    soft.resize(frame.soft_bodies.size());
    for (std::size_t b = 0; b < soft.size(); ++b) {
        const BodyView& view = frame.soft_bodies[b];
        SoftDraw& d = soft[b];
        interpolate_positions(view, frame.debug.body_offset + view.offset, d.particles);
        d.shape = measure_body(d.particles, view.rest_positions);
        d.color = view.color.value_or(look.body_color);
        const bool skinned = view.surface && !view.skin.empty() && !frame.debug.particle_mesh;
        const Mesh* drawn = skinned ? view.surface : view.mesh;
        d.has_surface = drawn && drawn->triangle_count() > 0 && look.body != BodyStyle::Hidden &&
                        look.body != BodyStyle::Wireframe;
        if (!d.has_surface) continue;
        if (drawn == view.mesh) {
            d.surface.update(*view.mesh, d.particles, frame.debug.flip_normals);
            continue;
        }
        // A reduced body: every particle of the full mesh from the three simulated ones it follows.
        const std::size_t n = d.particles.size(), full = view.skin.size();
        for (auto* v : {&d.sx, &d.sy, &d.sz}) v->resize(n);
        for (auto* v : {&d.fx, &d.fy, &d.fz}) v->resize(full);
        for (std::size_t i = 0; i < n; ++i) {
            d.sx[i] = d.particles[i].x;
            d.sy[i] = d.particles[i].y;
            d.sz[i] = d.particles[i].z;
        }
        apply_skinning(view.skin, d.sx.data(), d.sy.data(), d.sz.data(), d.fx.data(), d.fy.data(), d.fz.data());
        d.full.resize(full);
        for (std::size_t i = 0; i < full; ++i) d.full[i] = {d.fx[i], d.fy[i], d.fz[i]};
        d.surface.update(*drawn, d.full, frame.debug.flip_normals);
    }
    timings.surface_ms = ms_since(start);
    const auto upload_start = Clock::now();
    for (std::size_t b = 0; b < soft.size(); ++b) {
        SoftDraw& d = soft[b];
        if (!d.has_surface) continue;
        const BodyView& view = frame.soft_bodies[b];
        const bool skinned = view.surface && !view.skin.empty() && !frame.debug.particle_mesh;
        d.gpu.upload_topology(skinned ? *view.surface : *view.mesh);
        const auto& vertices = d.surface.vertices();
        gl::stream(GL_ARRAY_BUFFER, d.gpu.vbo.id(), vertices.data(), static_cast<GLsizeiptr>(vertices.size() * sizeof(SurfaceVertex)));
    }
    timings.upload_ms = ms_since(upload_start);
}

// Each rigid body's fixed mesh (uploaded once), model matrix and world bounding box.
void Renderer::State::prepare_rigid(const Frame& frame) {
    rigid.resize(frame.rigid_bodies.size());
    for (std::size_t b = 0; b < rigid.size(); ++b) {
        const RigidBodyView& view = frame.rigid_bodies[b];
        RigidDraw& d = rigid[b];
        d.model = model_matrix(view);
        d.model[3] += glm::vec4(frame.debug.body_offset, 0.0f);
        d.normal_matrix = glm::transpose(glm::inverse(glm::mat3(d.model)));
        d.low = d.high = glm::vec3(d.model[3]);
        if (!view.mesh || view.mesh->triangle_count() == 0) continue;
        if (d.gpu.upload_topology(*view.mesh)) {
            std::vector<glm::vec3> points(view.mesh->positions.size());
            for (std::size_t i = 0; i < points.size(); ++i) {
                const Vec3& p = view.mesh->positions[i];
                points[i] = {p.x, p.y, p.z};
            }
            d.surface.update(*view.mesh, points);
            const auto& vertices = d.surface.vertices();
            glBindBuffer(GL_ARRAY_BUFFER, d.gpu.vbo.id());
            glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(SurfaceVertex)), vertices.data(),
                         GL_STATIC_DRAW);
            glBindBuffer(GL_ARRAY_BUFFER, 0);
        }
        bool first = true;
        for (const SurfaceVertex& v : d.surface.vertices()) {
            const glm::vec3 p(d.model * glm::vec4(v.position, 1.0f));
            d.low = first ? p : glm::min(d.low, p);
            d.high = first ? p : glm::max(d.high, p);
            first = false;
        }
    }
}

void Renderer::State::set_lighting(const ShaderProgram& program, const glm::vec3& eye, const glm::mat4& shadow_matrix,
                                   bool shadows, float penumbra_scale, float normal_offset) const {
    set(program.uniform("u_sun_dir"), kSunDirection);
    set(program.uniform("u_eye"), eye);
    set(program.uniform("u_shadow_moments"), 0);
    set(program.uniform("u_shadow_matrix"), shadow_matrix);
    set(program.uniform("u_shadows"), shadows ? 1.0f : 0.0f);
    set(program.uniform("u_shadow_size"), float(kShadowMapSize));
    set(program.uniform("u_penumbra_scale"), penumbra_scale);
    set(program.uniform("u_shadow_normal_offset"), normal_offset);
}

void Renderer::State::draw_lines(const std::vector<LineInstance>& lines, const glm::mat4& view_projection, int width,
                                 int height, const glm::vec3& eye) {
    if (lines.empty()) return;
    line.use();
    set(line.uniform("u_view_projection"), view_projection);
    set(line.uniform("u_viewport"), glm::vec2(float(width), float(height)));
    set(line.uniform("u_eye"), eye);
    gl::stream(GL_ARRAY_BUFFER, line_vbo.id(), lines.data(), static_cast<GLsizeiptr>(lines.size() * sizeof(LineInstance)));
    glBindVertexArray(line_vao.id());
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(lines.size()));
}

void Renderer::State::draw_spheres(const std::vector<SphereInstance>& spheres, const Camera& camera, float aspect,
                                   const glm::mat4& shadow_matrix) {
    if (spheres.empty()) return;
    sphere.use();
    const glm::mat4 view = camera.view();
    set(sphere.uniform("u_view"), view);
    set(sphere.uniform("u_projection"), camera.projection(aspect));
    set(sphere.uniform("u_view_to_world"), glm::transpose(glm::mat3(view)));
    set_lighting(sphere, camera.eye(), shadow_matrix, false, 0.0f, 0.0f);
    gl::stream(GL_ARRAY_BUFFER, sphere_vbo.id(), spheres.data(),
               static_cast<GLsizeiptr>(spheres.size() * sizeof(SphereInstance)));
    glBindVertexArray(sphere_vao.id());
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(spheres.size()));
}

namespace {

constexpr int kMaxOccluders = 16;  // as in floor.glsl

SceneShape measure_scene(const Frame& frame, const std::vector<SoftDraw>& soft, const std::vector<RigidDraw>& rigid) {
    SceneShape scene;
    struct Box {
        glm::vec3 low, high;
        float size;  // the body's radius, for its occluder's smallest axis
    };
    std::vector<Box> boxes;
    for (const SoftDraw& d : soft) {
        if (d.particles.empty()) continue;
        boxes.push_back({d.shape.low, d.shape.high, std::max(d.shape.rest_radius, 1e-3f)});
        scene.body_size = std::max(scene.body_size, d.shape.rest_radius);
    }
    float largest_fixed = 0.0f;
    bool moving = !boxes.empty();
    for (std::size_t b = 0; b < rigid.size(); ++b) {
        const RigidBodyView& view = frame.rigid_bodies[b];
        boxes.push_back({rigid[b].low, rigid[b].high, std::max(view.radius, 1e-3f)});
        if (view.fixed) largest_fixed = std::max(largest_fixed, view.radius);
        else {
            scene.body_size = std::max(scene.body_size, view.radius);
            moving = true;
        }
    }
    if (!moving) scene.body_size = std::max(scene.body_size, largest_fixed);
    scene.any = !boxes.empty();
    if (soft.size() == 1 && rigid.empty() && !soft[0].particles.empty()) {
        // One soft body: its own centre of mass and radius.
        scene.centre = soft[0].shape.centre_of_mass;
        scene.radius = soft[0].shape.radius;
        scene.body_size = std::max(soft[0].shape.rest_radius, 1e-3f);
    } else if (scene.any) {
        glm::vec3 low = boxes[0].low, high = boxes[0].high;
        for (const Box& box : boxes) {
            low = glm::min(low, box.low);
            high = glm::max(high, box.high);
        }
        scene.centre = 0.5f * (low + high);
        for (const Box& box : boxes) {
            scene.radius = std::max(scene.radius, glm::length(0.5f * (box.low + box.high) - scene.centre) +
                                                      0.5f * glm::length(box.high - box.low));
        }
        scene.body_size = std::max(scene.body_size, 1e-3f);
    }
    // The occluders: the largest bodies' boxes, as ellipsoids a little larger than the box.
    std::stable_sort(boxes.begin(), boxes.end(), [](const Box& a, const Box& b) { return a.size > b.size; });
    if (boxes.size() > std::size_t(kMaxOccluders)) boxes.resize(kMaxOccluders);
    for (const Box& box : boxes) {
        scene.occluder_centres.push_back(0.5f * (box.high + box.low));
        scene.occluder_axes.push_back(glm::max(0.5f * (box.high - box.low), glm::vec3(0.05f * box.size)) * 1.1f);
    }
    return scene;
}

void draw_mesh(const MeshGpu& gpu) {
    glBindVertexArray(gpu.vao.id());
    glDrawElements(GL_TRIANGLES, gpu.index_count(), GL_UNSIGNED_INT, nullptr);
}

}  // namespace

// The overlays' lines and spheres for this frame, from the soft bodies as drawn.
void Renderer::State::build_overlays(const Frame& frame, const SceneShape& scene) {
    std::vector<SoftBodyDrawn> soft_drawn;
    for (const SoftDraw& d : soft) {
        soft_drawn.push_back({d.particles, d.has_surface ? std::span<const SurfaceVertex>(d.surface.vertices())
                                                         : std::span<const SurfaceVertex>(),
                              d.shape});
    }
    overlay_builder.build(frame, soft_drawn, scene.body_size, overlays);
}

// The sun's shadow map, fitted to the bodies (and the overlays' spheres): an orthographic view
// along the sun's rays holding a sphere about them all, deep enough to reach the floor below.
// The moments are mipmapped for the soft shadows' lookups (lighting.glsl). Leaves the map bound
// to texture unit 0 for the lit passes, made or not.
SunShadow Renderer::State::draw_shadow_map(const Appearance& look, const SceneShape& scene) {
    float largest_sphere = 0.0f;
    for (const SphereInstance& ball : overlays.spheres) largest_sphere = std::max(largest_sphere, ball.radius);
    bool any_surface = false;
    for (const SoftDraw& d : soft) any_surface |= d.has_surface;
    for (const RigidDraw& d : rigid) any_surface |= d.gpu.index_count() > 0;

    SunShadow sun;
    sun.on = look.shadows && (any_surface || !overlays.spheres.empty());
    if (sun.on) {
        const float r = std::max(scene.radius, 1e-3f) * 1.05f + largest_sphere;
        const glm::vec3 c = scene.centre;
        const glm::vec3 up = std::abs(kSunDirection.z) > 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1);
        const glm::mat4 light_view = glm::lookAt(c + kSunDirection * (r + 1.0f), c, up);
        // Deep enough to reach the floor below the bodies along the sun's rays.
        const float to_floor = look.ground ? std::max(0.0f, (c.z - look.ground_height) / kSunDirection.z) : 0.0f;
        const float near_plane = 0.5f, far_plane = r + 1.0f + to_floor + r + 1.0f;
        const glm::mat4 light_projection = glm::ortho(-r, r, -r, r, near_plane, far_plane);
        const glm::mat4 light = light_projection * light_view;
        const glm::mat4 to_unit = glm::translate(glm::mat4(1.0f), glm::vec3(0.5f)) * glm::scale(glm::mat4(1.0f), glm::vec3(0.5f));
        sun.matrix = to_unit * light;
        sun.penumbra_scale = (far_plane - near_plane) * std::tan(kSunAngularRadius) / (2.0f * r);
        sun.normal_offset = 2.0f * (2.0f * r / float(kShadowMapSize));

        glBindFramebuffer(GL_FRAMEBUFFER, shadow_fbo.id());
        glViewport(0, 0, kShadowMapSize, kShadowMapSize);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        glDisable(GL_BLEND);
        glClearColor(1.0f, 1.0f, 0.0f, 0.0f);  // the far plane: nothing in the way
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        if (any_surface) {
            shadow.use();
            set(shadow.uniform("u_shadow_view_projection"), light);
            set(shadow.uniform("u_model"), glm::mat4(1.0f));
            for (const SoftDraw& d : soft) {
                if (d.has_surface) draw_mesh(d.gpu);
            }
            for (const RigidDraw& d : rigid) {
                if (d.gpu.index_count() == 0) continue;
                set(shadow.uniform("u_model"), d.model);
                draw_mesh(d.gpu);
            }
        }
        if (!overlays.spheres.empty()) {
            sphere_shadow.use();
            set(sphere_shadow.uniform("u_light_view"), light_view);
            set(sphere_shadow.uniform("u_light_projection"), light_projection);
            gl::stream(GL_ARRAY_BUFFER, sphere_vbo.id(), overlays.spheres.data(),
                       static_cast<GLsizeiptr>(overlays.spheres.size() * sizeof(SphereInstance)));
            glBindVertexArray(sphere_vao.id());
            glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(overlays.spheres.size()));
        }
        glBindTexture(GL_TEXTURE_2D, shadow_texture.id());
        glGenerateMipmap(GL_TEXTURE_2D);
    }
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, shadow_texture.id());
    return sun;
}

// The multisampled target at this size, bound and cleared, depth tested.
void Renderer::State::begin_scene(int width, int height, int samples) {
    ensure_targets(width, height, std::clamp(samples, 1, std::max(1, info.max_samples)));
    glBindFramebuffer(GL_FRAMEBUFFER, msaa_fbo.id());
    glViewport(0, 0, width, height);
    glDepthMask(GL_TRUE);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glDisable(GL_CULL_FACE);

    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
}

// The floor: its grid sized to the bodies, soft shadows, and darkening under each body (its
// occluders: ellipsoids about the largest bodies' boxes). A large square under the camera's
// target, drawn without the shadow map's lookups; then, where the map reaches (the bodies and
// their shadows), that part again with them. The floor is the first thing drawn, so the second
// pass simply replaces the first's pixels. The picture is the one a single pass would give, at
// the cost of the lookups over a small part of the floor only: a software rasterizer runs the
// whole lookup for every pixel, shadowed or not.
void Renderer::State::draw_ground(const FramePass& pass, const SceneShape& scene, const SunShadow& sun) {
    const Camera& camera = pass.frame.camera;
    const float half = std::max(camera.far_plane * 0.5f, 60.0f * scene.body_size);
    const FloorRect floor{glm::vec2(camera.target.x, camera.target.y), glm::vec2(half)};
    // Pushed back a little in depth: a body flattened onto the floor stays in front of it.
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(2.0f, 4.0f);
    glBindVertexArray(empty_vao.id());
    draw_floor_rect(ground_sunlit, pass, scene, sun, floor);
    if (sun.on) {
        const float height = pass.frame.appearance.ground_height;
        const std::optional<FloorRect> reached = shadow_footprint(sun.matrix, height, sun.normal_offset);
        const std::optional<FloorRect> shaded = reached ? overlap(*reached, floor) : std::optional<FloorRect>(floor);
        if (shaded) {
            glDepthFunc(GL_ALWAYS);
            draw_floor_rect(ground, pass, scene, sun, *shaded);
            glDepthFunc(GL_LESS);
        }
    }
    glDisable(GL_POLYGON_OFFSET_FILL);
}

// One rectangle of the floor with one of its two programs.
void Renderer::State::draw_floor_rect(const ShaderProgram& program, const FramePass& pass, const SceneShape& scene,
                                      const SunShadow& sun, const FloorRect& rect) {
    const Appearance& look = pass.frame.appearance;
    const Camera& camera = pass.frame.camera;
    const float body_size = scene.body_size;
    program.use();
    set(program.uniform("u_view_projection"), pass.view_projection);
    set(program.uniform("u_centre"), rect.centre);
    set(program.uniform("u_half_size"), rect.half_size);
    set(program.uniform("u_height"), look.ground_height);
    set(program.uniform("u_floor_color"), kFloorColor);
    set(program.uniform("u_grid_major"), grid_spacing(body_size));
    set(program.uniform("u_fog_distance"), 3.0f * camera.distance + 12.0f * body_size);
    const GLsizei occluders = static_cast<GLsizei>(scene.occluder_centres.size());
    set(program.uniform("u_occluder_count"), int(occluders));
    if (occluders > 0) {
        glUniform3fv(program.uniform("u_occluder_centre"), occluders, glm::value_ptr(scene.occluder_centres[0]));
        glUniform3fv(program.uniform("u_occluder_axes"), occluders, glm::value_ptr(scene.occluder_axes[0]));
    }
    set(program.uniform("u_occlusion"), scene.any ? 0.75f : 0.0f);
    set_lighting(program, pass.eye, sun.matrix, sun.on, sun.penumbra_scale, sun.normal_offset);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
}

// One body's surface: soft bodies with the identity model matrix, rigid ones with theirs.
void Renderer::State::draw_body(const FramePass& pass, const SunShadow& sun, const MeshGpu& gpu, const glm::mat4& model,
                                const glm::mat3& normal_matrix, const glm::vec3& color, float size, float opacity,
                                bool two_sided) {
    const Appearance& look = pass.frame.appearance;
    body.use();
    set(body.uniform("u_view_projection"), pass.view_projection);
    set(body.uniform("u_model"), model);
    set(body.uniform("u_normal_matrix"), normal_matrix);
    set(body.uniform("u_body_color"), color);
    set(body.uniform("u_pattern"), look.pattern ? 1.0f : 0.0f);
    set(body.uniform("u_opacity"), opacity);
    set(body.uniform("u_two_sided"), two_sided ? 1.0f : 0.0f);
    set(body.uniform("u_ground_height"), look.ground ? look.ground_height : -1e30f);
    set(body.uniform("u_contact_range"), 0.6f * size);
    set_lighting(body, pass.eye, sun.matrix, sun.on, sun.penumbra_scale, sun.normal_offset);
    draw_mesh(gpu);
}

// Every soft body that has a surface, at one opacity (a see-through body's two halves).
void Renderer::State::draw_soft_surfaces(const FramePass& pass, const SunShadow& sun, float opacity, bool two_sided) {
    for (const SoftDraw& d : soft) {
        if (d.has_surface) {
            draw_body(pass, sun, d.gpu, glm::mat4(1.0f), glm::mat3(1.0f), d.color, std::max(d.shape.rest_radius, 1e-3f),
                      opacity, two_sided);
        }
    }
}

// The opaque bodies: solid soft bodies, then every rigid body.
void Renderer::State::draw_solid_bodies(const FramePass& pass, const SunShadow& sun) {
    // A closed body hides its back faces (they would fight with the front ones when it is
    // crushed flat); an open one shows both sides.
    if (pass.frame.appearance.body == BodyStyle::Solid) {
        for (const SoftDraw& d : soft) {
            if (!d.has_surface) continue;
            if (d.gpu.closed) glEnable(GL_CULL_FACE);
            glCullFace(GL_BACK);
            draw_body(pass, sun, d.gpu, glm::mat4(1.0f), glm::mat3(1.0f), d.color, std::max(d.shape.rest_radius, 1e-3f), 1.0f,
                      false);
            glDisable(GL_CULL_FACE);
        }
    }
    // Rigid bodies are always solid; fixed ones (scenery) in a quieter tone of their colour,
    // and pushed back a little in depth as the floor is: a flat body lying on a ramp (within
    // the contact's slop of its face) stays in front of it.
    for (std::size_t b = 0; b < rigid.size(); ++b) {
        const RigidDraw& d = rigid[b];
        if (d.gpu.index_count() == 0) continue;
        const RigidBodyView& view = pass.frame.rigid_bodies[b];
        const glm::vec3 color = view.fixed ? glm::mix(view.color, glm::vec3(0.62f, 0.62f, 0.6f), 0.6f) : view.color;
        if (d.gpu.closed) glEnable(GL_CULL_FACE);
        glCullFace(GL_BACK);
        if (view.fixed) {
            glEnable(GL_POLYGON_OFFSET_FILL);
            glPolygonOffset(2.0f, 4.0f);
        }
        draw_body(pass, sun, d.gpu, d.model, d.normal_matrix, color, std::max(view.radius, 1e-3f), 1.0f, false);
        glDisable(GL_POLYGON_OFFSET_FILL);
        glDisable(GL_CULL_FACE);
    }
}

// The sky, on the far plane: only where nothing else was drawn (the cheaper order).
void Renderer::State::draw_sky(const FramePass& pass) {
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    sky.use();
    set(sky.uniform("u_inverse_view_projection"), glm::inverse(pass.view_projection));
    set(sky.uniform("u_sun_dir"), kSunDirection);
    set(sky.uniform("u_eye"), pass.eye);
    glBindVertexArray(empty_vao.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
}

// The overlays, blended: those inside or on the bodies depth tested (a see-through body wraps
// them: its far side first, the lines, then its near side), then the markers that must always
// show (the centre of mass sits inside the body).
void Renderer::State::draw_overlays(const FramePass& pass, const SunShadow& sun) {
    const Camera& camera = pass.frame.camera;
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    draw_spheres(overlays.spheres, camera, pass.aspect, sun.matrix);
    glDepthMask(GL_FALSE);
    const bool ghost = pass.frame.appearance.body == BodyStyle::Ghost;
    if (ghost) {
        glEnable(GL_CULL_FACE);
        glCullFace(GL_FRONT);
        draw_soft_surfaces(pass, sun, kGhostOpacity * 0.6f, true);
        glDisable(GL_CULL_FACE);
    }
    draw_lines(overlays.lines, pass.view_projection, pass.width, pass.height, pass.eye);
    if (ghost) {
        glEnable(GL_CULL_FACE);
        glCullFace(GL_BACK);
        draw_soft_surfaces(pass, sun, kGhostOpacity, true);
        glDisable(GL_CULL_FACE);
    }

    glDisable(GL_DEPTH_TEST);
    draw_lines(overlays.lines_on_top, pass.view_projection, pass.width, pass.height, pass.eye);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glClear(GL_DEPTH_BUFFER_BIT);
    draw_spheres(overlays.spheres_on_top, camera, pass.aspect, sun.matrix);
}

// Resolve the samples, copy to the caller's framebuffer, and leave GL as a caller expects to
// find it (renderer.h).
void Renderer::State::resolve(int width, int height, unsigned target_framebuffer) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, msaa_fbo.id());
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo.id());
    glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, resolve_fbo.id());
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, target_framebuffer);
    glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);

    glBindFramebuffer(GL_FRAMEBUFFER, target_framebuffer);
    glDisable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ZERO);
    glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glBindTexture(GL_TEXTURE_2D, 0);
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glUseProgram(0);
}

// The frame, pass by pass (the list at the top of this file).
void Renderer::draw(const Frame& frame, int width, int height, unsigned target_framebuffer) {
    if (width <= 0 || height <= 0) return;
    State& s = *state_;
    const auto start = Clock::now();
    const Camera& camera = frame.camera;
    const float aspect = float(width) / float(height);
    const FramePass pass{frame, width, height, aspect, camera.projection(aspect) * camera.view(), camera.eye()};

    s.prepare_soft(frame);
    s.prepare_rigid(frame);
    const SceneShape scene = measure_scene(frame, s.soft, s.rigid);
    s.build_overlays(frame, scene);
    const SunShadow sun = s.draw_shadow_map(frame.appearance, scene);
    s.begin_scene(width, height, frame.appearance.samples);
    if (frame.appearance.ground) s.draw_ground(pass, scene, sun);
    s.draw_solid_bodies(pass, sun);
    s.draw_sky(pass);
    s.draw_overlays(pass, sun);
    s.resolve(width, height, target_framebuffer);
    s.timings.total_ms = ms_since(start);
}

glm::mat4 model_matrix(const RigidBodyView& body) {
    const float a = body.alpha;
    const glm::vec3 x = glm::mix(body.previous_position, body.position, a);
    // Along the shorter arc between the two ticks' orientations, normalised, then given back
    // the length the physics' quaternion has (1, unless it was left to drift).
    glm::vec4 q0 = body.previous_orientation, q1 = body.orientation;
    if (glm::dot(q0, q1) < 0.0f) q1 = -q1;
    glm::vec4 q = glm::mix(q0, q1, a);
    const float len = glm::length(q);
    if (len > 0.0f) q *= glm::mix(glm::length(q0), glm::length(q1), a) / len;
    // The physics' formula (Quat::to_matrix): it takes |q| = 1 for granted.
    const float w = q.x, i = q.y, j = q.z, k = q.w;
    glm::mat4 m(1.0f);
    m[0] = glm::vec4(1.0f - 2.0f * (j * j + k * k), 2.0f * (i * j + w * k), 2.0f * (i * k - w * j), 0.0f);
    m[1] = glm::vec4(2.0f * (i * j - w * k), 1.0f - 2.0f * (i * i + k * k), 2.0f * (j * k + w * i), 0.0f);
    m[2] = glm::vec4(2.0f * (i * k + w * j), 2.0f * (j * k - w * i), 1.0f - 2.0f * (i * i + j * j), 0.0f);
    m[3] = glm::vec4(x, 1.0f);
    return m;
}

Image Renderer::read_back() const {
    const State& s = *state_;
    Image image(s.fb_width, s.fb_height);
    if (!s.resolve_fbo) return image;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, s.resolve_fbo.id());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    std::vector<std::uint8_t> rows(image.rgba.size());
    glReadPixels(0, 0, s.fb_width, s.fb_height, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    // GL's rows run bottom to top; images run top to bottom.
    const std::size_t stride = static_cast<std::size_t>(s.fb_width) * 4;
    for (int y = 0; y < s.fb_height; ++y) {
        std::copy_n(&rows[static_cast<std::size_t>(s.fb_height - 1 - y) * stride], stride,
                    &image.rgba[static_cast<std::size_t>(y) * stride]);
    }
    for (std::size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;
    return image;
}

}  // namespace softbody::render

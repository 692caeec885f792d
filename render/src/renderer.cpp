// The frame, pass by pass:
//   1. the body's particles interpolated, normals recomputed, vertices streamed (deform.h)
//   2. the sun's shadow map: depth moments of the body (and overlay spheres), mipmapped
//   3. multisampled: the floor (grid, soft shadow, contact darkening), the solid body, the sky
//      where nothing else is, the overlays and a see-through body, the always-visible markers
//   4. resolve the samples, copy to the caller's framebuffer
#include "render/renderer.h"

#include <glad/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <stdexcept>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gl_util.h"
#include "overlays.h"
#include "render/deform.h"
#include "render/shader.h"

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

struct Renderer::State {
    RendererInfo info;
    DrawTimings timings;

    ShaderProgram sky, ground, body, shadow, sphere_shadow, line, sphere;
    gl::VertexArray empty_vao;  // for draws that make their vertices from gl_VertexID

    // The body: streamed vertices, fixed indices.
    gl::VertexArray body_vao;
    gl::Buffer body_vbo, body_ebo;
    gl::Buffer body_material;  // fixed: each vertex's place in the body at rest (see body.frag.glsl)
    const Mesh* uploaded_mesh = nullptr;
    std::size_t uploaded_render_vertices = 0, uploaded_indices = 0;
    bool closed_mesh = false;  // every edge shared by two triangles: back faces can be culled

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

    // Scratch kept between frames.
    std::vector<glm::vec3> particles;
    DeformedSurface surface;
    OverlayBuilder overlay_builder;
    OverlayGeometry overlays;

    void build_programs();
    void build_buffers();
    void ensure_targets(int width, int height, int samples);
    void upload_topology(const Mesh& mesh);
    void set_lighting(const ShaderProgram& program, const glm::vec3& eye, const glm::mat4& shadow_matrix,
                      bool shadows, float penumbra_scale, float normal_offset) const;
    void draw_lines(const std::vector<LineInstance>& lines, const glm::mat4& view_projection, int width, int height,
                    const glm::vec3& eye);
    void draw_spheres(const std::vector<SphereInstance>& spheres, const Camera& camera, float aspect,
                      const glm::mat4& shadow_matrix);
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
    body = ShaderProgram("body.vert.glsl", "body.frag.glsl");
    shadow = ShaderProgram("shadow.vert.glsl", "shadow.frag.glsl");
    sphere_shadow = ShaderProgram("sphere_shadow.vert.glsl", "sphere_shadow.frag.glsl");
    line = ShaderProgram("line.vert.glsl", "line.frag.glsl");
    sphere = ShaderProgram("sphere.vert.glsl", "sphere.frag.glsl");
}

void Renderer::State::build_buffers() {
    empty_vao = gl::make_vertex_array();

    body_vao = gl::make_vertex_array();
    body_vbo = gl::make_buffer();
    body_ebo = gl::make_buffer();
    glBindVertexArray(body_vao.id());
    glBindBuffer(GL_ARRAY_BUFFER, body_vbo.id());
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(SurfaceVertex), reinterpret_cast<void*>(offsetof(SurfaceVertex, position)));
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(SurfaceVertex), reinterpret_cast<void*>(offsetof(SurfaceVertex, normal)));
    body_material = gl::make_buffer();
    glBindBuffer(GL_ARRAY_BUFFER, body_material.id());
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, body_ebo.id());

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

void Renderer::State::upload_topology(const Mesh& mesh) {
    if (uploaded_mesh == &mesh && uploaded_render_vertices == mesh.render_vertices.size() &&
        uploaded_indices == mesh.triangles.size()) {
        return;
    }
    glBindVertexArray(body_vao.id());
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh.triangles.size() * sizeof(std::uint32_t)),
                 mesh.triangles.data(), GL_STATIC_DRAW);
    glBindVertexArray(0);
    // Material coordinates: the mesh's own vertex positions about their centre, in units of the
    // mesh's radius. They move with the body, so a pattern drawn from them shows it roll.
    glm::dvec3 centre(0.0);
    for (const Vec3& p : mesh.positions) centre += glm::dvec3(p.x, p.y, p.z);
    centre /= double(std::max<std::size_t>(mesh.positions.size(), 1));
    double radius = 1e-9;
    for (const Vec3& p : mesh.positions) radius = std::max(radius, glm::length(glm::dvec3(p.x, p.y, p.z) - centre));
    std::vector<glm::vec3> material(mesh.render_vertices.size());
    for (std::size_t i = 0; i < material.size(); ++i) {
        const Vec3& p = mesh.positions[mesh.render_vertices[i].particle];
        material[i] = glm::vec3((glm::dvec3(p.x, p.y, p.z) - centre) / radius);
    }
    glBindBuffer(GL_ARRAY_BUFFER, body_material.id());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(material.size() * sizeof(glm::vec3)), material.data(),
                 GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    // Closed: every edge (on particles) belongs to exactly two triangles.
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
    for (std::size_t k = 0; k + 2 < mesh.triangles.size(); k += 3) {
        for (std::size_t e = 0; e < 3; ++e) {
            std::uint32_t a = mesh.render_vertices[mesh.triangles[k + e]].particle;
            std::uint32_t b = mesh.render_vertices[mesh.triangles[k + (e + 1) % 3]].particle;
            ++edges[{std::min(a, b), std::max(a, b)}];
        }
    }
    closed_mesh = !edges.empty() && std::all_of(edges.begin(), edges.end(), [](const auto& e) { return e.second == 2; });
    uploaded_mesh = &mesh;
    uploaded_render_vertices = mesh.render_vertices.size();
    uploaded_indices = mesh.triangles.size();
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

void Renderer::draw(const Frame& frame, int width, int height, unsigned target_framebuffer) {
    if (width <= 0 || height <= 0) return;
    State& s = *state_;
    const auto start = Clock::now();
    const Appearance& look = frame.appearance;
    const Camera& camera = frame.camera;
    const float aspect = float(width) / float(height);
    const glm::mat4 view_projection = camera.projection(aspect) * camera.view();
    const glm::vec3 eye = camera.eye();

    // --- The body this frame: positions, normals, shape -------------------------------------
    const Mesh* mesh = frame.body.mesh;
    interpolate_positions(frame.body, frame.debug.body_offset, s.particles);
    const BodyShape shape = measure_body(s.particles, frame.body.rest_positions);
    const bool has_surface = mesh && mesh->triangle_count() > 0 && look.body != BodyStyle::Hidden &&
                             look.body != BodyStyle::Wireframe;
    if (has_surface) s.surface.update(*mesh, s.particles, frame.debug.flip_normals);
    s.timings.surface_ms = ms_since(start);

    const auto upload_start = Clock::now();
    if (has_surface) {
        s.upload_topology(*mesh);
        const auto& vertices = s.surface.vertices();
        gl::stream(GL_ARRAY_BUFFER, s.body_vbo.id(), vertices.data(),
                   static_cast<GLsizeiptr>(vertices.size() * sizeof(SurfaceVertex)));
    }
    s.timings.upload_ms = ms_since(upload_start);
    const GLsizei index_count = has_surface ? static_cast<GLsizei>(mesh->triangles.size()) : 0;
    s.overlay_builder.build(frame, s.particles,
                            has_surface ? std::span<const SurfaceVertex>(s.surface.vertices()) : std::span<const SurfaceVertex>(),
                            shape, s.overlays);
    float largest_sphere = 0.0f;
    for (const SphereInstance& sphere : s.overlays.spheres) largest_sphere = std::max(largest_sphere, sphere.radius);

    // --- Shadow map, fitted to the body ------------------------------------------------------
    const bool shadows = look.shadows && (has_surface || !s.overlays.spheres.empty());
    glm::mat4 shadow_matrix(1.0f);
    float penumbra_scale = 0.0f, normal_offset = 0.0f;
    if (shadows) {
        const float r = std::max(shape.radius, 1e-3f) * 1.05f + largest_sphere;
        const glm::vec3 c = shape.centre_of_mass;
        const glm::vec3 up = std::abs(kSunDirection.z) > 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1);
        const glm::mat4 light_view = glm::lookAt(c + kSunDirection * (r + 1.0f), c, up);
        // Deep enough to reach the floor below the body along the sun's rays.
        const float to_floor = look.ground ? std::max(0.0f, (c.z - look.ground_height) / kSunDirection.z) : 0.0f;
        const float near_plane = 0.5f, far_plane = r + 1.0f + to_floor + r + 1.0f;
        const glm::mat4 light_projection = glm::ortho(-r, r, -r, r, near_plane, far_plane);
        const glm::mat4 light = light_projection * light_view;
        const glm::mat4 to_unit = glm::translate(glm::mat4(1.0f), glm::vec3(0.5f)) * glm::scale(glm::mat4(1.0f), glm::vec3(0.5f));
        shadow_matrix = to_unit * light;
        penumbra_scale = (far_plane - near_plane) * std::tan(kSunAngularRadius) / (2.0f * r);
        normal_offset = 2.0f * (2.0f * r / float(kShadowMapSize));

        glBindFramebuffer(GL_FRAMEBUFFER, s.shadow_fbo.id());
        glViewport(0, 0, kShadowMapSize, kShadowMapSize);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        glDisable(GL_BLEND);
        glClearColor(1.0f, 1.0f, 0.0f, 0.0f);  // the far plane: nothing in the way
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        if (has_surface) {
            s.shadow.use();
            set(s.shadow.uniform("u_shadow_view_projection"), light);
            glBindVertexArray(s.body_vao.id());
            glDrawElements(GL_TRIANGLES, index_count, GL_UNSIGNED_INT, nullptr);
        }
        if (!s.overlays.spheres.empty()) {
            s.sphere_shadow.use();
            set(s.sphere_shadow.uniform("u_light_view"), light_view);
            set(s.sphere_shadow.uniform("u_light_projection"), light_projection);
            gl::stream(GL_ARRAY_BUFFER, s.sphere_vbo.id(), s.overlays.spheres.data(),
                       static_cast<GLsizeiptr>(s.overlays.spheres.size() * sizeof(SphereInstance)));
            glBindVertexArray(s.sphere_vao.id());
            glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(s.overlays.spheres.size()));
        }
        glBindTexture(GL_TEXTURE_2D, s.shadow_texture.id());
        glGenerateMipmap(GL_TEXTURE_2D);
    }
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, s.shadow_texture.id());

    // --- Main pass, multisampled -------------------------------------------------------------
    const int samples = std::clamp(look.samples, 1, std::max(1, s.info.max_samples));
    s.ensure_targets(width, height, samples);
    glBindFramebuffer(GL_FRAMEBUFFER, s.msaa_fbo.id());
    glViewport(0, 0, width, height);
    glDepthMask(GL_TRUE);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glDisable(GL_CULL_FACE);

    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);

    const float body_size = std::max(shape.rest_radius, 1e-3f);
    if (look.ground) {
        s.ground.use();
        set(s.ground.uniform("u_view_projection"), view_projection);
        set(s.ground.uniform("u_centre"), glm::vec2(camera.target.x, camera.target.y));
        set(s.ground.uniform("u_half_size"), std::max(camera.far_plane * 0.5f, 60.0f * body_size));
        set(s.ground.uniform("u_height"), look.ground_height);
        set(s.ground.uniform("u_floor_color"), kFloorColor);
        set(s.ground.uniform("u_grid_major"), grid_spacing(body_size));
        set(s.ground.uniform("u_fog_distance"), 3.0f * camera.distance + 12.0f * body_size);
        const glm::vec3 axes = glm::max(0.5f * (shape.high - shape.low), glm::vec3(0.05f * body_size));
        set(s.ground.uniform("u_occluder_centre"), 0.5f * (shape.high + shape.low));
        set(s.ground.uniform("u_occluder_axes"), axes * 1.1f);
        set(s.ground.uniform("u_occlusion"), mesh && !s.particles.empty() ? 0.75f : 0.0f);
        s.set_lighting(s.ground, eye, shadow_matrix, shadows, penumbra_scale, normal_offset);
        // Pushed back a little in depth: a body flattened onto the floor stays in front of it.
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(2.0f, 4.0f);
        glBindVertexArray(s.empty_vao.id());
        glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
        glDisable(GL_POLYGON_OFFSET_FILL);
    }

    const auto draw_body = [&](float opacity) {
        s.body.use();
        set(s.body.uniform("u_view_projection"), view_projection);
        set(s.body.uniform("u_body_color"), look.body_color);
        set(s.body.uniform("u_pattern"), look.pattern ? 1.0f : 0.0f);
        set(s.body.uniform("u_opacity"), opacity);
        set(s.body.uniform("u_two_sided"), look.body == BodyStyle::Ghost ? 1.0f : 0.0f);
        set(s.body.uniform("u_ground_height"), look.ground ? look.ground_height : -1e30f);
        set(s.body.uniform("u_contact_range"), 0.6f * body_size);
        s.set_lighting(s.body, eye, shadow_matrix, shadows, penumbra_scale, normal_offset);
        glBindVertexArray(s.body_vao.id());
        glDrawElements(GL_TRIANGLES, index_count, GL_UNSIGNED_INT, nullptr);
    };
    // A closed body hides its back faces (they would fight with the front ones when it is
    // crushed flat); an open one shows both sides.
    if (has_surface && look.body == BodyStyle::Solid) {
        if (s.closed_mesh) glEnable(GL_CULL_FACE);
        glCullFace(GL_BACK);
        draw_body(1.0f);
        glDisable(GL_CULL_FACE);
    }

    // The sky, on the far plane: only where nothing else was drawn (the cheaper order).
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    s.sky.use();
    set(s.sky.uniform("u_inverse_view_projection"), glm::inverse(view_projection));
    set(s.sky.uniform("u_sun_dir"), kSunDirection);
    set(s.sky.uniform("u_eye"), eye);
    glBindVertexArray(s.empty_vao.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);

    // Overlays inside or on the body, depth tested.
    // A see-through body wraps them: its far side first, the lines, then its near side.
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    s.draw_spheres(s.overlays.spheres, camera, aspect, shadow_matrix);
    glDepthMask(GL_FALSE);
    const bool ghost = has_surface && look.body == BodyStyle::Ghost;
    if (ghost) {
        glEnable(GL_CULL_FACE);
        glCullFace(GL_FRONT);
        draw_body(kGhostOpacity * 0.6f);
        glDisable(GL_CULL_FACE);
    }
    s.draw_lines(s.overlays.lines, view_projection, width, height, eye);
    if (ghost) {
        glEnable(GL_CULL_FACE);
        glCullFace(GL_BACK);
        draw_body(kGhostOpacity);
        glDisable(GL_CULL_FACE);
    }

    // Markers that must always show (the centre of mass sits inside the body).
    glDisable(GL_DEPTH_TEST);
    s.draw_lines(s.overlays.lines_on_top, view_projection, width, height, eye);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glClear(GL_DEPTH_BUFFER_BIT);
    s.draw_spheres(s.overlays.spheres_on_top, camera, aspect, shadow_matrix);

    // --- Resolve the samples, then copy to the caller's framebuffer ---------------------------
    glBindFramebuffer(GL_READ_FRAMEBUFFER, s.msaa_fbo.id());
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, s.resolve_fbo.id());
    glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, s.resolve_fbo.id());
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, target_framebuffer);
    glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);

    // --- Leave GL as a caller expects to find it ----------------------------------------------
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
    s.timings.total_ms = ms_since(start);
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

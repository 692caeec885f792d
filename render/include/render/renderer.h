// The renderer's one entry point. The caller owns the GL context (a window, or an offscreen
// one), makes it current, and hands over its loader; every GL call then goes through the
// pointers glad loads from it. OpenGL 3.3 core.
//
//   Renderer renderer(loader);                     // after the context is current
//   renderer.draw(frame, width, height, target);   // each frame
//   Image shot = renderer.read_back();             // the last frame, for screenshots
//
// draw() renders into its own multisampled framebuffer and resolves into `target` (0: the
// context's default framebuffer). It sets every GL state it relies on and leaves the ones it
// touched at GL's defaults (no blending, no depth test or culling, no program, VAO 0, texture
// 0, clear colour 0), with `target` bound and the viewport covering width x height, so a UI
// drawn after it starts from a known state.
#pragma once

#include <memory>
#include <string>

#include "render/frame.h"
#include "render/image.h"

namespace softbody::render {

using ProcAddress = void (*)();
using Loader = ProcAddress (*)(const char* name);

// Where the time of the last draw() went, CPU side, in milliseconds.
struct DrawTimings {
    double surface_ms = 0.0;   // interpolation + normal recomputation
    double upload_ms = 0.0;    // streaming the vertices into the GPU buffer
    double total_ms = 0.0;     // the whole draw() call (GL work is queued, not finished)
};

struct RendererInfo {
    std::string vendor, renderer, version, glsl_version;
    int max_samples = 1;
    int max_size = 0;  // largest framebuffer side
};

class Renderer {
public:
    // Loads GL through `loader` and builds the shaders. Throws std::runtime_error when GL 3.3
    // core cannot be loaded, ShaderError for a shader that fails to compile or link.
    explicit Renderer(Loader loader);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    void draw(const Frame& frame, int width, int height, unsigned target_framebuffer = 0);

    // The last frame draw() made, top row first (waits for the GPU to finish it).
    Image read_back() const;

    const RendererInfo& info() const;
    const DrawTimings& timings() const;

private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace softbody::render

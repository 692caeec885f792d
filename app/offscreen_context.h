// An OpenGL 3.3 core context with no window and no display: OSMesa (llvmpipe), rendering into
// memory. It is a context provider, like a window: it makes the context current and offers the
// loader the renderer needs.
//
// OSMesa is opened at run time, so `softbody` runs without it and only the commands that need
// it say what is missing. SOFTBODY_OSMESA names another library file to open instead.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

#include "render/renderer.h"

namespace softbody::app {

struct OffscreenError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class OffscreenContext {
public:
    // Throws OffscreenError when OSMesa is missing or cannot make a 3.3 core context.
    OffscreenContext(int width, int height);
    ~OffscreenContext();
    OffscreenContext(const OffscreenContext&) = delete;
    OffscreenContext& operator=(const OffscreenContext&) = delete;

    render::Loader loader() const;
    int width() const { return width_; }
    int height() const { return height_; }
    static constexpr int kMaxSide = 8192;

private:
    struct Library;
    std::unique_ptr<Library> library_;
    void* context_ = nullptr;
    int width_, height_;
    std::unique_ptr<unsigned char[]> buffer_;
};

}  // namespace softbody::app

#include "offscreen_context.h"

#include <dlfcn.h>

#include <cstdlib>

// glad's header first: it stands in for the system GL header that osmesa.h would include.
#include <glad/gl.h>
#include <GL/osmesa.h>

namespace softbody::app {

namespace {
constexpr const char* kDefaultLibrary = "libOSMesa.so.8";
}  // namespace

struct OffscreenContext::Library {
    void* handle = nullptr;
    OSMesaContext (*create)(const int*, OSMesaContext) = nullptr;
    GLboolean (*make_current)(OSMesaContext, void*, GLenum, GLsizei, GLsizei) = nullptr;
    void (*destroy)(OSMesaContext) = nullptr;
    render::Loader get_proc_address = nullptr;  // OSMesaGetProcAddress has the loader's signature
    // The library stays loaded until the process ends: its driver registers exit handlers, and
    // unloading it early is not safe.
};

OffscreenContext::OffscreenContext(int width, int height) : library_(std::make_unique<Library>()), width_(width), height_(height) {
    if (width < 1 || height < 1 || width > kMaxSide || height > kMaxSide) {
        throw OffscreenError("image size " + std::to_string(width) + "x" + std::to_string(height) + " is out of range 1.." +
                             std::to_string(kMaxSide));
    }
    const char* override_path = std::getenv("SOFTBODY_OSMESA");
    const std::string path = override_path && *override_path ? override_path : kDefaultLibrary;
    library_->handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!library_->handle) {
        const char* why = dlerror();
        throw OffscreenError("headless rendering needs OSMesa, and " + path + " cannot be opened (" +
                             (why ? why : "unknown reason") + "); on Debian: apt-get install libosmesa6");
    }
    auto symbol = [&](const char* name) {
        void* address = dlsym(library_->handle, name);
        if (!address) throw OffscreenError(path + " has no " + name + ": not a usable OSMesa library");
        return address;
    };
    library_->create = reinterpret_cast<decltype(library_->create)>(symbol("OSMesaCreateContextAttribs"));
    library_->make_current = reinterpret_cast<decltype(library_->make_current)>(symbol("OSMesaMakeCurrent"));
    library_->destroy = reinterpret_cast<decltype(library_->destroy)>(symbol("OSMesaDestroyContext"));
    library_->get_proc_address = reinterpret_cast<render::Loader>(symbol("OSMesaGetProcAddress"));

    const int attributes[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_STENCIL_BITS, 8,
                              OSMESA_PROFILE, OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 3,
                              OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
    OSMesaContext context = library_->create(attributes, nullptr);
    if (!context) throw OffscreenError("OSMesa could not create an OpenGL 3.3 core context");
    context_ = context;
    buffer_ = std::make_unique<unsigned char[]>(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4);
    if (!library_->make_current(context, buffer_.get(), GL_UNSIGNED_BYTE, width, height)) {
        library_->destroy(context);
        context_ = nullptr;
        throw OffscreenError("OSMesa could not make its context current at " + std::to_string(width) + "x" +
                             std::to_string(height));
    }
}

OffscreenContext::~OffscreenContext() {
    if (context_) {
        library_->make_current(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0);
        library_->destroy(static_cast<OSMesaContext>(context_));
    }
}

render::Loader OffscreenContext::loader() const { return library_->get_proc_address; }

}  // namespace softbody::app

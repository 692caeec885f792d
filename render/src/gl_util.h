// Small owners for GL objects (each deletes its object once) and helpers shared by the passes.
// Internal to the renderer.
#pragma once

#include <glad/gl.h>

#include <utility>

namespace softbody::render::gl {

template <void (*Delete)(GLuint)>
class Name {
public:
    Name() = default;
    explicit Name(GLuint id) : id_(id) {}
    ~Name() { reset(); }
    Name(Name&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
    Name& operator=(Name&& other) noexcept {
        if (this != &other) {
            reset();
            id_ = std::exchange(other.id_, 0);
        }
        return *this;
    }
    Name(const Name&) = delete;
    Name& operator=(const Name&) = delete;
    GLuint id() const { return id_; }
    explicit operator bool() const { return id_ != 0; }
    void reset() {
        if (id_) Delete(id_);
        id_ = 0;
    }

private:
    GLuint id_ = 0;
};

void delete_buffer(GLuint id);
void delete_vertex_array(GLuint id);
void delete_texture(GLuint id);
void delete_framebuffer(GLuint id);
void delete_renderbuffer(GLuint id);

using Buffer = Name<delete_buffer>;
using VertexArray = Name<delete_vertex_array>;
using Texture = Name<delete_texture>;
using Framebuffer = Name<delete_framebuffer>;
using Renderbuffer = Name<delete_renderbuffer>;

Buffer make_buffer();
VertexArray make_vertex_array();
Texture make_texture();
Framebuffer make_framebuffer();
Renderbuffer make_renderbuffer();

// Replaces a buffer's contents without waiting for the GPU to finish reading the old ones:
// the old storage is orphaned (glBufferData with no data) and the new bytes are written into
// fresh storage. Grows the buffer when needed.
void stream(GLenum target, GLuint buffer, const void* data, GLsizeiptr bytes);

// Throws std::runtime_error naming `what` when the framebuffer is incomplete.
void check_framebuffer(GLenum target, const char* what);

}  // namespace softbody::render::gl

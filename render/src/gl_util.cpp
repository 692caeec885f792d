#include "gl_util.h"

#include <cstdio>
#include <stdexcept>
#include <string>

namespace softbody::render::gl {

void delete_buffer(GLuint id) { glDeleteBuffers(1, &id); }
void delete_vertex_array(GLuint id) { glDeleteVertexArrays(1, &id); }
void delete_texture(GLuint id) { glDeleteTextures(1, &id); }
void delete_framebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
void delete_renderbuffer(GLuint id) { glDeleteRenderbuffers(1, &id); }

Buffer make_buffer() {
    GLuint id = 0;
    glGenBuffers(1, &id);
    return Buffer(id);
}
VertexArray make_vertex_array() {
    GLuint id = 0;
    glGenVertexArrays(1, &id);
    return VertexArray(id);
}
Texture make_texture() {
    GLuint id = 0;
    glGenTextures(1, &id);
    return Texture(id);
}
Framebuffer make_framebuffer() {
    GLuint id = 0;
    glGenFramebuffers(1, &id);
    return Framebuffer(id);
}
Renderbuffer make_renderbuffer() {
    GLuint id = 0;
    glGenRenderbuffers(1, &id);
    return Renderbuffer(id);
}

void stream(GLenum target, GLuint buffer, const void* data, GLsizeiptr bytes) {
    glBindBuffer(target, buffer);
    glBufferData(target, bytes, nullptr, GL_STREAM_DRAW);  // orphan: the GPU may still read the old one
    if (bytes > 0) glBufferSubData(target, 0, bytes, data);
}

void check_framebuffer(GLenum target, const char* what) {
    const GLenum status = glCheckFramebufferStatus(target);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        throw std::runtime_error(std::string(what) + ": framebuffer incomplete (status 0x" +
                                 [](GLenum s) {
                                     char text[16];
                                     std::snprintf(text, sizeof text, "%04X", s);
                                     return std::string(text);
                                 }(status) +
                                 ")");
    }
}

}  // namespace softbody::render::gl

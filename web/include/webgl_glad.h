// The browser build's <glad/gl.h> (web/CMakeLists.txt copies it there at configure time). In the browser GL is WebGL2, that is OpenGL ES 3.0, and
// emscripten links its functions directly: there is nothing to load. This header gives the
// renderer and the UI backend ES 3.0's declarations under glad's names, so they compile
// unchanged (the native build generates the real glad at build time).
//
// What the renderer takes from OpenGL 3.3 core is in ES 3.0 (vertex arrays, instancing,
// multisampled renderbuffers, blits, GLSL 3.00 es: see render/src/shader.cpp for the version
// line), except float colour buffers for the shadow map's moments: EXT_color_buffer_float,
// and OES_texture_float_linear to filter them. gladLoadGL checks both and reports the
// context as 3.3 when they are there: the renderer asks for nothing else.
#pragma once

#include <GLES3/gl3.h>
#include <emscripten/console.h>
#include <emscripten/html5.h>

typedef void (*GLADapiproc)(void);
typedef GLADapiproc (*GLADloadfunc)(const char* name);

#define GLAD_MAKE_VERSION(major, minor) ((major) * 10000 + (minor))
#define GLAD_VERSION_MAJOR(version) ((version) / 10000)
#define GLAD_VERSION_MINOR(version) ((version) % 10000)

// 3.3 when the current WebGL2 context can do what the renderer needs, 0 when it cannot.
static inline int gladLoadGL(GLADloadfunc) {
    const EMSCRIPTEN_WEBGL_CONTEXT_HANDLE context = emscripten_webgl_get_current_context();
    if (context == 0) return 0;
    if (!emscripten_webgl_enable_extension(context, "EXT_color_buffer_float")) {
        emscripten_console_error("softbody: this browser's WebGL2 cannot render to float textures "
                                 "(EXT_color_buffer_float), which the shadows need");
        return 0;
    }
    if (!emscripten_webgl_enable_extension(context, "OES_texture_float_linear")) {
        emscripten_console_warn("softbody: this browser's WebGL2 cannot filter float textures "
                                "(OES_texture_float_linear): shadows will look wrong");
    }
    return GLAD_MAKE_VERSION(3, 3);
}

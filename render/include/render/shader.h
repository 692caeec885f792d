// Shader programs built from the GLSL files in shaders/, which are embedded into the binary at
// build time. A file may pull in another with a line `#include "name.glsl"`.
//
// A compile or link error throws ShaderError whose text names the shader files and carries the
// driver's log, ready to print.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace softbody::render {

struct ShaderError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The text of an embedded shader file ("body.frag.glsl"), or nothing.
std::optional<std::string_view> embedded_shader(std::string_view name);

// A file's text with its #include lines replaced by the included files, and the files it drew
// on (files[0] is the named one). `#line` directives number the sources as in `files`, so the
// driver's "1:12" means line 12 of files[1]. Throws ShaderError for a missing file or an
// include cycle.
struct ExpandedShader {
    std::string text;
    std::vector<std::string> files;
};
ExpandedShader expand_shader(std::string_view name);

// One linked program. Needs a current GL context with glad loaded; move-only.
class ShaderProgram {
public:
    ShaderProgram() = default;
    // Builds from embedded files, e.g. ("body.vert.glsl", "body.frag.glsl").
    ShaderProgram(std::string_view vertex_file, std::string_view fragment_file);
    // Builds from text (tests use it to check the error messages); names label the log.
    static ShaderProgram from_source(const std::string& vertex_name, const std::string& vertex_text,
                                     const std::string& fragment_name, const std::string& fragment_text);
    ~ShaderProgram();
    ShaderProgram(ShaderProgram&& other) noexcept;
    ShaderProgram& operator=(ShaderProgram&& other) noexcept;
    ShaderProgram(const ShaderProgram&) = delete;
    ShaderProgram& operator=(const ShaderProgram&) = delete;

    unsigned id() const { return program_; }
    void use() const;
    // -1 when the program has no active uniform of that name (GL ignores it then).
    int uniform(const char* name) const;

private:
    static ShaderProgram build(const std::string& vertex_name, const std::string& vertex_text,
                               const std::string& vertex_sources, const std::string& fragment_name,
                               const std::string& fragment_text, const std::string& fragment_sources);
    unsigned program_ = 0;
};

}  // namespace softbody::render

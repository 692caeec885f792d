#include "render/shader.h"

#include <glad/gl.h>

#include <utility>

namespace softbody::render {

namespace {

constexpr int kMaxIncludeDepth = 8;

// Copies a file into `out`, replacing its #include lines by the included text. `#line L S`
// directives keep the driver's log meaningful: S is the file's index in `files`, so a message
// "2:14(3)" means line 14 of files[2].
void expand_into(std::string_view name, std::string& out, std::vector<std::string>& files, int depth) {
    if (depth > kMaxIncludeDepth) {
        throw ShaderError(std::string(name) + ": #include nested too deeply (a cycle?)");
    }
    const auto text = embedded_shader(name);
    if (!text) throw ShaderError("shader file '" + std::string(name) + "' is not among the embedded shaders");
    const int index = static_cast<int>(files.size());
    files.emplace_back(name);
    std::size_t start = 0;
    int line_number = 0;
    while (start < text->size()) {
        std::size_t end = text->find('\n', start);
        if (end == std::string_view::npos) end = text->size();
        const std::string_view line = text->substr(start, end - start);
        ++line_number;
        constexpr std::string_view kInclude = "#include \"";
        if (line.starts_with(kInclude) && line.size() > kInclude.size() && line.back() == '"') {
            out += "#line 1 " + std::to_string(files.size()) + "\n";
            expand_into(line.substr(kInclude.size(), line.size() - kInclude.size() - 1), out, files, depth + 1);
            out += "#line " + std::to_string(line_number + 1) + " " + std::to_string(index) + "\n";
        } else {
            out.append(line);
            out.push_back('\n');
        }
        start = end + 1;
    }
}

std::string legend(const std::vector<std::string>& files) {
    if (files.size() < 2) return "";
    std::string text = "(sources in the log: ";
    for (std::size_t i = 0; i < files.size(); ++i) {
        text += (i ? ", " : "") + std::to_string(i) + " = " + files[i];
    }
    return text + ")\n";
}

// The shaders are written in GLSL 3.30 core. An OpenGL ES 3.0 context (WebGL2, in the browser
// build) takes them as GLSL 3.00 es, which has what they use, once their version line says so
// and the default precisions are given (ES has none for floats in a fragment shader); the
// `#line` after them keeps the driver's line numbers those of the file.
std::string for_this_context(const std::string& text) {
    constexpr std::string_view kCore = "#version 330 core\n";
    const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    if (!text.starts_with(kCore) || version == nullptr || !std::string_view(version).starts_with("OpenGL ES")) return text;
    return "#version 300 es\nprecision highp float;\nprecision highp int;\nprecision highp sampler2D;\n#line 2 0\n" +
           text.substr(kCore.size());
}

unsigned compile(GLenum stage, const std::string& name, const std::string& original, const std::string& sources) {
    const unsigned shader = glCreateShader(stage);
    const std::string text = for_this_context(original);
    const char* source = text.c_str();
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (ok != GL_TRUE) {
        GLint length = 0;
        glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
        std::string log(static_cast<std::size_t>(length > 0 ? length : 1), '\0');
        glGetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), nullptr, log.data());
        glDeleteShader(shader);
        log.resize(log.find('\0') == std::string::npos ? log.size() : log.find('\0'));
        throw ShaderError("shader " + name + " failed to compile:\n" + sources + log);
    }
    return shader;
}

}  // namespace

ExpandedShader expand_shader(std::string_view name) {
    ExpandedShader shader;
    expand_into(name, shader.text, shader.files, 0);
    return shader;
}

ShaderProgram::ShaderProgram(std::string_view vertex_file, std::string_view fragment_file) {
    const ExpandedShader vertex = expand_shader(vertex_file);
    const ExpandedShader fragment = expand_shader(fragment_file);
    *this = build(std::string(vertex_file), vertex.text, legend(vertex.files), std::string(fragment_file),
                  fragment.text, legend(fragment.files));
}

ShaderProgram ShaderProgram::from_source(const std::string& vertex_name, const std::string& vertex_text,
                                         const std::string& fragment_name, const std::string& fragment_text) {
    return build(vertex_name, vertex_text, "", fragment_name, fragment_text, "");
}

ShaderProgram ShaderProgram::build(const std::string& vertex_name, const std::string& vertex_text,
                                   const std::string& vertex_sources, const std::string& fragment_name,
                                   const std::string& fragment_text, const std::string& fragment_sources) {
    const unsigned vs = compile(GL_VERTEX_SHADER, vertex_name, vertex_text, vertex_sources);
    unsigned fs = 0;
    try {
        fs = compile(GL_FRAGMENT_SHADER, fragment_name, fragment_text, fragment_sources);
    } catch (...) {
        glDeleteShader(vs);
        throw;
    }
    ShaderProgram program;
    program.program_ = glCreateProgram();
    glAttachShader(program.program_, vs);
    glAttachShader(program.program_, fs);
    glLinkProgram(program.program_);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = GL_FALSE;
    glGetProgramiv(program.program_, GL_LINK_STATUS, &ok);
    if (ok != GL_TRUE) {
        GLint length = 0;
        glGetProgramiv(program.program_, GL_INFO_LOG_LENGTH, &length);
        std::string log(static_cast<std::size_t>(length > 0 ? length : 1), '\0');
        glGetProgramInfoLog(program.program_, static_cast<GLsizei>(log.size()), nullptr, log.data());
        log.resize(log.find('\0') == std::string::npos ? log.size() : log.find('\0'));
        throw ShaderError("shader program " + vertex_name + " + " + fragment_name + " failed to link:\n" + log);
    }
    return program;
}

ShaderProgram::~ShaderProgram() {
    if (program_) glDeleteProgram(program_);
}

ShaderProgram::ShaderProgram(ShaderProgram&& other) noexcept : program_(std::exchange(other.program_, 0)) {}

ShaderProgram& ShaderProgram::operator=(ShaderProgram&& other) noexcept {
    if (this != &other) {
        if (program_) glDeleteProgram(program_);
        program_ = std::exchange(other.program_, 0);
    }
    return *this;
}

void ShaderProgram::use() const { glUseProgram(program_); }

int ShaderProgram::uniform(const char* name) const { return glGetUniformLocation(program_, name); }

}  // namespace softbody::render

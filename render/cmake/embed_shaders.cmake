# Turns shader files into one C++ source: a table of {file name, text} the renderer looks up,
# so the program runs from any working directory. Run as a script:
#   cmake -DOUTPUT=<file.cpp> "-DINPUTS=<a.glsl;b.glsl>" -P embed_shaders.cmake
# Each text becomes a raw string literal; a file that contains the literal's closing
# delimiter is refused rather than silently cut short.
if(NOT OUTPUT OR NOT INPUTS)
  message(FATAL_ERROR "embed_shaders.cmake needs -DOUTPUT=... and -DINPUTS=...")
endif()

set(delimiter "glsl_")
set(entries "")
list(SORT INPUTS)
foreach(input IN LISTS INPUTS)
  get_filename_component(name ${input} NAME)
  file(READ ${input} text)
  string(FIND "${text}" ")${delimiter}\"" clash)
  if(NOT clash EQUAL -1)
    message(FATAL_ERROR "${name}: contains the sequence )${delimiter}\" that ends the embedded text")
  endif()
  string(APPEND entries "    {\"${name}\", R\"${delimiter}(${text})${delimiter}\"},\n")
endforeach()

set(content "// Generated from the files in shaders/ at build time. Do not edit.
#include <string_view>

#include \"render/shader.h\"

namespace softbody::render {

namespace {
struct Embedded {
    std::string_view name;
    std::string_view text;
};
constexpr Embedded kShaders[] = {
${entries}};
}  // namespace

std::optional<std::string_view> embedded_shader(std::string_view name) {
    for (const Embedded& shader : kShaders) {
        if (shader.name == name) return shader.text;
    }
    return std::nullopt;
}

}  // namespace softbody::render
")

# Rewrite only when the content changed, so an unrelated rebuild does not recompile it.
if(EXISTS ${OUTPUT})
  file(READ ${OUTPUT} old)
  if(old STREQUAL content)
    return()
  endif()
endif()
file(WRITE ${OUTPUT} "${content}")

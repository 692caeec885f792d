// Writing a file the user asked for (a preset, a CSV) so that nothing they made is lost: the text
// goes to a temporary file beside it and is then moved into place, so a failure (a full disk, no
// permission) leaves any old file as it was; an existing file is replaced only when asked.
#pragma once

#include <string>

namespace softbody {

enum class Overwrite { No, Yes };

// Throws InputError with one line naming the path and the reason; with Overwrite::No an existing
// file is left untouched ("already exists; not overwriting it").
void write_text_file(const std::string& path, const std::string& text, Overwrite overwrite);

}  // namespace softbody

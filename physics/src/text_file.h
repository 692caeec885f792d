// Reading a whole file the user named, safely: only a regular file is read (a folder, a pipe,
// a socket or a device is refused without ever blocking on it), and never more than a bound.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace softbody {

// Returns the contents of the regular file at `path`. `what` names the kind of file in
// messages ("mesh file"). Throws InputError naming the path when it is missing or unreadable
// (with the system's reason), a folder, not a regular file, or larger than max_bytes.
std::string read_text_file(const std::string& path, std::size_t max_bytes, std::string_view what);

}  // namespace softbody

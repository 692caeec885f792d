// Text from a file or the command line, made fit to quote in a one-line message.
#pragma once

#include <cctype>
#include <cstddef>
#include <string>
#include <string_view>

namespace softbody {

// At most `limit` characters, with control characters (a newline, a NUL) shown as '?' so the
// message stays on one line; "..." marks a cut.
inline std::string printable(std::string_view text, std::size_t limit = 60) {
    std::string out;
    for (const char c : text.substr(0, limit)) out += std::iscntrl(static_cast<unsigned char>(c)) ? '?' : c;
    if (text.size() > limit) out += "...";
    return out;
}

}  // namespace softbody

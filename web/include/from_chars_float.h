// The browser build's stand-in for std::from_chars and std::to_chars on float and double,
// force-included into every C++ source of ours there (web/CMakeLists.txt). Debian's emscripten
// 3.1.6 comes with libc++ 14, which has C++17's from_chars and to_chars for integers only.
//
// Parsed by strtod/strtof, which round correctly as from_chars does, so a number gives the
// same bits as in the native build. from_chars' stricter rules are kept where they differ:
// no leading space or '+', no hexadecimal in the general format, and a number beyond the
// type's range is result_out_of_range with the value left alone. to_chars writes the shortest
// %g text that reads back as the same number (only messages print numbers that way).
#pragma once

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <system_error>

namespace softbody::web_compat {

template <class T>
std::from_chars_result parse_floating(const char* first, const char* last, T& value) {
    std::from_chars_result result{first, std::errc::invalid_argument};
    if (first == last) return result;
    const char* digits = *first == '-' ? first + 1 : first;
    if (digits == last || *digits == '+' || *digits == ' ' || *digits == '\t' || *digits == '\n' || *digits == '\r' ||
        *digits == '\f' || *digits == '\v' || *digits == '-') {
        return result;
    }
    if (last - digits >= 2 && digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X')) {
        // from_chars reads the "0" and stops before the 'x'
        value = *first == '-' ? T(-0.0) : T(0.0);
        return {digits + 1, std::errc()};
    }
    const std::string text(first, last);  // strtod needs the end marked
    char* end = nullptr;
    errno = 0;
    const T parsed = sizeof(T) == sizeof(float) ? T(std::strtof(text.c_str(), &end)) : T(std::strtod(text.c_str(), &end));
    if (end == text.c_str()) return result;
    result.ptr = first + (end - text.c_str());
    if (errno == ERANGE && std::isinf(parsed)) {
        result.ec = std::errc::result_out_of_range;
        return result;
    }
    result.ec = std::errc();
    value = parsed;
    return result;
}

inline std::to_chars_result shortest_text(char* first, char* last, double value) {
    char text[40];
    int length = 0;
    for (int digits = 1; digits <= 17; ++digits) {
        length = std::snprintf(text, sizeof text, "%.*g", digits, value);
        if (std::strtod(text, nullptr) == value || std::isnan(value)) break;
    }
    if (length < 0 || length > last - first) return {last, std::errc::value_too_large};
    for (int i = 0; i < length; ++i) first[i] = text[i];
    return {first + length, std::errc()};
}

}  // namespace softbody::web_compat

namespace std {

inline from_chars_result from_chars(const char* first, const char* last, double& value, chars_format = chars_format::general) {
    return softbody::web_compat::parse_floating(first, last, value);
}
inline from_chars_result from_chars(const char* first, const char* last, float& value, chars_format = chars_format::general) {
    return softbody::web_compat::parse_floating(first, last, value);
}
inline to_chars_result to_chars(char* first, char* last, double value) {
    return softbody::web_compat::shortest_text(first, last, value);
}

}  // namespace std

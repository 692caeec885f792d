// The browser build's stand-in for std::from_chars and std::to_chars on float and double,
// force-included into every C++ source of ours there (web/CMakeLists.txt). Debian's emscripten
// 3.1.6 comes with libc++ 14, which has C++17's from_chars and to_chars for integers only.
//
// Parsed by strtod/strtof, which round correctly as from_chars does, so a number gives the
// same bits as in the native build. from_chars' stricter rules are kept where they differ:
// no leading space or '+', no hexadecimal in the general format, and a number beyond the
// type's range is result_out_of_range with the value left alone. to_chars writes the shortest
// text that reads back as the same number, in to_chars' own form, so that the page prints a
// key's value, a time or a CSV cell exactly as the desktop does.
#pragma once

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
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

// The fewest significant digits that read back as the same number, written as std::to_chars
// writes it: plain decimals unless the exponent form is shorter ("100", "0.02", "1e-07").
template <class T>
std::to_chars_result shortest_text(char* first, char* last, T value) {
    const auto reads_back = [&](const char* text) {
        return sizeof(T) == sizeof(float) ? T(std::strtof(text, nullptr)) == value : T(std::strtod(text, nullptr)) == value;
    };
    char text[64];
    int length = 0;
    if (!std::isfinite(value)) {
        length = std::snprintf(text, sizeof text, "%s", std::isnan(value) ? (std::signbit(value) ? "-nan" : "nan")
                                                                             : (value < 0 ? "-inf" : "inf"));
    } else {
        const int most = sizeof(T) == sizeof(float) ? 9 : 17;
        int digits = 1;
        char exponent_form[64];
        for (; digits <= most; ++digits) {
            std::snprintf(exponent_form, sizeof exponent_form, "%.*e", digits - 1, double(value));
            if (reads_back(exponent_form)) break;
        }
        // The same digits without an exponent: as many decimals as the last digit needs.
        const int exponent = value == 0 ? 0 : std::atoi(std::strchr(exponent_form, 'e') + 1);
        const int decimals = digits - 1 - exponent > 0 ? digits - 1 - exponent : 0;
        char plain[400];
        const int plain_length = std::snprintf(plain, sizeof plain, "%.*f", decimals, double(value));
        // %e keeps trailing zeros of the mantissa ("1.0e+02" cannot happen: digits is the fewest)
        const int exponent_length = int(std::strlen(exponent_form));
        const bool use_plain = plain_length > 0 && plain_length <= exponent_length && plain_length < int(sizeof text);
        length = std::snprintf(text, sizeof text, "%s", use_plain ? plain : exponent_form);
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
inline to_chars_result to_chars(char* first, char* last, float value) {
    return softbody::web_compat::shortest_text(first, last, value);
}

}  // namespace std

// Reading OBJ and OFF files into a RawMesh. Every number and index is checked, with the line
// it came from, before anything trusts it: tinyobjloader on its own turns `nan` into 0, only
// warns about an index out of range, and its polygon splitting takes time quadratic in the
// corners (and drops parts of a polygon that crosses itself). So the file is checked here
// first, tinyobjloader reads the numbers and hands over each face whole, and the faces are
// split into triangles here, in linear time.
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <istream>
#include <streambuf>
#include <string>
#include <vector>

#include "physics/error.h"
#include "message_text.h"
#include "physics/generated.h"
#include "physics/mesh.h"
#include "text_file.h"

namespace softbody {

namespace {

constexpr std::size_t kMaxFileBytes = std::size_t{1} << 30;  // 1 GiB: far beyond any usable mesh
constexpr std::size_t kMaxElements = 50'000'000;              // vertices, normals or UVs a file may hold

// Splits text into lines and tokens, remembering line numbers. Lines end at "\n", "\r\n" or a
// lone "\r"; tokens are separated by spaces and tabs. These are the OBJ reader's own rules, so
// the check below sees the same lines and tokens as the reader.
class LineReader {
public:
    enum class Comments {
        TokenStart,  // OBJ: a token that starts with '#' starts a comment ("3#x" is one token)
        Anywhere,    // OFF: a '#' anywhere starts a comment
    };
    LineReader(const std::string& text, Comments comments) : text_(text), comments_(comments) {}

    // Next line with at least one token (comments removed); false at the end.
    bool next(std::vector<std::string_view>& tokens) {
        while (pos_ < text_.size()) {
            std::size_t end = pos_;
            while (end < text_.size() && text_[end] != '\n' && text_[end] != '\r') ++end;
            std::string_view line(text_.data() + pos_, end - pos_);
            pos_ = end + 1;
            if (end < text_.size() && text_[end] == '\r' && pos_ < text_.size() && text_[pos_] == '\n') ++pos_;
            ++line_;
            raw_ = line;
            had_comment_ = false;
            if (comments_ == Comments::Anywhere) {
                if (const auto hash = line.find('#'); hash != std::string_view::npos) {
                    line = line.substr(0, hash);
                    had_comment_ = true;
                }
            }
            tokens.clear();
            std::size_t i = 0;
            while (i < line.size()) {
                while (i < line.size() && is_space(line[i])) ++i;
                if (i < line.size() && line[i] == '#' && comments_ == Comments::TokenStart) {
                    had_comment_ = true;
                    break;
                }
                const std::size_t start = i;
                while (i < line.size() && !is_space(line[i])) ++i;
                if (i > start) tokens.push_back(line.substr(start, i - start));
            }
            if (!tokens.empty()) return true;
        }
        return false;
    }
    std::size_t line() const { return line_; }
    bool had_comment() const { return had_comment_; }
    std::string_view raw_line() const { return raw_; }  // comment included

private:
    static bool is_space(char c) { return c == ' ' || c == '\t'; }
    const std::string& text_;
    Comments comments_;
    std::size_t pos_ = 0;
    std::size_t line_ = 0;
    std::string_view raw_;
    bool had_comment_ = false;
};

[[noreturn]] void malformed(const std::string& origin, std::size_t line, const std::string& what) {
    throw InputError(origin + ":" + std::to_string(line) + ": " + what);
}

// A leading '+' is allowed ("+1.5"), but only one sign.
std::string_view without_plus(std::string_view token) {
    if (token.size() >= 2 && token.front() == '+' && token[1] != '-' && token[1] != '+') token.remove_prefix(1);
    return token;
}

bool to_float(std::string_view token, float& out) {
    token = without_plus(token);
    double value = 0.0;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (token.empty() || ec != std::errc() || end != token.data() + token.size()) return false;
    out = static_cast<float>(value);
    return std::isfinite(out);
}

// The OBJ reader's own number parser counts a number's exponent in an int without a bound:
// "0e2147483648" (zero, and valid) overflows it. A float's exponent needs three digits; more
// than six significant ones only ever write zero or a number out of range. The reader parses
// a vertex line's first tokens whatever they are, a comment's words included, so every token
// on the line that it could take for a number is checked.
bool exponent_fits_reader(std::string_view token) {
    if (token.empty() || !(std::isdigit(static_cast<unsigned char>(token.front())) || token.front() == '+' ||
                           token.front() == '-' || token.front() == '.')) {
        return true;  // not a number to the reader: it stops at the first character
    }
    const auto e = token.find_first_of("eE");
    if (e == std::string_view::npos) return true;
    std::string_view exponent = token.substr(e + 1);
    if (!exponent.empty() && (exponent.front() == '+' || exponent.front() == '-')) exponent.remove_prefix(1);
    while (!exponent.empty() && exponent.front() == '0') exponent.remove_prefix(1);
    std::size_t digits = 0;
    while (digits < exponent.size() && std::isdigit(static_cast<unsigned char>(exponent[digits]))) ++digits;
    return digits <= 6;
}

bool to_long(std::string_view token, long long& out) {
    token = without_plus(token);
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), out);
    return !token.empty() && ec == std::errc() && end == token.data() + token.size();
}

// A token for a message: at most 40 characters, control bytes shown as '?', so the message
// stays one readable line whatever the file holds.
std::string quoted(std::string_view token) { return "'" + printable(token, 40) + "'"; }

// Checks what tinyobjloader would accept silently: numbers that are not finite numbers, face
// indices that point at no vertex (OBJ indices are 1-based; negative ones count back from the
// last one defined so far), and more triangles than kMaxTriangles.
void check_obj(const std::string& text, const std::string& origin) {
    LineReader reader(text, LineReader::Comments::TokenStart);
    std::vector<std::string_view> tokens;
    long long counts[3] = {0, 0, 0};  // v, vt, vn seen so far
    std::size_t triangles = 0;
    while (reader.next(tokens)) {
        const std::string_view kind = tokens[0];
        const std::size_t line = reader.line();
        if (kind == "v" || kind == "vn" || kind == "vt") {
            const std::size_t needed = kind == "vt" ? 1 : 3;
            if (tokens.size() < needed + 1) {
                malformed(origin, line, "'" + std::string(kind) + "' needs " + std::to_string(needed) + " numbers");
            }
            for (std::size_t t = 1; t < tokens.size(); ++t) {
                float value = 0.0f;
                if (!to_float(tokens[t], value)) {
                    malformed(origin, line, "coordinate " + quoted(tokens[t]) + " is not a finite number");
                }
            }
            for (std::string_view rest = reader.raw_line(); !rest.empty();) {
                const std::size_t start = std::min(rest.find_first_not_of(" \t"), rest.size());
                const std::size_t end = std::min(rest.find_first_of(" \t", start), rest.size());
                if (const auto token = rest.substr(start, end - start); !exponent_fits_reader(token)) {
                    malformed(origin, line, "number " + quoted(token) + " has an exponent out of range");
                }
                rest.remove_prefix(end);
            }
            long long& count = counts[kind == "v" ? 0 : kind == "vt" ? 1 : 2];
            if (++count > static_cast<long long>(kMaxElements)) {
                malformed(origin, line, "more than " + std::to_string(kMaxElements) + " '" + std::string(kind) +
                                            "' lines; too many for a mesh");
            }
        } else if (kind == "f" || kind == "l" || kind == "p") {
            const std::size_t minimum = kind == "f" ? 3 : kind == "l" ? 2 : 1;
            if (reader.had_comment()) {
                // The reader would take the comment's words for indices.
                malformed(origin, line,
                          "a comment after a face's indices is not supported; put it on a line of its own");
            }
            if (tokens.size() < minimum + 1) {
                malformed(origin, line, "'" + std::string(kind) + "' needs at least " + std::to_string(minimum) + " vertices");
            }
            for (std::size_t t = 1; t < tokens.size(); ++t) {
                if (tokens[t].back() == '/') {
                    // The reader would take the next corner's number for the missing index.
                    malformed(origin, line, "face corner " + quoted(tokens[t]) + " ends with '/'");
                }
                std::string_view rest = tokens[t];
                for (int part = 0; part < 3 && !rest.empty(); ++part) {
                    const auto slash = rest.find('/');
                    const std::string_view index_text = rest.substr(0, slash);
                    rest = slash == std::string_view::npos ? std::string_view{} : rest.substr(slash + 1);
                    if (part == 2 && slash != std::string_view::npos) {
                        malformed(origin, line, "face corner " + quoted(tokens[t]) + " has more than three indices");
                    }
                    if (index_text.empty() && part > 0) continue;  // "1//3": no texture coordinate
                    const long long available = counts[part == 0 ? 0 : part == 1 ? 1 : 2];
                    long long index = 0;
                    if (!to_long(index_text, index) || index == 0 || index > available || index < -available) {
                        static const char* names[] = {"vertex", "texture coordinate", "normal"};
                        malformed(origin, line, "face " + std::string(names[part]) + " index " + quoted(index_text) +
                                                    " does not refer to one of the " + std::to_string(available) +
                                                    " defined so far");
                    }
                }
            }
            if (kind == "f") {
                triangles += tokens.size() - 3;  // k corners make k - 2 triangles
                if (triangles > kMaxTriangles) {
                    malformed(origin, line, "more than " + std::to_string(kMaxTriangles) +
                                                " triangles; too many for a mesh (use a smaller or decimated one)");
                }
            }
        }
    }
}

// Lets the OBJ reader read a string in place, without a copy of a file that may be large.
class TextBuffer : public std::streambuf {
public:
    explicit TextBuffer(const std::string& text) {
        char* begin = const_cast<char*>(text.data());  // only ever read: no put area is set
        setg(begin, begin, begin + text.size());
    }
};

// What the reader's callbacks build. An error stops the building (the reader cannot be
// stopped, so later callbacks are ignored) and is thrown once the reader returns.
struct ObjBuilder {
    RawMesh raw;
    std::string error;

    void fail(const std::string& what) {
        if (error.empty()) error = what;
    }

    // An OBJ index (1-based, negative counts back, 0 absent) as a 0-based one, or -1 when
    // absent; -2 when it points at nothing.
    static std::int32_t resolve(int index, std::size_t count) {
        const long long n = static_cast<long long>(count);
        long long i = index > 0 ? index - 1LL : index < 0 ? n + index : -1;
        if (index != 0 && (i < 0 || i >= n)) return -2;
        return static_cast<std::int32_t>(i);
    }

    void add_face(const tinyobj::index_t* indices, int count) {
        if (!error.empty()) return;
        if (count < 3) return fail("a face needs at least three vertices");
        corners.clear();
        for (int c = 0; c < count; ++c) {
            Corner corner;
            corner.position = resolve(indices[c].vertex_index, raw.positions.size());
            corner.uv = resolve(indices[c].texcoord_index, raw.uvs.size());
            corner.normal = resolve(indices[c].normal_index, raw.normals.size());
            if (corner.position < 0 || corner.uv < -1 || corner.normal < -1) {
                return fail("a face index does not refer to a vertex, texture coordinate or normal");
            }
            corners.push_back(corner);
        }
        if (raw.triangle_corners.size() / 3 + corners.size() - 2 > kMaxTriangles) {
            return fail("more than " + std::to_string(kMaxTriangles) + " triangles; too many for a mesh");
        }
        auto triangle = [&](std::size_t a, std::size_t b, std::size_t c) {
            raw.triangle_corners.push_back(corners[a]);
            raw.triangle_corners.push_back(corners[b]);
            raw.triangle_corners.push_back(corners[c]);
        };
        if (corners.size() == 4) {
            // Along the shorter diagonal (as the reader's own splitting did, so quads keep
            // their triangles), computed in float as it was.
            auto distance_sq = [&](std::size_t a, std::size_t b) {
                const Vec3 d = raw.positions[static_cast<std::size_t>(corners[b].position)] -
                               raw.positions[static_cast<std::size_t>(corners[a].position)];
                return d.x * d.x + d.y * d.y + d.z * d.z;
            };
            if (distance_sq(0, 2) < distance_sq(1, 3)) {
                triangle(0, 1, 2);
                triangle(0, 2, 3);
            } else {
                triangle(0, 1, 3);
                triangle(1, 2, 3);
            }
            return;
        }
        for (std::size_t c = 1; c + 1 < corners.size(); ++c) triangle(0, c, c + 1);  // a fan
    }

private:
    std::vector<Corner> corners;  // kept between faces: no allocation per face
};

}  // namespace

RawMesh parse_obj_text(const std::string& text, const std::string& origin) {
    check_obj(text, origin);

    tinyobj::callback_t callback;
    callback.vertex_cb = [](void* user, tinyobj::real_t x, tinyobj::real_t y, tinyobj::real_t z, tinyobj::real_t) {
        static_cast<ObjBuilder*>(user)->raw.positions.push_back({x, y, z});
    };
    callback.normal_cb = [](void* user, tinyobj::real_t x, tinyobj::real_t y, tinyobj::real_t z) {
        auto* builder = static_cast<ObjBuilder*>(user);
        const Vec3 n{x, y, z};
        if (!is_finite(n)) builder->fail("a normal is not finite");
        builder->raw.normals.push_back(n);
    };
    callback.texcoord_cb = [](void* user, tinyobj::real_t u, tinyobj::real_t v, tinyobj::real_t) {
        auto* builder = static_cast<ObjBuilder*>(user);
        if (!std::isfinite(u) || !std::isfinite(v)) builder->fail("a texture coordinate is not finite");
        builder->raw.uvs.push_back({u, v});
    };
    callback.index_cb = [](void* user, tinyobj::index_t* indices, int count) {
        static_cast<ObjBuilder*>(user)->add_face(indices, count);
    };

    ObjBuilder builder;
    TextBuffer buffer(text);
    std::istream in(&buffer);
    std::string warnings, errors;
    // No material reader: `mtllib` lines are skipped, and no other file is ever opened.
    const bool ok = tinyobj::LoadObjWithCallback(in, callback, &builder, nullptr, &warnings, &errors);
    if (!ok && builder.error.empty()) {
        while (!errors.empty() && (errors.back() == '\n' || errors.back() == '\r')) errors.pop_back();
        if (const auto nl = errors.find('\n'); nl != std::string::npos) errors = errors.substr(0, nl);
        builder.fail(errors.empty() ? "unreadable" : errors);
    }
    if (!builder.error.empty()) throw InputError(origin + ": malformed OBJ: " + builder.error);
    for (const Vec3& p : builder.raw.positions) {
        if (!is_finite(p)) throw InputError(origin + ": malformed OBJ: a vertex coordinate is not finite");
    }
    return std::move(builder.raw);
}

RawMesh parse_off_text(const std::string& text, const std::string& origin) {
    LineReader reader(text, LineReader::Comments::Anywhere);
    std::vector<std::string_view> tokens;
    if (!reader.next(tokens)) throw InputError(origin + ": empty file; expected an OFF header");

    // Header: "OFF" (or COFF/NOFF/...), then "vertices faces edges", possibly on the same line.
    std::size_t first = 0;
    const std::string_view magic = tokens[0];
    if (magic.size() >= 3 && magic.substr(magic.size() - 3) == "OFF") {
        first = 1;
    } else {
        malformed(origin, reader.line(), "expected 'OFF' at the start of the file");
    }
    if (tokens.size() == first) {  // "OFF" alone on its line: the counts are on the next one
        if (!reader.next(tokens)) malformed(origin, reader.line(), "expected the vertex and face counts");
        first = 0;
    }
    long long counts[2] = {0, 0};
    if (tokens.size() < first + 2 || !to_long(tokens[first], counts[0]) || !to_long(tokens[first + 1], counts[1])) {
        malformed(origin, reader.line(), "expected the vertex and face counts");
    }
    if (counts[0] < 0 || counts[1] < 0 || counts[0] > static_cast<long long>(kMaxElements) ||
        counts[1] > static_cast<long long>(kMaxElements)) {
        malformed(origin, reader.line(), "vertex or face count out of range (0 to " + std::to_string(kMaxElements) + ")");
    }

    RawMesh raw;
    raw.positions.reserve(static_cast<std::size_t>(std::min<long long>(counts[0], 1 << 20)));
    for (long long i = 0; i < counts[0]; ++i) {
        if (!reader.next(tokens)) {
            malformed(origin, reader.line(), "file ends after " + std::to_string(i) + " of " +
                                                 std::to_string(counts[0]) + " vertices");
        }
        Vec3 p;
        if (tokens.size() < 3) malformed(origin, reader.line(), "a vertex needs three coordinates");
        if (!to_float(tokens[0], p.x) || !to_float(tokens[1], p.y) || !to_float(tokens[2], p.z)) {
            malformed(origin, reader.line(), "vertex coordinate is not a finite number");
        }
        raw.positions.push_back(p);
    }
    std::vector<std::int32_t> face;
    for (long long f = 0; f < counts[1]; ++f) {
        if (!reader.next(tokens)) {
            malformed(origin, reader.line(), "file ends after " + std::to_string(f) + " of " +
                                                 std::to_string(counts[1]) + " faces");
        }
        long long k = 0;
        if (!to_long(tokens[0], k) || k < 1 || static_cast<unsigned long long>(k) + 1 > tokens.size()) {
            malformed(origin, reader.line(), "a face must start with its vertex count, then that many indices");
        }
        face.clear();
        for (long long c = 1; c <= k; ++c) {
            long long index = 0;
            if (!to_long(tokens[static_cast<std::size_t>(c)], index) || index < 0 || index >= counts[0]) {
                malformed(origin, reader.line(), "face index " + quoted(tokens[static_cast<std::size_t>(c)]) +
                                                     " is not one of the " + std::to_string(counts[0]) + " vertices");
            }
            face.push_back(static_cast<std::int32_t>(index));
        }
        if (face.size() >= 3 && raw.triangle_corners.size() / 3 + face.size() - 2 > kMaxTriangles) {
            malformed(origin, reader.line(), "more than " + std::to_string(kMaxTriangles) +
                                                 " triangles; too many for a mesh (use a smaller or decimated one)");
        }
        for (std::size_t c = 1; c + 1 < face.size(); ++c) {  // a fan: (0, c, c+1)
            raw.triangle_corners.push_back({face[0], -1, -1});
            raw.triangle_corners.push_back({face[c], -1, -1});
            raw.triangle_corners.push_back({face[c + 1], -1, -1});
        }
    }
    return raw;
}

Mesh load_mesh(const std::string& path) {
    if (is_generated(path)) return generated_mesh(path);  // "cloud:N": made, not read
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext != ".obj" && ext != ".off") {
        throw InputError(path + ": unsupported mesh format '" + ext + "' (use .obj or .off)");
    }
    const std::string text = read_text_file(path, kMaxFileBytes, "mesh file");
    const RawMesh raw = ext == ".obj" ? parse_obj_text(text, path) : parse_off_text(text, path);
    return build_mesh(raw, path);
}

}  // namespace softbody

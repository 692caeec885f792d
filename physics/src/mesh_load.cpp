// Reading OBJ and OFF files into a RawMesh. Every number and index is checked, with the line
// it came from, before anything trusts it: tinyobjloader on its own turns `nan` into 0, only
// warns about an index out of range, and its polygon splitting takes time quadratic in the
// corners (and drops parts of a polygon that crosses itself). So the file is checked here
// first, tinyobjloader reads the numbers and hands over each face whole, and the faces are
// split into triangles here, in linear time.
//
// The check refuses what would put a particle in the wrong place and forgives what only the
// drawing uses (mesh.h lists both). Where the reader would misread a forgiven fault (a comment
// after a face's indices, an index that names no normal), the reader is handed a copy of the
// text with that fault blanked out by spaces: same length, same lines, nothing else changed.
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
    // `start`: where reading begins (past a byte-order mark).
    LineReader(const std::string& text, Comments comments, std::size_t start = 0)
        : text_(text), comments_(comments), pos_(start) {}

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
            comment_ = std::string_view::npos;
            if (comments_ == Comments::Anywhere) {
                if (const auto hash = line.find('#'); hash != std::string_view::npos) {
                    line = line.substr(0, hash);
                    comment_ = offset(line) + hash;
                }
            }
            tokens.clear();
            std::size_t i = 0;
            while (i < line.size()) {
                while (i < line.size() && is_space(line[i])) ++i;
                if (i < line.size() && line[i] == '#' && comments_ == Comments::TokenStart) {
                    comment_ = offset(line) + i;
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
    std::string_view raw_line() const { return raw_; }  // comment included
    // The current line's comment as offsets into the text, [comment_begin, line_end), or
    // comment_begin() == npos when it has none.
    std::size_t comment_begin() const { return comment_; }
    std::size_t line_end() const { return offset(raw_) + raw_.size(); }
    // Where a token (a view into the text) starts in the text.
    std::size_t offset(std::string_view part) const { return static_cast<std::size_t>(part.data() - text_.data()); }

private:
    static bool is_space(char c) { return c == ' ' || c == '\t'; }
    const std::string& text_;
    Comments comments_;
    std::size_t pos_ = 0;
    std::size_t line_ = 0;
    std::string_view raw_;
    std::size_t comment_ = std::string_view::npos;
};

// A byte-order mark: UTF-8's is skipped (some editors write one); UTF-16 text is refused, as
// its every other byte is zero and no line of it would read.
std::size_t skip_byte_order_mark(const std::string& text, const std::string& origin) {
    auto starts = [&](std::string_view prefix) { return std::string_view(text).substr(0, prefix.size()) == prefix; };
    if (starts("\xFE\xFF") || starts("\xFF\xFE")) {
        throw InputError(origin + ": UTF-16 text; save the file as UTF-8 or ASCII");
    }
    return starts("\xEF\xBB\xBF") ? 3 : 0;
}

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

// An index as written: digits with at most one sign. One too large for a long long is still a
// whole number (out of range), not a malformed one.
bool is_whole_number(std::string_view token) {
    token = without_plus(token);
    if (!token.empty() && token.front() == '-') token.remove_prefix(1);
    return !token.empty() && std::all_of(token.begin(), token.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// Faults of one kind that the check forgives: the first is described, the others counted, so
// a file gives one warning line per kind of fault however often it repeats it.
struct Forgiven {
    std::string first;
    std::size_t count = 0;

    void add(const std::string& origin, std::size_t line, const std::string& what) {
        if (count++ == 0) first = origin + ":" + std::to_string(line) + ": " + what;
    }
    void report(std::vector<std::string>& warnings) const {
        if (count == 0) return;
        warnings.push_back(count == 1 ? first : first + " (" + std::to_string(count - 1) + " more like it)");
    }
};

// What the check hands the reader and the builder.
struct ObjCheck {
    // The text the reader reads: empty when the file's own text will do, else a copy with the
    // forgiven faults blanked out (same length, so the same lines).
    std::string reader_text;
    // Per `vn` and `vt` line, in order: whether its numbers are finite (else faces that name it
    // go without it).
    std::vector<bool> normal_usable, uv_usable;
    std::vector<std::string> warnings;
};

// Checks what tinyobjloader would accept silently or misread: numbers that are not finite
// numbers, face indices that point at no vertex (OBJ indices are 1-based; negative ones count
// back from the last one defined so far), and more triangles than kMaxTriangles. Refuses what
// moves or loses a particle; blanks out, for the reader, what it forgives.
ObjCheck check_obj(const std::string& text, const std::string& origin) {
    ObjCheck check;
    auto blank = [&](std::size_t begin, std::size_t end) {
        if (check.reader_text.empty()) check.reader_text = text;
        std::fill(check.reader_text.begin() + static_cast<std::ptrdiff_t>(begin),
                  check.reader_text.begin() + static_cast<std::ptrdiff_t>(end), ' ');
    };
    const std::size_t start = skip_byte_order_mark(text, origin);
    if (start > 0) blank(0, start);

    LineReader reader(text, LineReader::Comments::TokenStart, start);
    std::vector<std::string_view> tokens;
    long long counts[3] = {0, 0, 0};  // v, vt, vn seen so far
    std::size_t triangles = 0;
    Forgiven bad_normal, bad_uv, dangling_normal, dangling_uv;
    while (reader.next(tokens)) {
        const std::string_view kind = tokens[0];
        const std::size_t line = reader.line();
        const bool element = kind == "v" || kind == "vn" || kind == "vt" || kind == "f" || kind == "l" || kind == "p";
        if (element && reader.comment_begin() != std::string_view::npos) {
            // The reader would take the comment's words for numbers or indices.
            blank(reader.comment_begin(), reader.line_end());
        }
        if (kind == "v" || kind == "vn" || kind == "vt") {
            const bool position = kind == "v";
            const std::size_t needed = kind == "vt" ? 1 : 3;
            // A position needs its three numbers; a `vn` or `vt` with none is not even counted
            // by the reader, which would shift every later index.
            if (tokens.size() < (position ? needed + 1 : 2)) {
                malformed(origin, line, "'" + std::string(kind) + "' needs " + std::to_string(needed) + " numbers");
            }
            std::string fault = tokens.size() < needed + 1 ? "needs " + std::to_string(needed) + " numbers" : "";
            for (std::size_t t = 1; t < tokens.size(); ++t) {
                float value = 0.0f;
                if (!exponent_fits_reader(tokens[t])) {
                    if (position) malformed(origin, line, "number " + quoted(tokens[t]) + " has an exponent out of range");
                    // The reader must not parse it; the line is unusable anyway.
                    blank(reader.offset(tokens[t]), reader.offset(tokens[t]) + tokens[t].size());
                    if (fault.empty()) fault = quoted(tokens[t]) + " has an exponent out of range";
                } else if (!to_float(tokens[t], value)) {
                    if (position) malformed(origin, line, "coordinate " + quoted(tokens[t]) + " is not a finite number");
                    if (fault.empty()) fault = quoted(tokens[t]) + " is not a finite number";
                }
            }
            long long& count = counts[position ? 0 : kind == "vt" ? 1 : 2];
            if (++count > static_cast<long long>(kMaxElements)) {
                malformed(origin, line, "more than " + std::to_string(kMaxElements) + " '" + std::string(kind) +
                                            "' lines; too many for a mesh");
            }
            if (kind == "vn") {
                check.normal_usable.push_back(fault.empty());
                if (!fault.empty()) bad_normal.add(origin, line, "normal " + fault + "; faces that use it get recomputed normals");
            } else if (kind == "vt") {
                check.uv_usable.push_back(fault.empty());
                if (!fault.empty()) bad_uv.add(origin, line, "texture coordinate " + fault + "; faces that use it go without");
            }
        } else if (kind == "f" || kind == "l" || kind == "p") {
            const std::size_t minimum = kind == "f" ? 3 : kind == "l" ? 2 : 1;
            if (tokens.size() < minimum + 1) {
                malformed(origin, line, "'" + std::string(kind) + "' needs at least " + std::to_string(minimum) + " vertices");
            }
            for (std::size_t t = 1; t < tokens.size(); ++t) {
                const std::string_view corner = tokens[t];
                std::string_view parts[3];
                std::size_t part_count = 0;
                for (std::string_view rest = corner;;) {
                    const auto slash = rest.find('/');
                    if (part_count == 3) {
                        malformed(origin, line, "face corner " + quoted(corner) + " has more than three indices");
                    }
                    parts[part_count++] = rest.substr(0, slash);
                    if (slash == std::string_view::npos) break;
                    rest = rest.substr(slash + 1);
                }
                // parts[0]: the vertex (refused when it names none); [1] the texture
                // coordinate, [2] the normal (dropped when they name none).
                static const char* names[] = {"vertex", "texture coordinate", "normal"};
                bool keep[3] = {true, false, false};
                for (std::size_t part = 0; part < part_count; ++part) {
                    const std::string_view index_text = parts[part];
                    if (index_text.empty() && part > 0) continue;  // "1//3": no texture coordinate; "1/": none either
                    const long long available = counts[part];
                    long long index = 0;
                    const bool whole = is_whole_number(index_text);
                    const bool valid = whole && to_long(index_text, index) && index != 0 && index <= available &&
                                       index >= -available;
                    const std::string what = "face " + std::string(names[part]) + " index " + quoted(index_text) +
                                             " does not refer to one of the " + std::to_string(available) + " defined so far";
                    if (part == 0 || !whole) {
                        if (!valid) malformed(origin, line, what);
                    } else if (!valid) {
                        (part == 1 ? dangling_uv : dangling_normal)
                            .add(origin, line, what + (part == 1 ? "; those corners go without" : "; normals are recomputed"));
                        continue;
                    }
                    keep[part] = true;
                }
                // What the reader is to see: the corner without what was dropped and without a
                // trailing '/' (the reader would take the next corner's number for the index
                // that '/' announces), blanked to the same length.
                std::string canonical(parts[0]);
                if (keep[1]) canonical += "/" + std::string(parts[1]);
                if (keep[2]) canonical += (keep[1] ? "/" : "//") + std::string(parts[2]);
                if (canonical.size() != corner.size()) {
                    if (check.reader_text.empty()) check.reader_text = text;
                    const std::size_t at = reader.offset(corner);
                    check.reader_text.replace(at, canonical.size(), canonical);
                    blank(at + canonical.size(), at + corner.size());
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
    dangling_normal.report(check.warnings);
    bad_normal.report(check.warnings);
    dangling_uv.report(check.warnings);
    bad_uv.report(check.warnings);
    return check;
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
    const ObjCheck* check = nullptr;

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
            // A normal or texture coordinate whose numbers are not finite: the corner goes
            // without (the check has warned).
            if (corner.uv >= 0 && !usable(check->uv_usable, corner.uv)) corner.uv = -1;
            if (corner.normal >= 0 && !usable(check->normal_usable, corner.normal)) corner.normal = -1;
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

    static bool usable(const std::vector<bool>& flags, std::int32_t index) {
        return static_cast<std::size_t>(index) < flags.size() && flags[static_cast<std::size_t>(index)];
    }

private:
    std::vector<Corner> corners;  // kept between faces: no allocation per face
};

}  // namespace

RawMesh parse_obj_text(const std::string& text, const std::string& origin) {
    const ObjCheck check = check_obj(text, origin);

    tinyobj::callback_t callback;
    callback.vertex_cb = [](void* user, tinyobj::real_t x, tinyobj::real_t y, tinyobj::real_t z, tinyobj::real_t) {
        static_cast<ObjBuilder*>(user)->raw.positions.push_back({x, y, z});
    };
    callback.normal_cb = [](void* user, tinyobj::real_t x, tinyobj::real_t y, tinyobj::real_t z) {
        // One that the check found unusable is kept as (0, 0, 0), so later indices still match.
        auto* builder = static_cast<ObjBuilder*>(user);
        const Vec3 n{x, y, z};
        const bool ok = is_finite(n) && ObjBuilder::usable(builder->check->normal_usable,
                                                           static_cast<std::int32_t>(builder->raw.normals.size()));
        builder->raw.normals.push_back(ok ? n : Vec3{});
    };
    callback.texcoord_cb = [](void* user, tinyobj::real_t u, tinyobj::real_t v, tinyobj::real_t) {
        auto* builder = static_cast<ObjBuilder*>(user);
        const bool ok = std::isfinite(u) && std::isfinite(v) &&
                        ObjBuilder::usable(builder->check->uv_usable, static_cast<std::int32_t>(builder->raw.uvs.size()));
        builder->raw.uvs.push_back(ok ? std::array<float, 2>{u, v} : std::array<float, 2>{0.0f, 0.0f});
    };
    callback.index_cb = [](void* user, tinyobj::index_t* indices, int count) {
        static_cast<ObjBuilder*>(user)->add_face(indices, count);
    };

    ObjBuilder builder;
    builder.check = &check;
    TextBuffer buffer(check.reader_text.empty() ? text : check.reader_text);
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
    builder.raw.warnings = check.warnings;
    return std::move(builder.raw);
}

RawMesh parse_off_text(const std::string& text, const std::string& origin) {
    LineReader reader(text, LineReader::Comments::Anywhere, skip_byte_order_mark(text, origin));
    std::vector<std::string_view> tokens;
    if (!reader.next(tokens)) throw InputError(origin + ": empty file; expected an OFF header");

    // Header: the keyword [ST][C][N][4][n]OFF, then "vertices faces edges", possibly on the same
    // line. The keyword is optional (many old files lack it): a file may open with the counts.
    // Texture coordinates (ST), colours (C) and normals (N) follow a vertex's x y z on its
    // line and are ignored, as are a face's colour numbers after its indices. A fourth
    // coordinate (4: homogeneous or 4-D, n: any dimension) would move every particle, and a
    // binary file is not text: both refused.
    std::size_t first = 0;
    const std::string_view magic = tokens[0];
    long long ignored = 0;
    if (to_long(magic, ignored)) {
        first = 0;  // no keyword: the counts
    } else if (magic.size() >= 3 && magic.substr(magic.size() - 3) == "OFF") {
        std::string_view prefix = magic.substr(0, magic.size() - 3);
        for (const std::string_view known : {"ST", "C", "N"}) {
            if (prefix.substr(0, known.size()) == known) prefix.remove_prefix(known.size());
        }
        if (!prefix.empty() && (prefix.front() == '4' || prefix.front() == 'n')) {
            malformed(origin, reader.line(), quoted(magic) + ": vertices with more than three coordinates (4-D, "
                                             "homogeneous or n-D OFF) are not supported");
        }
        if (!prefix.empty()) malformed(origin, reader.line(), "unknown OFF variant " + quoted(magic));
        if (tokens.size() > 1 && tokens[1] == "BINARY") {
            malformed(origin, reader.line(), "binary OFF is not supported; save the file as text OFF");
        }
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

// Reading OBJ and OFF files into a RawMesh. Every number and index is checked, with the line
// it came from, before anything trusts it: tinyobjloader on its own turns `nan` into 0 and
// only warns about an index out of range.
#include <tiny_obj_loader.h>

#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "physics/error.h"
#include "physics/mesh.h"

namespace softbody {

namespace {

constexpr std::size_t kMaxFileBytes = std::size_t{1} << 30;  // 1 GiB: far beyond any usable mesh
constexpr std::size_t kMaxElements = 50'000'000;              // vertices or faces a file may declare

// Splits text into lines and whitespace-separated tokens, remembering line numbers.
class LineReader {
public:
    explicit LineReader(const std::string& text) : text_(text) {}

    // Next line with at least one token (comments after '#' removed); false at the end.
    bool next(std::vector<std::string_view>& tokens) {
        while (pos_ < text_.size()) {
            const std::size_t end = std::min(text_.find('\n', pos_), text_.size());
            std::string_view line(text_.data() + pos_, end - pos_);
            pos_ = end + 1;
            ++line_;
            if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
            tokens.clear();
            std::size_t i = 0;
            while (i < line.size()) {
                while (i < line.size() && is_space(line[i])) ++i;
                const std::size_t start = i;
                while (i < line.size() && !is_space(line[i])) ++i;
                if (i > start) tokens.push_back(line.substr(start, i - start));
            }
            if (!tokens.empty()) return true;
        }
        return false;
    }
    std::size_t line() const { return line_; }

private:
    static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
    const std::string& text_;
    std::size_t pos_ = 0;
    std::size_t line_ = 0;
};

[[noreturn]] void malformed(const std::string& origin, std::size_t line, const std::string& what) {
    throw InputError(origin + ":" + std::to_string(line) + ": " + what);
}

bool to_float(std::string_view token, float& out) {
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    double value = 0.0;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (ec != std::errc() || end != token.data() + token.size()) return false;
    out = static_cast<float>(value);
    return std::isfinite(out);
}

bool to_long(std::string_view token, long long& out) {
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), out);
    return !token.empty() && ec == std::errc() && end == token.data() + token.size();
}

std::string quoted(std::string_view token) {
    std::string out("'");
    out.append(token.substr(0, 40)).append(token.size() > 40 ? "...'" : "'");
    return out;
}

// Checks what tinyobjloader would accept silently: numbers that are not finite numbers, and
// face indices that point at no vertex (OBJ indices are 1-based; negative ones count back).
void check_obj(const std::string& text, const std::string& origin) {
    LineReader reader(text);
    std::vector<std::string_view> tokens;
    long long counts[3] = {0, 0, 0};  // v, vt, vn seen so far
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
            ++counts[kind == "v" ? 0 : kind == "vt" ? 1 : 2];
            if (counts[0] > static_cast<long long>(kMaxElements)) malformed(origin, line, "too many vertices");
        } else if (kind == "f" || kind == "l" || kind == "p") {
            const std::size_t minimum = kind == "f" ? 3 : kind == "l" ? 2 : 1;
            if (tokens.size() < minimum + 1) {
                malformed(origin, line, "'" + std::string(kind) + "' needs at least " + std::to_string(minimum) + " vertices");
            }
            for (std::size_t t = 1; t < tokens.size(); ++t) {
                std::string_view rest = tokens[t];
                for (int part = 0; part < 3 && !rest.empty(); ++part) {
                    const auto slash = rest.find('/');
                    const std::string_view index_text = rest.substr(0, slash);
                    rest = slash == std::string_view::npos ? std::string_view{} : rest.substr(slash + 1);
                    if (index_text.empty() && part > 0) continue;  // "1//3": no texture coordinate
                    const long long available = counts[part == 0 ? 0 : part == 1 ? 1 : 2];
                    long long index = 0;
                    if (!to_long(index_text, index) || index == 0 || index > available || -index > available) {
                        static const char* names[] = {"vertex", "texture coordinate", "normal"};
                        malformed(origin, line, "face " + std::string(names[part]) + " index " + quoted(index_text) +
                                                    " does not refer to one of the " + std::to_string(available) +
                                                    " defined so far");
                    }
                }
            }
        }
    }
}

std::string read_file(const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw InputError(path + ": is a folder, not a mesh file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path + ": cannot open mesh file (" + std::strerror(errno) + ")");
    std::string text;
    char buffer[1 << 16];
    while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
        text.append(buffer, static_cast<std::size_t>(in.gcount()));
        if (text.size() > kMaxFileBytes) throw InputError(path + ": larger than 1 GiB; too large for a mesh");
    }
    if (in.bad()) throw InputError(path + ": cannot read mesh file");
    return text;
}

std::string lower_extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

}  // namespace

RawMesh parse_obj_text(const std::string& text, const std::string& origin) {
    check_obj(text, origin);

    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    if (!reader.ParseFromString(text, std::string(), config)) {
        std::string message = reader.Error();
        while (!message.empty() && (message.back() == '\n' || message.back() == '\r')) message.pop_back();
        if (const auto nl = message.find('\n'); nl != std::string::npos) message = message.substr(0, nl);
        throw InputError(origin + ": malformed OBJ: " + (message.empty() ? "unreadable" : message));
    }
    const tinyobj::attrib_t& attrib = reader.GetAttrib();

    RawMesh raw;
    const std::size_t vertex_count = attrib.vertices.size() / 3;
    raw.positions.reserve(vertex_count);
    for (std::size_t i = 0; i < vertex_count; ++i) {
        raw.positions.push_back({attrib.vertices[3 * i], attrib.vertices[3 * i + 1], attrib.vertices[3 * i + 2]});
    }
    for (std::size_t i = 0; i + 2 < attrib.normals.size(); i += 3) {
        raw.normals.push_back({attrib.normals[i], attrib.normals[i + 1], attrib.normals[i + 2]});
    }
    for (std::size_t i = 0; i + 1 < attrib.texcoords.size(); i += 2) {
        raw.uvs.push_back({attrib.texcoords[i], attrib.texcoords[i + 1]});
    }
    auto in_range = [](int index, std::size_t size) { return index >= -1 && index < static_cast<long long>(size); };
    for (const auto& shape : reader.GetShapes()) {
        std::size_t offset = 0;
        for (const unsigned char corners : shape.mesh.num_face_vertices) {
            if (corners == 3 && offset + 3 <= shape.mesh.indices.size()) {
                for (std::size_t c = 0; c < 3; ++c) {
                    const tinyobj::index_t& index = shape.mesh.indices[offset + c];
                    if (index.vertex_index < 0 || !in_range(index.vertex_index, vertex_count) ||
                        !in_range(index.normal_index, raw.normals.size()) ||
                        !in_range(index.texcoord_index, raw.uvs.size())) {
                        throw InputError(origin + ": malformed OBJ: a face index is out of range");
                    }
                    raw.triangle_corners.push_back({index.vertex_index, index.normal_index, index.texcoord_index});
                }
            }
            offset += corners;
        }
    }
    return raw;
}

RawMesh parse_off_text(const std::string& text, const std::string& origin) {
    LineReader reader(text);
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
        malformed(origin, reader.line(), "vertex or face count out of range");
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
    for (long long f = 0; f < counts[1]; ++f) {
        if (!reader.next(tokens)) {
            malformed(origin, reader.line(), "file ends after " + std::to_string(f) + " of " +
                                                 std::to_string(counts[1]) + " faces");
        }
        long long k = 0;
        if (!to_long(tokens[0], k) || k < 1 || static_cast<std::size_t>(k) + 1 > tokens.size()) {
            malformed(origin, reader.line(), "a face must start with its vertex count, then that many indices");
        }
        std::vector<std::int32_t> face;
        for (long long c = 1; c <= k; ++c) {
            long long index = 0;
            if (!to_long(tokens[static_cast<std::size_t>(c)], index) || index < 0 || index >= counts[0]) {
                malformed(origin, reader.line(), "face index " + quoted(tokens[static_cast<std::size_t>(c)]) +
                                                     " is not one of the " + std::to_string(counts[0]) + " vertices");
            }
            face.push_back(static_cast<std::int32_t>(index));
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
    const std::string ext = lower_extension(path);
    if (ext != ".obj" && ext != ".off") {
        throw InputError(path + ": unsupported mesh format '" + ext + "' (use .obj or .off)");
    }
    const std::string text = read_file(path);
    const RawMesh raw = ext == ".obj" ? parse_obj_text(text, path) : parse_off_text(text, path);
    return build_mesh(raw, path);
}

}  // namespace softbody

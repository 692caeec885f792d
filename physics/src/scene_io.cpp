#include "physics/scene_io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "message_text.h"
#include "physics/error.h"
#include "text_file.h"

namespace softbody {

namespace {

using nlohmann::json;
namespace fs = std::filesystem;

constexpr std::size_t kMaxSceneBytes = 1 << 20;  // a scene is a few hundred bytes
constexpr int kMaxDepth = 8;                      // a scene is one flat object

std::size_t line_of_offset(const std::string& text, std::size_t offset) {
    offset = std::min(offset, text.size());
    return 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + static_cast<long>(offset), '\n'));
}

// Line where "key" first appears, so an error can point at it.
std::string where(const std::string& origin, const std::string& text, const std::string& key) {
    const auto at = text.find("\"" + key + "\"");
    if (at == std::string::npos) return origin;
    return origin + ":" + std::to_string(line_of_offset(text, at));
}

std::string type_name(const json& value) {
    if (value.is_boolean()) return "true/false";
    if (value.is_number()) return "a number";
    return value.type_name();
}

// The command-line text for a JSON value of the key's type (set_param then checks the range).
std::string value_text(const ParamInfo& info, const json& value) {
    auto fail = [&](const char* expected) -> std::string {
        throw InputError("parameter '" + std::string(info.key) + "': expected " + expected + ", got " +
                         type_name(value));
    };
    auto number = [](const json& v) {
        std::ostringstream out;
        out.precision(9);
        out << v.get<double>();
        return out.str();
    };
    switch (info.type) {
        case ParamType::Float:
            if (!value.is_number()) return fail("a number");
            return number(value);
        case ParamType::Int:
            if (!value.is_number_integer()) return fail("a whole number");
            return value.dump();  // exact, even beyond the range of long long (set_param refuses it)
        case ParamType::Bool:
            if (!value.is_boolean()) return fail("true or false");
            return value.get<bool>() ? "true" : "false";
        case ParamType::Vec3:
            if (!value.is_array() || value.size() != 3 || !value[0].is_number() || !value[1].is_number() ||
                !value[2].is_number()) {
                return fail("an array of three numbers [x, y, z]");
            }
            return number(value[0]) + "," + number(value[1]) + "," + number(value[2]);
        case ParamType::String:
        case ParamType::Integrator:
            if (!value.is_string()) return fail("a string");
            return value.get<std::string>();
        case ParamType::IndexList: {
            if (!value.is_array()) return fail("an array of vertex indices");
            std::string out;
            for (const auto& item : value) {
                if (!item.is_number_integer()) return fail("an array of vertex indices (whole numbers)");
                if (!out.empty()) out += ',';
                out += item.dump();
            }
            return out;
        }
    }
    return {};
}

json value_json(const Params& params, const ParamInfo& info) {
    const std::string text = param_text(params, info.key);
    switch (info.type) {
        case ParamType::Float: return json(std::stod(text));
        case ParamType::Int: return json(std::stoll(text));
        case ParamType::Bool: return json(text == "true");
        case ParamType::Vec3: {
            json v = json::array();
            std::istringstream parts(text);
            for (std::string part; std::getline(parts, part, ',');) v.push_back(std::stod(part));
            return v;
        }
        case ParamType::String:
        case ParamType::Integrator: return json(text);
        case ParamType::IndexList: return json(params.pinned);
    }
    return {};
}

[[noreturn]] void io_error(const std::string& path, const std::string& what) {
    throw InputError(path + ": " + what + " (" + std::strerror(errno) + ")");
}

}  // namespace

Params parse_scene(const std::string& text, const std::string& origin, const Params& base) {
    if (text.size() > kMaxSceneBytes) {
        throw InputError(origin + ": too large for a scene file (" + std::to_string(text.size()) + " bytes)");
    }
    json root;
    try {
        root = json::parse(text, [](int depth, json::parse_event_t, json&) {
            if (depth > kMaxDepth) throw InputError("nested too deeply for a scene file");
            return true;
        });
    } catch (const json::parse_error& e) {
        std::string message = e.what();
        if (const auto at = message.find("; "); at != std::string::npos) message = message.substr(at + 2);
        throw InputError(origin + ":" + std::to_string(line_of_offset(text, e.byte ? e.byte - 1 : 0)) +
                         ": malformed JSON: " + printable(message, 200));
    } catch (const json::out_of_range& e) {
        // A number beyond double ("1e400"): reported without a position, so the line is the
        // one where its text first appears.
        std::string message = e.what();
        if (const auto at = message.find("] "); at != std::string::npos) message = message.substr(at + 2);
        std::string where_it_is = origin;
        if (const auto open = message.find('\''), close = message.rfind('\'');
            open != std::string::npos && close > open) {
            if (const auto at = text.find(message.substr(open + 1, close - open - 1)); at != std::string::npos) {
                where_it_is += ":" + std::to_string(line_of_offset(text, at));
            }
        }
        throw InputError(where_it_is + ": malformed JSON: " + printable(message, 120));
    } catch (const json::exception& e) {
        throw InputError(origin + ": malformed JSON: " + printable(e.what(), 120));
    } catch (const InputError& e) {
        throw InputError(origin + ": " + e.what());
    }
    if (!root.is_object()) throw InputError(origin + ": a scene file must be a JSON object {\"key\": value, ...}");

    Params params = base;
    for (const auto& [key, value] : root.items()) {
        const ParamInfo* info = find_param(key);
        if (!info) {
            std::string message = where(origin, text, key) + ": unknown key '" + printable(key) + "'";
            if (auto hint = closest_key(key); !hint.empty()) message += " (did you mean '" + std::string(hint) + "'?)";
            throw InputError(message);
        }
        try {
            set_param(params, key, value_text(*info, value));
        } catch (const InputError& e) {
            throw InputError(where(origin, text, key) + ": " + e.what());
        }
    }
    if (root.contains("mesh") && !params.mesh.empty() && fs::path(params.mesh).is_relative()) {
        const fs::path folder = fs::path(origin).parent_path();
        if (!folder.empty()) params.mesh = (folder / params.mesh).lexically_normal().string();
    }
    return params;
}

Params load_scene(const std::string& path, const Params& base) {
    return parse_scene(read_text_file(path, kMaxSceneBytes, "scene file"), path, base);
}

std::string scene_to_json(const Params& params) {
    json root = json::object();
    for (const auto& info : param_table()) {
        if (info.type == ParamType::String && param_text(params, info.key).empty()) continue;
        root[std::string(info.key)] = value_json(params, info);
    }
    // nlohmann's objects keep keys sorted, which keeps saved files stable and diffable.
    try {
        return root.dump(2) + "\n";
    } catch (const json::type_error&) {
        // JSON text is UTF-8; a path in another encoding cannot be written into it faithfully.
        throw InputError("parameter 'mesh': the path '" + printable(params.mesh) +
                         "' is not valid UTF-8, which a scene file cannot hold; rename the mesh file");
    }
}

void save_scene(const std::string& path, const Params& params, Overwrite overwrite) {
    const fs::path target(path);
    fs::path folder = target.parent_path();
    if (folder.empty()) folder = ".";
    std::error_code ec;
    if (fs::is_directory(target, ec)) throw InputError(path + ": is a folder; choose a file name");
    if (overwrite == Overwrite::No && fs::exists(fs::symlink_status(target, ec))) {
        throw InputError(path + ": already exists; not overwriting it");
    }

    // Store the mesh path relative to the scene's folder, so a folder of presets can move.
    Params saved = params;
    if (!saved.mesh.empty()) {
        const fs::path mesh = fs::absolute(saved.mesh, ec);
        const fs::path relative = fs::proximate(mesh, fs::absolute(folder, ec), ec);
        if (!ec && !relative.empty()) saved.mesh = relative.string();
    }
    const std::string text = scene_to_json(saved);  // before anything touches the disk

    // A replaced file keeps its permissions; a new one is readable by all, writable by its owner.
    mode_t mode = 0644;
    if (struct stat old {}; ::stat(path.c_str(), &old) == 0 && S_ISREG(old.st_mode)) mode = old.st_mode & 07777;

    // The temporary file sits beside the target (a rename cannot cross file systems), hidden,
    // named after it (cut short, so that a long name still leaves room for the suffix).
    std::string temp_name(".");
    temp_name.append(target.filename().string().substr(0, 200)).append(".XXXXXX");
    std::string temp = (folder / temp_name).string();
    const int fd = ::mkstemp(temp.data());
    if (fd < 0) io_error(path, "cannot create a temporary file beside it");
    auto fail = [&](const char* what) {
        const int saved_errno = errno;
        ::close(fd);
        ::unlink(temp.c_str());
        errno = saved_errno;
        io_error(path, what);
    };
    // A short write (a full disk, a file size limit) ends in an error, never in a shorter file.
    std::size_t written = 0;
    while (written < text.size()) {
        const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
        if (n < 0) {
            if (errno == EINTR) continue;
            fail("cannot write");
        }
        written += static_cast<std::size_t>(n);
    }
    if (::fchmod(fd, mode) != 0) fail("cannot set permissions");
    if (::fsync(fd) != 0) fail("cannot flush to disk");
    if (::close(fd) != 0) {
        const int saved_errno = errno;
        ::unlink(temp.c_str());
        errno = saved_errno;
        io_error(path, "cannot close");
    }
    if (overwrite == Overwrite::No) {
        // link() refuses to replace an existing name: no window for a race to clobber a file.
        if (::link(temp.c_str(), path.c_str()) != 0) {
            const int saved_errno = errno;
            ::unlink(temp.c_str());
            errno = saved_errno;
            if (errno == EEXIST) throw InputError(path + ": already exists; not overwriting it");
            io_error(path, "cannot save");
        }
        ::unlink(temp.c_str());
    } else if (::rename(temp.c_str(), path.c_str()) != 0) {
        const int saved_errno = errno;
        ::unlink(temp.c_str());
        errno = saved_errno;
        io_error(path, "cannot save");
    }
    // Make the new name itself durable (best effort: the file is in place either way).
    if (const int dir = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); dir >= 0) {
        ::fsync(dir);
        ::close(dir);
    }
}

}  // namespace softbody

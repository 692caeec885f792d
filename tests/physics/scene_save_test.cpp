// Nothing lost: saving a preset writes a temporary file beside the target and renames it into
// place, never replaces a file unless asked (Overwrite::Yes), and when a write fails (a folder
// it may not write in, a full disk, a file size limit) the old file is left exactly as it was
// and no temporary file is left behind.
//
// The failures are real, and each is made in a child process so it ends with it: a read-only
// folder (as root, the child saves as the unprivileged user, since root writes anywhere), a file
// size limit (RLIMIT_FSIZE, with SIGXFSZ ignored, so a write past it fails with EFBIG as on a
// full disk) and, where this system lets a process have a mount namespace of its own, a
// genuinely full 8 KiB tmpfs.
#include <sched.h>
#include <sys/mount.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "physics/error.h"
#include "physics/scene_io.h"
#include "test_support.h"

namespace softbody::test {
namespace {

namespace fs = std::filesystem;

constexpr char kOldScene[] = "{\n  \"stiffness\": 1.0\n}\n";

// Every name in the folder, sorted: temporary files would show here.
std::vector<std::string> names_in(const fs::path& folder) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(folder)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

Scene new_params() {
    Scene scene;
    SoftBodyDef body;
    body.name = "body";
    body.mesh = "cube:2";
    body.stiffness = 20.0f;
    body.pinned = {1, 2, 3};
    scene.soft_bodies.push_back(body);
    scene.settings.dt = 0.01f;
    return scene;
}

// In a child: saves and returns 0 when it fails with InputError naming the file and `reason`,
// 1 when it succeeds, 2 for a message without them, 3 for another exception.
int save_expecting_failure(const std::string& path, Overwrite overwrite, const char* reason) {
    try {
        save_scene(path, new_params(), overwrite);
        return 1;
    } catch (const InputError& e) {
        const std::string message = e.what();
        std::fprintf(stderr, "save_scene said: %s\n", message.c_str());
        return refusal_fault(message, {path.c_str(), reason}).empty() ? 0 : 2;
    } catch (...) {
        return 3;
    }
}

TEST(SaveScene, NeverReplacesAFileUnlessAsked) {
    TempDir dir;
    const std::string path = dir.write("scene.json", kOldScene);
    EXPECT_THROW(save_scene(path, new_params(), Overwrite::No), InputError);
    EXPECT_EQ(read_text(path), kOldScene);
    // Not even a link to nowhere: the name is taken.
    fs::create_symlink(dir.file("nowhere.json"), dir.file("link.json"));
    EXPECT_THROW(save_scene(dir.file("link.json"), new_params(), Overwrite::No), InputError);
    EXPECT_FALSE(fs::exists(dir.file("nowhere.json")));
    EXPECT_EQ(names_in(dir.path()), (std::vector<std::string>{"link.json", "scene.json"}));
    // Asked: replaced, and loads back.
    save_scene(path, new_params(), Overwrite::Yes);
    EXPECT_EQ(load_scene(path), new_params());
    EXPECT_EQ(names_in(dir.path()), (std::vector<std::string>{"link.json", "scene.json"}));
}

TEST(SaveScene, ReplacedFileKeepsItsPermissions) {
    TempDir dir;
    const std::string path = dir.write("private.json", kOldScene);
    fs::permissions(path, fs::perms::owner_read | fs::perms::owner_write);
    save_scene(path, new_params(), Overwrite::Yes);
    EXPECT_EQ(fs::status(path).permissions() & fs::perms::all, fs::perms::owner_read | fs::perms::owner_write);
    const std::string fresh = dir.file("fresh.json");
    save_scene(fresh, new_params(), Overwrite::No);
    EXPECT_EQ(fs::status(fresh).permissions() & fs::perms::all,
              fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read | fs::perms::others_read);
}

// The longest name a folder allows still saves: the temporary file's name is cut to fit.
TEST(SaveScene, LongestFileNameSaves) {
    TempDir dir;
    const std::string name = std::string(250, 'n') + ".json";  // 255 bytes: NAME_MAX
    save_scene(dir.file(name), new_params(), Overwrite::No);
    EXPECT_EQ(load_scene(dir.file(name)), new_params());
    EXPECT_EQ(names_in(dir.path()), std::vector<std::string>{name});
}

// A folder the saving user may read but not write in (mode 555). Root may write anywhere, so as
// root the save runs as the unprivileged user instead (as_unprivileged_user).
TEST(SaveScene, ReadOnlyFolderLeavesTheOldFile) {
    TempDir dir;
    const fs::path folder = dir.path() / "presets";
    fs::create_directory(folder);
    const std::string path = (folder / "scene.json").string();
    {
        std::ofstream(path) << kOldScene;
    }
    fs::permissions(folder, fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                                fs::perms::group_exec | fs::perms::others_read | fs::perms::others_exec);
    const int code = as_unprivileged_user([&] {
        if (::access(folder.c_str(), W_OK) == 0) return 77;  // CAP_DAC_OVERRIDE without being root
        if (const int replace = save_expecting_failure(path, Overwrite::Yes, "Permission denied"); replace != 0) {
            return 20 + replace;
        }
        return 30 + save_expecting_failure((folder / "fresh.json").string(), Overwrite::No, "Permission denied");
    });
    fs::permissions(folder, fs::perms::owner_all);
    if (code == 77) GTEST_SKIP() << "this process may write in a read-only folder and cannot give that up";
    EXPECT_EQ(code, 30) << "20+n: replacing, 30+n: a new file; n = 1 saved, 2 wrong message, 3 other exception";
    EXPECT_EQ(read_text(path), kOldScene);
    EXPECT_EQ(names_in(folder), std::vector<std::string>{"scene.json"});
}

// A file size limit of 64 bytes: the new scene (several hundred bytes) cannot be written. The
// save fails with the system's reason, the old file is intact, and nothing else is left.
TEST(SaveScene, FileSizeLimitLeavesTheOldFile) {
    TempDir dir;
    const std::string path = dir.write("scene.json", kOldScene);
    const std::string fresh = dir.file("fresh.json");
    const int code = in_child([&] {
        std::signal(SIGXFSZ, SIG_IGN);
        const rlimit limit{64, 64};
        if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) return 10;
        if (const int replace = save_expecting_failure(path, Overwrite::Yes, "File too large"); replace != 0) {
            return 20 + replace;
        }
        return 30 + save_expecting_failure(fresh, Overwrite::No, "File too large");
    });
    EXPECT_EQ(code, 30) << "20+n: replacing, 30+n: a new file; n = 1 saved, 2 wrong message, 3 other exception";
    EXPECT_EQ(read_text(path), kOldScene);
    EXPECT_EQ(names_in(dir.path()), std::vector<std::string>{"scene.json"});
    // Without the limit the same save works.
    save_scene(path, new_params(), Overwrite::Yes);
    EXPECT_EQ(load_scene(path), new_params());
}

// A mount namespace of this (child) process's own: directly when privileged, else inside a user
// namespace where this user is root (mapped, so files it creates have an owner).
bool own_mount_namespace() {
    if (::unshare(CLONE_NEWNS) == 0) return true;
    const uid_t uid = ::getuid();
    const gid_t gid = ::getgid();
    if (::unshare(CLONE_NEWUSER | CLONE_NEWNS) != 0) return false;
    auto write_file = [](const char* file, const std::string& text) {
        std::ofstream out(file);
        out << text;
        out.close();
        return static_cast<bool>(out);
    };
    write_file("/proc/self/setgroups", "deny");
    return write_file("/proc/self/uid_map", "0 " + std::to_string(uid) + " 1\n") &&
           write_file("/proc/self/gid_map", "0 " + std::to_string(gid) + " 1\n");
}

// A full disk, for real: an 8 KiB tmpfs filled to the last page, in a mount namespace of the
// child's own. Skipped where the system allows no such namespace.
TEST(SaveScene, FullDiskLeavesTheOldFile) {
    TempDir dir;
    const fs::path mount_point = dir.path() / "tiny";
    fs::create_directory(mount_point);
    const std::string path = (mount_point / "scene.json").string();
    const int code = in_child([&] {
        if (!own_mount_namespace()) return 77;
        if (::mount(nullptr, "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0) return 77;
        if (::mount("tmpfs", mount_point.c_str(), "tmpfs", 0, "size=8k") != 0) return 77;
        {
            std::ofstream(path) << kOldScene;
        }
        // Fill every page that is left.
        {
            std::ofstream filler(mount_point / "filler", std::ios::binary);
            const std::string block(512, 'x');
            for (int i = 0; i < 64 && filler; ++i) filler.write(block.data(), block.size()), filler.flush();
        }
        if (const int full = save_expecting_failure(path, Overwrite::Yes, "No space left"); full != 0) return 20 + full;
        if (read_text(path) != kOldScene) return 30;
        if (names_in(mount_point) != std::vector<std::string>{"filler", "scene.json"}) return 31;
        // Room again: the same save works.
        fs::remove(mount_point / "filler");
        save_scene(path, new_params(), Overwrite::Yes);
        if (load_scene(path) != new_params()) return 40;
        if (names_in(mount_point) != std::vector<std::string>{"scene.json"}) return 41;
        return 0;
    });
    if (code == 77) GTEST_SKIP() << "no mount namespace here (unshare or mount refused): cannot make a full tmpfs";
    EXPECT_EQ(code, 0) << "2x: the save on the full disk (21 saved, 22 wrong message, 23 other exception); "
                          "30/31: old file changed or a temporary file left; 4x: the save with room";
}

}  // namespace
}  // namespace softbody::test

#include "physics/file_output.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "physics/error.h"

namespace softbody {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void io_error(const std::string& path, const std::string& what) {
    throw InputError(path + ": " + what + " (" + std::strerror(errno) + ")");
}

}  // namespace

void write_text_file(const std::string& path, const std::string& text, Overwrite overwrite) {
    const fs::path target(path);
    fs::path folder = target.parent_path();
    if (folder.empty()) folder = ".";
    std::error_code ec;
    if (fs::is_directory(target, ec)) throw InputError(path + ": is a folder; choose a file name");
    if (overwrite == Overwrite::No && fs::exists(fs::symlink_status(target, ec))) {
        throw InputError(path + ": already exists; not overwriting it");
    }

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
        if (::link(temp.c_str(), path.c_str()) == 0) {
            ::unlink(temp.c_str());
        } else {
            int saved_errno = errno;
            // A file system without hard links (the browser's, FAT, some network ones): the name
            // is checked free, then taken by rename (a writer racing for it in between could be
            // replaced: that window exists only there).
            if (saved_errno == EMLINK || saved_errno == EPERM || saved_errno == ENOSYS || saved_errno == EOPNOTSUPP) {
                if (fs::exists(fs::symlink_status(target, ec))) saved_errno = EEXIST;
                else saved_errno = ::rename(temp.c_str(), path.c_str()) == 0 ? 0 : errno;
            }
            if (saved_errno != 0) {
                ::unlink(temp.c_str());
                errno = saved_errno;
                if (errno == EEXIST) throw InputError(path + ": already exists; not overwriting it");
                io_error(path, "cannot save");
            }
        }
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

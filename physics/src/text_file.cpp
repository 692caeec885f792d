#include "text_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "physics/error.h"

namespace softbody {

namespace {

class Descriptor {
public:
    explicit Descriptor(int fd) : fd_(fd) {}
    ~Descriptor() {
        if (fd_ >= 0) ::close(fd_);
    }
    Descriptor(const Descriptor&) = delete;
    Descriptor& operator=(const Descriptor&) = delete;
    int get() const { return fd_; }

private:
    int fd_;
};

// Every refusal here is about the file as a file (FileError), never about what it says.
[[noreturn]] void refuse(const std::string& path, const std::string& what, int error_number = 0) {
    throw FileError(path + ": " + what, error_number);
}

std::string reason(int error) { return std::string(" (") + std::strerror(error) + ")"; }

}  // namespace

std::string read_text_file(const std::string& path, std::size_t max_bytes, std::string_view what) {
    const std::string kind(what);
    // O_NONBLOCK: opening a FIFO with no writer would otherwise wait forever. It is cleared
    // again once the descriptor is known to be a regular file.
    const Descriptor fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC));
    if (fd.get() < 0) {
        const int error = errno;
        if (error == EISDIR) refuse(path, "is a folder, not a " + kind, error);
        refuse(path, "cannot open " + kind + reason(error), error);
    }
    // Decided on the open descriptor, not the name: the file cannot be swapped in between.
    struct stat info {};
    if (::fstat(fd.get(), &info) != 0) refuse(path, "cannot read " + kind + reason(errno), errno);
    if (S_ISDIR(info.st_mode)) refuse(path, "is a folder, not a " + kind);
    if (!S_ISREG(info.st_mode)) refuse(path, "is not a regular file (a pipe, socket or device), not a " + kind);
    if (info.st_size < 0 || static_cast<unsigned long long>(info.st_size) > max_bytes) {
        refuse(path, "too large for a " + kind + " (" + std::to_string(info.st_size) + " bytes; at most " +
                         std::to_string(max_bytes) + ")");
    }
    const int flags = ::fcntl(fd.get(), F_GETFL);
    if (flags < 0 || ::fcntl(fd.get(), F_SETFL, flags & ~O_NONBLOCK) != 0) {
        refuse(path, "cannot read " + kind + reason(errno), errno);
    }

    // The size is a hint, not a promise: the file may grow or shrink while it is read.
    std::string text;
    text.reserve(static_cast<std::size_t>(info.st_size));
    char buffer[1 << 16];
    for (;;) {
        const ssize_t n = ::read(fd.get(), buffer, sizeof buffer);
        if (n < 0) {
            if (errno == EINTR) continue;
            refuse(path, "cannot read " + kind + reason(errno), errno);
        }
        if (n == 0) break;
        text.append(buffer, static_cast<std::size_t>(n));
        if (text.size() > max_bytes) {
            refuse(path, "too large for a " + kind + " (more than " + std::to_string(max_bytes) + " bytes)");
        }
    }
    return text;
}

}  // namespace softbody

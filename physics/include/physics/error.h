// Errors the user can fix: a bad file, a bad parameter. Each carries one line of text that
// names the culprit (the key, or the file and line), ready to print as it is.
#pragma once

#include <stdexcept>
#include <string>

namespace softbody {

class InputError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// A file the user named that cannot be read at all (missing, a folder, unreadable, too large),
// as opposed to one that reads but says something wrong. `error_number` is the system's errno
// when there was one (ENOENT for a missing file), else 0. The Python module raises OSError for it.
class FileError : public InputError {
public:
    FileError(const std::string& line, int error_number) : InputError(line), error_number_(error_number) {}
    int error_number() const { return error_number_; }

private:
    int error_number_;
};

// The same error with `prefix` before its line ("soft body 'jelly': "), of the same kind.
[[noreturn]] inline void rethrow_within(const std::string& prefix, const InputError& error) {
    if (const auto* file = dynamic_cast<const FileError*>(&error)) throw FileError(prefix + file->what(), file->error_number());
    throw InputError(prefix + error.what());
}

}  // namespace softbody

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

}  // namespace softbody

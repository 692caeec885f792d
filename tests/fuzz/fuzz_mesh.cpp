// libFuzzer target: see fuzz_inputs.h (mesh_input) and README.md in this folder.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_inputs.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    softbody::fuzz::mesh_input(std::string_view(reinterpret_cast<const char*>(data), size));
    return 0;
}

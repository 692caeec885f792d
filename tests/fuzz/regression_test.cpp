// Every seed of the fuzz targets (corpus/<target>/) and every input that ever broke a parser
// (regressions/<target>/), replayed through the fuzz targets' own entry points in an ordinary
// build: each must give a result or an InputError, never a crash, a sanitizer's report,
// another exception or a broken promise. This is how a fixed crash stays fixed.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz_inputs.h"

namespace softbody::fuzz {
namespace {

namespace fs = std::filesystem;

std::size_t replay(const std::string& target, void (*entry)(std::string_view)) {
    std::size_t replayed = 0;
    for (const char* kind : {"corpus", "regressions"}) {
        const fs::path folder = fs::path(SOFTBODY_FUZZ_DIR) / kind / target;
        if (!fs::is_directory(folder)) continue;
        std::vector<fs::path> files;
        for (const auto& entry_in_folder : fs::directory_iterator(folder)) {
            if (entry_in_folder.is_regular_file()) files.push_back(entry_in_folder.path());
        }
        std::sort(files.begin(), files.end());
        for (const fs::path& file : files) {
            std::ifstream in(file, std::ios::binary);
            const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
            try {
                entry(bytes);
            } catch (const std::exception& e) {
                ADD_FAILURE() << file.string() << ": " << e.what();
            }
            ++replayed;
        }
    }
    return replayed;
}

TEST(FuzzRegressions, MeshInputs) { EXPECT_GT(replay("fuzz_mesh", mesh_input), 0u); }
TEST(FuzzRegressions, SceneInputs) { EXPECT_GT(replay("fuzz_scene", scene_input), 0u); }
TEST(FuzzRegressions, SetInputs) { EXPECT_GT(replay("fuzz_set", set_input), 0u); }

}  // namespace
}  // namespace softbody::fuzz

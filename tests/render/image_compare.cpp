// Compares a rendered screenshot with its reference, for the screenshot tests.
//
//   softbody_image_compare ACTUAL EXPECTED --name CASE --failures DIR [--expect-different]
//                          [--pixel-threshold N] [--max-fraction F] [--max-mean M]
//
// Prints one line with the measures and the thresholds. Exit 0 when the outcome is the
// expected one (a match, or with --expect-different a mismatch), 1 otherwise, 2 for bad input.
// When a match was expected and not found, writes CASE_actual.png, CASE_expected.png and
// CASE_diff.png to DIR and names them.
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>
#include <string_view>

#include "render/image.h"

namespace {

using softbody::render::CompareThresholds;

double number(std::string_view option, const char* text) {
    char* end = nullptr;
    const double value = std::strtod(text, &end);
    if (!end || *end != '\0' || !(value >= 0.0)) {
        throw std::runtime_error(std::string(option) + ": expected a number >= 0, got '" + text + "'");
    }
    return value;
}

int run(int argc, char** argv) {
    std::string actual_path, expected_path, name = "screenshot", failures = "failures";
    bool expect_different = false;
    CompareThresholds thresholds;
    for (int i = 1; i < argc; ++i) {
        const std::string_view arg = argv[i];
        auto value = [&]() -> const char* {
            if (i + 1 >= argc) throw std::runtime_error(std::string(arg) + " needs a value");
            return argv[++i];
        };
        if (arg == "--name") name = value();
        else if (arg == "--failures") failures = value();
        else if (arg == "--expect-different") expect_different = true;
        else if (arg == "--pixel-threshold") thresholds.pixel_threshold = static_cast<int>(number(arg, value()));
        else if (arg == "--max-fraction") thresholds.max_differing_fraction = number(arg, value());
        else if (arg == "--max-mean") thresholds.max_mean_difference = number(arg, value());
        else if (!arg.starts_with("--") && actual_path.empty()) actual_path = arg;
        else if (!arg.starts_with("--") && expected_path.empty()) expected_path = arg;
        else throw std::runtime_error("unknown argument '" + std::string(arg) + "'");
    }
    if (actual_path.empty() || expected_path.empty()) throw std::runtime_error("usage: softbody_image_compare ACTUAL EXPECTED [options]");

    const auto actual = softbody::render::read_png(actual_path);
    if (!std::filesystem::exists(expected_path)) {
        std::cout << name << ": FAIL, no reference image " << expected_path
                  << " (render one on purpose: see tests/render/README.md)\n";
        return 1;
    }
    const auto expected = softbody::render::read_png(expected_path);
    const auto d = softbody::render::compare_images(actual, expected, thresholds);
    const bool match = softbody::render::images_match(d, thresholds);

    char line[400];
    if (!d.same_size) {
        std::snprintf(line, sizeof line, "size %dx%d, reference %dx%d", actual.width, actual.height, expected.width,
                      expected.height);
    } else {
        std::snprintf(line, sizeof line,
                      "max %d, mean %.4f (limit %.4f), pixels over %d: %lld = %.4f%% (limit %.4f%%)", d.max_difference,
                      d.mean_difference, thresholds.max_mean_difference, thresholds.pixel_threshold,
                      static_cast<long long>(d.differing_pixels), 100.0 * d.differing_fraction,
                      100.0 * thresholds.max_differing_fraction);
    }
    const bool ok = match != expect_different;
    std::cout << name << ": " << (ok ? "ok" : "FAIL") << ", "
              << (expect_different ? (match ? "the altered image MATCHED the reference" : "the altered image differs as it should")
                                   : (match ? "matches" : "differs from the reference"))
              << " (" << line << ")\n";
    if (!ok && !expect_different) {
        std::filesystem::create_directories(failures);
        const std::filesystem::path dir(failures);
        const std::string a = (dir / (name + "_actual.png")).string();
        const std::string e = (dir / (name + "_expected.png")).string();
        const std::string f = (dir / (name + "_diff.png")).string();
        softbody::render::write_png(a, actual);
        softbody::render::write_png(e, expected);
        softbody::render::write_png(f, softbody::render::difference_image(actual, expected, thresholds));
        std::cout << "  actual:   " << a << "\n  expected: " << e << "\n  diff:     " << f << "\n";
    }
    if (!ok && expect_different) {
        std::cout << "  the thresholds are too loose to notice this fault\n";
    }
    return ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception& e) {
        std::cerr << "softbody_image_compare: " << e.what() << "\n";
        return 2;
    }
}

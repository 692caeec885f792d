// RGBA images with 8 bits a channel, rows from the top: PNG files in and out, and the
// comparison the screenshot tests use. No GL here.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace softbody::render {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba;  // width * height * 4, top row first

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgba(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4, 0) {}
    std::uint8_t* pixel(int x, int y) { return &rgba[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 4]; }
    const std::uint8_t* pixel(int x, int y) const {
        return &rgba[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 4];
    }
};

// Writes a PNG (RGB when every pixel is opaque, else RGBA). The same image always gives the
// same bytes. Throws std::runtime_error naming the file when it cannot be written.
void write_png(const std::string& path, const Image& image);

// Reads a PNG (any channel count, returned as RGBA). Throws std::runtime_error naming the file.
Image read_png(const std::string& path);

// How far apart two images are, channel by channel on 0..255 (alpha ignored).
struct ImageDifference {
    bool same_size = true;
    int max_difference = 0;          // largest |a - b| over every pixel and colour channel
    double mean_difference = 0.0;    // mean |a - b| over every pixel and colour channel
    double differing_fraction = 0.0; // pixels whose largest channel difference exceeds the threshold
    std::int64_t differing_pixels = 0;
};

// When two renderings count as the same picture. A pixel "differs" when one of its channels
// is off by more than pixel_threshold; the images match while at most max_differing_fraction
// of the pixels differ and the mean difference stays within max_mean_difference.
//
// Measured for the screenshot cases at 320x240 (tests/render/README.md has the table):
// llvmpipe with its SIMD extensions off (another CPU's rounding) gives a mean of at most 0.008
// and at most 0.003% differing pixels; the faults the negative tests make give at least 0.43%
// (a body 1 cm off) or a mean of at least 0.43 (a body colour 5 levels off).
struct CompareThresholds {
    int pixel_threshold = 16;
    double max_differing_fraction = 0.001;  // 0.1%
    double max_mean_difference = 0.2;
};

ImageDifference compare_images(const Image& actual, const Image& expected, const CompareThresholds& thresholds);
bool images_match(const ImageDifference& difference, const CompareThresholds& thresholds);

// A picture of where two images differ: the expected image faded to grey, with pixels over the
// threshold in red and smaller differences in yellow, brighter for larger ones.
Image difference_image(const Image& actual, const Image& expected, const CompareThresholds& thresholds);

}  // namespace softbody::render

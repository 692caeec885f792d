#include "render/image.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#ifdef SOFTBODY_HAVE_ZLIB
#include <zlib.h>

namespace {
// PNG's deflate stream through zlib when the build has it: files about a quarter smaller than
// the writer's own compressor gives. zlib's default level: its best one is three times slower
// at 800x600 for 7% less. Either way, the same image always gives the same bytes.
unsigned char* deflate_zlib(unsigned char* data, int length, int* out_length, int /*quality*/) {
    uLongf size = compressBound(static_cast<uLong>(length));
    auto* out = static_cast<unsigned char*>(std::malloc(size));
    if (!out) return nullptr;
    if (compress2(out, &size, data, static_cast<uLong>(length), Z_DEFAULT_COMPRESSION) != Z_OK) {
        std::free(out);
        return nullptr;
    }
    *out_length = static_cast<int>(size);
    return out;
}
}  // namespace

#define STBIW_ZLIB_COMPRESS deflate_zlib
#endif
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wcast-align"
#pragma GCC diagnostic ignored "-Wduplicated-branches"
#endif
#include <stb_image.h>
#include <stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace softbody::render {

void write_png(const std::string& path, const Image& image) {
    if (image.width <= 0 || image.height <= 0) throw std::runtime_error(path + ": cannot write an empty image");
    bool opaque = true;
    for (std::size_t i = 3; i < image.rgba.size() && opaque; i += 4) opaque = image.rgba[i] == 255;
    const int channels = opaque ? 3 : 4;
    std::vector<std::uint8_t> data;
    if (opaque) {
        data.reserve(image.rgba.size() / 4 * 3);
        for (std::size_t i = 0; i < image.rgba.size(); i += 4) data.insert(data.end(), &image.rgba[i], &image.rgba[i] + 3);
    }
    const void* pixels = opaque ? static_cast<const void*>(data.data()) : static_cast<const void*>(image.rgba.data());
    if (!stbi_write_png(path.c_str(), image.width, image.height, channels, pixels, image.width * channels)) {
        throw std::runtime_error(path + ": cannot write the PNG file");
    }
}

Image read_png(const std::string& path) {
    int w = 0, h = 0, channels = 0;
    stbi_uc* data = stbi_load(path.c_str(), &w, &h, &channels, 4);
    if (!data) {
        const char* reason = stbi_failure_reason();
        throw std::runtime_error(path + ": cannot read the PNG file (" + (reason ? reason : "unknown reason") + ")");
    }
    Image image(w, h);
    std::copy(data, data + image.rgba.size(), image.rgba.begin());
    stbi_image_free(data);
    return image;
}

ImageDifference compare_images(const Image& actual, const Image& expected, const CompareThresholds& thresholds) {
    ImageDifference d;
    if (actual.width != expected.width || actual.height != expected.height) {
        d.same_size = false;
        d.max_difference = 255;
        d.mean_difference = 255.0;
        d.differing_fraction = 1.0;
        return d;
    }
    std::int64_t sum = 0;
    const std::size_t pixels = actual.rgba.size() / 4;
    for (std::size_t p = 0; p < pixels; ++p) {
        int largest = 0;
        for (std::size_t c = 0; c < 3; ++c) {
            const int diff = std::abs(int(actual.rgba[p * 4 + c]) - int(expected.rgba[p * 4 + c]));
            largest = std::max(largest, diff);
            sum += diff;
        }
        d.max_difference = std::max(d.max_difference, largest);
        if (largest > thresholds.pixel_threshold) ++d.differing_pixels;
    }
    if (pixels > 0) {
        d.mean_difference = double(sum) / double(pixels * 3);
        d.differing_fraction = double(d.differing_pixels) / double(pixels);
    }
    return d;
}

bool images_match(const ImageDifference& difference, const CompareThresholds& thresholds) {
    return difference.same_size && difference.differing_fraction <= thresholds.max_differing_fraction &&
           difference.mean_difference <= thresholds.max_mean_difference;
}

Image difference_image(const Image& actual, const Image& expected, const CompareThresholds& thresholds) {
    if (actual.width != expected.width || actual.height != expected.height) return actual;
    Image out(actual.width, actual.height);
    for (std::size_t i = 0; i < out.rgba.size(); i += 4) {
        int largest = 0, grey = 0;
        for (std::size_t c = 0; c < 3; ++c) {
            largest = std::max(largest, std::abs(int(actual.rgba[i + c]) - int(expected.rgba[i + c])));
            grey += expected.rgba[i + c];
        }
        grey = 160 + grey / 3 / 5;  // faded expected image, for orientation
        std::uint8_t* o = &out.rgba[i];
        if (largest > thresholds.pixel_threshold) {
            o[0] = 255, o[1] = 0, o[2] = 0;
        } else if (largest > 0) {
            const int v = std::min(255, 120 + largest * 135 / std::max(1, thresholds.pixel_threshold));
            o[0] = static_cast<std::uint8_t>(v), o[1] = static_cast<std::uint8_t>(v * 3 / 4), o[2] = 0;
        } else {
            o[0] = o[1] = o[2] = static_cast<std::uint8_t>(std::min(grey, 255));
        }
        o[3] = 255;
    }
    return out;
}

}  // namespace softbody::render

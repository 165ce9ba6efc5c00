#include "core/png_write.h"

#include "core/image.h"

#include <algorithm>
#include <csetjmp>
#include <vector>

// libpng stays inside this file (DESIGN.md, "Heavy dependencies behind a .cpp").
#include <png.h>

namespace velvet {
namespace {

/// OpenImageIO's float to unsigned conversion (scaled_conversion): scale, round half away from
/// zero, clamp, truncate; so a PNG written here has the samples the image codec wrote.
template <typename T>
T quantize(float v, float scale) {
    float s = v * scale;
    s += s < 0.0f ? -0.5f : 0.5f;
    return T(std::clamp(s, 0.0f, scale)); // NaN: never reaches here (renders check finiteness)
}

struct Sink {
    std::string* bytes;
};

void writeBytes(png_structp png, png_bytep data, png_size_t size) {
    auto* sink = static_cast<Sink*>(png_get_io_ptr(png));
    sink->bytes->append(reinterpret_cast<const char*>(data), size);
}
void flushNothing(png_structp) {}

struct ErrorText {
    std::string text;
};
void onError(png_structp png, png_const_charp message) {
    static_cast<ErrorText*>(png_get_error_ptr(png))->text = message ? message : "libpng error";
    png_longjmp(png, 1);
}
void onWarning(png_structp, png_const_charp) {}

} // namespace

bool encodePng(const Image& image, bool sixteenBit, std::string& bytes, std::string* error) {
    static const int kColorType[4] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA,
                                      PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGB_ALPHA};
    if (image.empty() || image.channels < 1 || image.channels > 4) {
        if (error)
            *error = "nothing to encode as PNG";
        return false;
    }
    // Every row converted before libpng starts: no C++ object lives across its longjmp.
    const size_t rowSamples = size_t(image.width) * size_t(image.channels);
    const size_t rowBytes = rowSamples * (sixteenBit ? 2u : 1u);
    std::vector<png_byte> data(rowBytes * size_t(image.height));
    for (size_t i = 0, n = image.pixels.size(); i < n; ++i) {
        if (sixteenBit) { // PNG stores 16-bit samples big-endian (PNG spec, section 7.1)
            const auto v = quantize<std::uint16_t>(image.pixels[i], 65535.0f);
            data[2 * i] = png_byte(v >> 8);
            data[2 * i + 1] = png_byte(v & 0xff);
        } else {
            data[i] = quantize<png_byte>(image.pixels[i], 255.0f);
        }
    }
    std::vector<png_bytep> rows(size_t(image.height));
    for (int y = 0; y < image.height; ++y)
        rows[size_t(y)] = data.data() + size_t(y) * rowBytes;

    ErrorText errorText;
    std::string out;
    Sink sink{&out};
    png_structp png =
        png_create_write_struct(PNG_LIBPNG_VER_STRING, &errorText, onError, onWarning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!png || !info) {
        png_destroy_write_struct(&png, nullptr);
        if (error)
            *error = "libpng: out of memory";
        return false;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        if (error)
            *error = "libpng: " + errorText.text;
        return false;
    }
    png_set_write_fn(png, &sink, writeBytes, flushNothing);
    png_set_compression_level(png, kPngCompressionLevel);
    png_set_IHDR(png, info, png_uint_32(image.width), png_uint_32(image.height),
                 sixteenBit ? 16 : 8, kColorType[image.channels - 1], PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    png_write_image(png, rows.data());
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    bytes = std::move(out);
    return true;
}

} // namespace velvet

#pragma once
/// @file image.h
/// Images in memory (float RGBA, row 0 at the top) and their file I/O, through OpenImageIO.

#include <cstdint>
#include <filesystem>
#include <glm/vec4.hpp>
#include <string>
#include <vector>

namespace velvet {

struct Image {
    int width = 0;
    int height = 0;
    int channels = 4;          ///< 1 to 4
    std::vector<float> pixels; ///< width * height * channels, row-major, top row first

    Image() = default;
    Image(int w, int h, int c)
        : width(w), height(h), channels(c), pixels(size_t(w) * h * c, 0.0f) {}
    bool empty() const { return width == 0 || height == 0; }
    float* at(int x, int y) { return pixels.data() + (size_t(y) * width + x) * channels; }
    const float* at(int x, int y) const {
        return pixels.data() + (size_t(y) * width + x) * channels;
    }
    /// The pixel as RGBA (grey -> RRR, missing alpha -> 1).
    glm::vec4 rgba(int x, int y) const;
};

/// Limits checked against a file's header before any pixel is decoded.
struct ImageReadLimits {
    int maxSide = 16384;
    std::uint64_t maxDecodedBytes = std::uint64_t(1) << 30; ///< as float RGBA
};

/// Sample type written to a file.
enum class PixelFormat { UInt8, UInt16, Half, Float };

/// Reads any format OpenImageIO knows into float pixels (8-bit values map to [0, 1], no colour
/// conversion). Returns false and a message naming the file and the problem.
bool readImage(const std::filesystem::path& file, Image& out, std::string* error,
               const ImageReadLimits& limits = {});
/// Writes @p image as is (no colour conversion); the format is chosen by extension. Atomic.
bool writeImage(const std::filesystem::path& file, const Image& image, PixelFormat format,
                std::string* error);

} // namespace velvet

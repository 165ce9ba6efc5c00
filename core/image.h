#pragma once
/// @file image.h
/// Images in memory (float RGBA, row 0 at the top) and their file I/O, through OpenImageIO.

#include <cstdint>
#include <filesystem>
#include <glm/vec4.hpp>
#include <string>
#include <string_view>
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

/// @name Image decode limits
/// Built in: 16384 pixels a side and 1 GiB decoded (as float RGBA). The environment variables
/// VELVET_MAX_IMAGE_SIDE (pixels, 1 to 1048576) and VELVET_MAX_IMAGE_BYTES (bytes, with an
/// optional K, M or G suffix meaning KiB, MiB, GiB; 1 KiB to 1 TiB) replace them for every read
/// that does not pass limits of its own. They are read once, on first use
/// (configuredImageReadLimits). Here a bad value leaves that variable's built-in limit in effect
/// and is described by imageLimitsProblem(); the velvet application (app/main.cpp) checks that
/// at startup and exits with code 2 and the message, so it never runs with a limit the user did
/// not mean. docs/file-formats.md.
/// @{
inline constexpr int kDefaultMaxImageSide = 16384;
inline constexpr std::uint64_t kDefaultMaxImageBytes = std::uint64_t(1) << 30;
struct ImageReadLimits;
/// The limits in effect: the environment's where set and valid, else the built-in ones.
const ImageReadLimits& configuredImageReadLimits();
/// "" when both variables are unset or valid; otherwise one line per bad variable naming it,
/// the value and what is expected.
std::string imageLimitsProblem();
/// Parses the two variables' values (null: unset) into @p out, starting from the built-in
/// limits. False + message (naming the variable) when a value is not valid; @p out then keeps
/// the built-in value for that variable.
bool parseImageLimits(const char* maxSide, const char* maxBytes, ImageReadLimits& out,
                      std::string* error);
/// @}

/// Limits checked against a file's header before any pixel is decoded.
struct ImageReadLimits {
    int maxSide = configuredImageReadLimits().maxSide;
    std::uint64_t maxDecodedBytes = configuredImageReadLimits().maxDecodedBytes; ///< float RGBA
};

/// Sample type written to a file.
enum class PixelFormat { UInt8, UInt16, Half, Float };

/// What a file's header says, read without decoding any pixel (readImageInfo()).
struct ImageInfo {
    std::string format;       ///< OpenImageIO's format name: "png", "openexr", "tiff", ...
    int width = 0;            ///< as stored (before orientation)
    int height = 0;           ///< as stored (before orientation)
    int channels = 0;         ///< channels in the file (readImage() keeps at most the first 4)
    int bitsPerSample = 0;    ///< 8, 16, 32, ... (RGBE .hdr reports 32: it decodes to float)
    bool isFloat = false;     ///< half or float samples
    int orientation = 1;      ///< EXIF/TIFF Orientation, 1 to 8 (1: as stored)
    int displayWidth() const; ///< width after orientation (5 to 8 swap the axes)
    int displayHeight() const;
};

/// Reads a file's header only: format, size, channels, sample type and orientation, checked
/// against @p limits (the same checks readImage() makes before decoding). Returns false and a
/// message naming the file and the problem (missing, empty, unknown format, too large).
bool readImageInfo(const std::filesystem::path& file, ImageInfo& out, std::string* error,
                   const ImageReadLimits& limits = {});

/// Reads any format OpenImageIO knows (PNG, JPEG, TIFF, OpenEXR, Radiance HDR, TGA, BMP, ...)
/// into float pixels: integer samples map to [0, 1], float samples are kept, no colour
/// conversion, straight (unassociated) alpha where the format stores it so. The first of several
/// subimages is read, and at most its first four channels. The EXIF/TIFF Orientation is applied
/// (ImageBufAlgo::reorient), so row 0 is the top of the image as it is meant to be displayed.
/// The header is checked against @p limits before any pixel is decoded. On failure returns
/// false and sets @p error to one line that starts with the file name and says what is wrong.
bool readImage(const std::filesystem::path& file, Image& out, std::string* error,
               const ImageReadLimits& limits = {});

/// Reads an 8-bit file straight into 8-bit RGBA (@p rgba, width * height * 4 bytes, row 0 at
/// the top), without a float copy: grey becomes RRR, grey + alpha RRRA, a missing alpha 255 (as
/// Image::rgba() reads them). For the GPU's 8-bit texture path (core/mip_texture.h), where a
/// 4096² map must not pass through 256 MB of float. Refuses (false + message naming the file)
/// what it cannot read exactly as readImage() would: a file whose samples are not 8-bit or that
/// carries an EXIF orientation other than 1 (the caller falls back to readImage()); the same
/// header limits are checked first. @p info receives the header.
bool readImage8(const std::filesystem::path& file, std::vector<std::uint8_t>& rgba, ImageInfo& info,
                std::string* error, const ImageReadLimits& limits = {});

/// Options of writeImage().
struct ImageWriteOptions {
    /// EXIF/TIFF Orientation (1 to 8) to record; the pixels are written as given. Honoured by
    /// the formats that store it (TIFF, JPEG, OpenEXR); others ignore it.
    int orientation = 1;
    int jpegQuality = 95; ///< 1 to 100
};

/// Writes @p image as is (no colour conversion); the format is chosen by the extension. Where
/// the format cannot hold what is asked, the nearest it can is written: PNG 8 or 16 bit; JPEG,
/// BMP and TGA 8 bit; Radiance HDR float RGB (grey becomes RRR, alpha is dropped); JPEG has no
/// alpha (dropped); BMP has no grey + alpha (written RRRA). Atomic: a temp file beside the
/// target, then a rename. Returns false and a message naming the file on failure.
bool writeImage(const std::filesystem::path& file, const Image& image, PixelFormat format,
                std::string* error, const ImageWriteOptions& options = {});

/// Encodes @p image in memory as writeImage() would write a file with @p extension (".png",
/// ".jpg", ".tga", ".tif", ".exr": the formats whose OpenImageIO writer streams to memory), for
/// containers that embed images (GLB). Returns false and a message on failure.
bool encodeImage(const Image& image, std::string_view extension, PixelFormat format,
                 std::string& bytes, std::string* error, const ImageWriteOptions& options = {});

} // namespace velvet

#pragma once
/// @file image_codec.h
/// Core-internal: the image library (OpenImageIO) behind a table of functions, loaded on first
/// use. Debian's OpenImageIO 2.4 maps about 260 shared libraries (OpenCV, FFmpeg, GDCM, LibRaw,
/// OpenVDB, ...); linked into the executable, the dynamic loader spent 0.25 s of every start on
/// them before main (BENCHMARKS.md, "Whole-process velvet render"), even for runs that read and
/// write no image through it. So core/image.cpp, image_ops.cpp and mip_cache.cpp keep their
/// policy (limits, channel layouts, atomic writes, cache keys) and call the few functions that
/// need OpenImageIO through this table, which lives in a module (core/codec/, the MODULE
/// library velvet-image-codec.so) opened with dlopen the first time an image is read, resized or
/// written in a format Velvet does not write itself (PNG is written with libpng: core/png_write.h).
///
/// Where the module is looked for, in order: $VELVET_IMAGE_CODEC (a file), the folder
/// kCodecInstallDir relative to the executable's folder (bin/../lib/velvet in an install, and
/// build/bin/../lib/velvet in the build tree). Builds configured with VELVET_IMAGE_CODEC_MODULE
/// OFF (the fuzz and sanitizer builds) link the same code into velvet_core instead.
///
/// Every function takes and returns the standard library's types: the module is built by the
/// same compiler from the same tree, and kImageCodecAbi (checked at load) changes with the table.

#include "core/image.h"
#include "core/mip_texture.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace velvet::codec {

/// Bumped whenever ImageCodec or a type it passes changes.
inline constexpr int kImageCodecAbi = 2;

struct ImageCodec {
    int abi = kImageCodecAbi;
    /// OpenImageIO's version as loaded ("2.4.7").
    const char* (*libraryVersion)();
    /// readImageInfo(), readImage(), readImage8() (core/image.h): header checks and decoding.
    bool (*readInfo)(const std::filesystem::path&, ImageInfo&, std::string*,
                     const ImageReadLimits&);
    bool (*read)(const std::filesystem::path&, Image&, std::string*, const ImageReadLimits&);
    bool (*read8)(const std::filesystem::path&, std::vector<std::uint8_t>&, ImageInfo&,
                  std::string*, const ImageReadLimits&);
    /// True when the writer for @p extension (lower case, with the dot) can encode to memory.
    bool (*encodesToMemory)(std::string_view extension);
    /// encodeImage() (core/image.h); the caller has checked the image.
    bool (*encode)(const Image&, std::string_view extension, PixelFormat, std::string& bytes,
                   std::string*, const ImageWriteOptions&);
    /// Writes @p image to the file @p path in the format of @p extension (for writers that
    /// cannot encode to memory; the caller names a temporary and renames it).
    bool (*writeFile)(const std::filesystem::path& path, std::string_view extension, const Image&,
                      PixelFormat, std::string*, const ImageWriteOptions&);
    /// ImageBufAlgo::resize of @p in into @p out (already sized) with the named filter.
    bool (*resize)(const Image& in, Image& out, const char* filter, std::string*);
    /// A tiled MIP-mapped TIFF as maketx writes it (core/mip_cache.h): writes @p levels (RGBA,
    /// half or 8-bit samples) with @p description as its ImageDescription to @p path.
    bool (*writeMipFile)(const std::filesystem::path& path, const std::string& description,
                         bool half, bool srgb, const std::vector<MipLevel>& levels, std::string*);
    /// Reads such a file: its ImageDescription, whether level 0 holds half samples (else
    /// 8-bit; anything else fails), and every MIP level as RGBA in that type; the levels finer
    /// than @p firstLevel get their size but no bytes (read later with readMipRows). False + why.
    bool (*readMipFile)(const std::filesystem::path& path, std::string& description, bool& half,
                        std::vector<MipLevel>& levels, int firstLevel, std::string*);
    /// Rows @p y0 .. @p y0 + @p rows of MIP level @p level of such a file into @p out (tightly
    /// packed RGBA, half samples when @p half, else 8-bit; @p width * @p rows pixels). @p y0
    /// is a multiple of the tile height (64) and the band ends on one or at the level's last
    /// row; a level of another width or type fails. False + why.
    bool (*readMipRows)(const std::filesystem::path& path, int level, int width, int y0, int rows,
                        bool half, std::uint8_t* out, std::string*);
};

/// The codec, loaded on first use (thread-safe); null + a message naming the places searched
/// and the loader's reason when the module cannot be loaded. The message is also returned by
/// later calls.
const ImageCodec* imageCodec(std::string* error);

/// True once the codec has been loaded in this process (tests: a render from the environment
/// cache writing a PNG must not load it).
bool imageCodecLoaded();

} // namespace velvet::codec

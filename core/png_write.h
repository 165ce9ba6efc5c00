#pragma once
/// @file png_write.h
/// PNG encoding through libpng, for core/image.h's writeImage() and encodeImage(): libpng is
/// loaded with the GUI libraries the velvet executable links anyway, so writing a PNG does not
/// load the image codec module (core/image_codec.h) and its ~260 libraries.

#include <string>

namespace velvet {

struct Image;

/// zlib level of the PNGs Velvet writes (1 = fastest). BENCHMARKS.md, "Whole-process velvet
/// render": level 6 (zlib's and OpenImageIO's default) spent about 90 ms on a 1280x720 frame
/// for files 10 % smaller.
inline constexpr int kPngCompressionLevel = 1;

/// Encodes @p image (1 to 4 channels: grey, grey + alpha, RGB, RGBA; straight alpha) as an 8-bit
/// or, with @p sixteenBit, a 16-bit PNG into @p bytes. Samples are clamped to [0, 1] and rounded
/// to nearest (as OpenImageIO converts). False + message on failure.
bool encodePng(const Image& image, bool sixteenBit, std::string& bytes, std::string* error);

} // namespace velvet

#pragma once
/// @file frame_pattern.h
/// Numbered output paths for image sequences ("out/%03d.png"), in the printf form ffmpeg's image2
/// muxer and demuxer read, so the same pattern names the frames and feeds the video encoder.

#include <optional>
#include <string>

namespace velvet {

/// One integer conversion in the file name: `%d`, `%Nd` or `%0Nd` (N at most 9: zero-padded or
/// space-padded to N digits); `%%` is a literal percent sign.
struct FramePattern {
    std::string text;   ///< the pattern as given (what ffmpeg's `-i` reads)
    std::string prefix; ///< before the conversion, `%%` already turned into `%`
    std::string suffix; ///< after it
    int width = 0;      ///< minimum digits (0: as many as needed)
    bool zeroPad = false;
};

/// Parses @p text. nullopt + @p why when it has no conversion, more than one, a conversion other
/// than the three forms (`%s`, `%x`, `%-3d`, a lone `%`), or the conversion is in a folder name
/// rather than the file name (every frame must land in one folder, the one checked before
/// rendering).
std::optional<FramePattern> parseFramePattern(const std::string& text, std::string* why);

/// The path of frame @p frame (0-based), as printf would write it.
std::string framePath(const FramePattern& pattern, int frame);

/// Whether @p text holds a `%` at all (a still's output with one is refused: it would be written
/// under a name the user did not mean).
bool looksLikeFramePattern(const std::string& text);

} // namespace velvet

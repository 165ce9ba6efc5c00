#include "core/frame_pattern.h"

#include <cstdio>
#include <filesystem>

namespace velvet {

std::optional<FramePattern> parseFramePattern(const std::string& text, std::string* why) {
    auto fail = [&](const std::string& message) -> std::optional<FramePattern> {
        if (why)
            *why = "'" + text + "': " + message;
        return std::nullopt;
    };
    FramePattern p;
    p.text = text;
    bool seen = false;
    size_t conversionAt = 0;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c != '%') {
            (seen ? p.suffix : p.prefix) += c;
            continue;
        }
        if (i + 1 < text.size() && text[i + 1] == '%') {
            (seen ? p.suffix : p.prefix) += '%';
            ++i;
            continue;
        }
        // %d, %Nd, %0Nd: what ffmpeg's image2 (av_get_frame_filename) reads as the frame number.
        size_t j = i + 1;
        bool zero = false;
        if (j < text.size() && text[j] == '0') {
            zero = true;
            ++j;
        }
        int width = 0;
        int digits = 0;
        while (j < text.size() && text[j] >= '0' && text[j] <= '9') {
            width = width * 10 + (text[j] - '0');
            ++j;
            ++digits;
        }
        if (j >= text.size() || text[j] != 'd' || digits > 1 || (zero && digits == 0))
            return fail("the frame number must be written %d, %Nd or %0Nd (N from 1 to 9), "
                        "and a literal percent sign as %%");
        if (seen)
            return fail("more than one frame-number conversion; write a literal percent sign as "
                        "%%");
        seen = true;
        conversionAt = i;
        p.width = width;
        p.zeroPad = zero;
        i = j;
    }
    if (!seen)
        return fail("no frame number in the name; a turntable writes one file per frame, e.g. "
                    "out/%03d.png");
    if (text.find('/', conversionAt) != std::string::npos)
        return fail("the frame number must be in the file name, not in a folder name (every "
                    "frame is written into one folder)");
    return p;
}

std::string framePath(const FramePattern& pattern, int frame) {
    char digits[32];
    std::snprintf(digits, sizeof digits, pattern.zeroPad ? "%0*d" : "%*d", pattern.width, frame);
    return pattern.prefix + digits + pattern.suffix;
}

bool looksLikeFramePattern(const std::string& text) {
    return text.find('%') != std::string::npos;
}

} // namespace velvet

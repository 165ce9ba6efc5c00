// Image decode limits from the environment (core/image.h): read in this one place.
#include "core/image.h"

#include <cctype>
#include <charconv>
#include <cstdlib>

namespace velvet {
namespace {

/// OIIO sizes are ints; a side beyond 2^20 is far past any texture a GPU takes (16384 on most).
constexpr std::uint64_t kMaxSideLimit = std::uint64_t(1) << 20;
constexpr std::uint64_t kMinBytes = std::uint64_t(1) << 10;
constexpr std::uint64_t kMaxBytes = std::uint64_t(1) << 40;

/// A whole number with an optional binary suffix (K, M, G; case-insensitive, optional "iB"/"B").
bool parseAmount(std::string_view text, bool allowSuffix, std::uint64_t& out) {
    std::uint64_t value = 0;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || ptr == text.data())
        return false;
    std::string suffix(ptr, text.data() + text.size());
    for (char& c : suffix)
        c = char(std::toupper(static_cast<unsigned char>(c)));
    int shift = 0;
    if (suffix.empty())
        shift = 0;
    else if (!allowSuffix)
        return false;
    else if (suffix == "K" || suffix == "KB" || suffix == "KIB")
        shift = 10;
    else if (suffix == "M" || suffix == "MB" || suffix == "MIB")
        shift = 20;
    else if (suffix == "G" || suffix == "GB" || suffix == "GIB")
        shift = 30;
    else
        return false;
    if (value > (kMaxBytes >> shift))
        return false;
    out = value << shift;
    return true;
}

struct Configured {
    ImageReadLimits limits;
    std::string problem;
};

const Configured& configured() {
    static const Configured c = [] {
        // Aggregate initialisation with every member given: the default member initialisers
        // (which call configuredImageReadLimits) do not run.
        Configured out{ImageReadLimits{kDefaultMaxImageSide, kDefaultMaxImageBytes}, {}};
        parseImageLimits(std::getenv("VELVET_MAX_IMAGE_SIDE"),
                         std::getenv("VELVET_MAX_IMAGE_BYTES"), out.limits, &out.problem);
        return out;
    }();
    return c;
}

} // namespace

bool parseImageLimits(const char* maxSide, const char* maxBytes, ImageReadLimits& out,
                      std::string* error) {
    out.maxSide = kDefaultMaxImageSide;
    out.maxDecodedBytes = kDefaultMaxImageBytes;
    std::string problems;
    const auto bad = [&](const std::string& line) {
        problems += (problems.empty() ? "" : "\n") + line;
    };
    if (maxSide && *maxSide) {
        std::uint64_t v = 0;
        if (parseAmount(maxSide, false, v) && v >= 1 && v <= kMaxSideLimit)
            out.maxSide = int(v);
        else
            bad("VELVET_MAX_IMAGE_SIDE: expected a whole number of pixels from 1 to " +
                std::to_string(kMaxSideLimit) + ", got \"" + maxSide + "\"");
    }
    if (maxBytes && *maxBytes) {
        std::uint64_t v = 0;
        if (parseAmount(maxBytes, true, v) && v >= kMinBytes && v <= kMaxBytes)
            out.maxDecodedBytes = v;
        else
            bad(std::string("VELVET_MAX_IMAGE_BYTES: expected a byte count from 1K to 1024G "
                            "(suffixes K, M, G: KiB, MiB, GiB), got \"") +
                maxBytes + "\"");
    }
    if (!problems.empty() && error)
        *error = problems;
    return problems.empty();
}

const ImageReadLimits& configuredImageReadLimits() {
    return configured().limits;
}

std::string imageLimitsProblem() {
    return configured().problem;
}

} // namespace velvet

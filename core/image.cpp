#include "core/image.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <system_error>

// OpenImageIO stays inside this file (DESIGN.md, "Heavy dependencies behind a .cpp").
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

namespace velvet {
namespace {

bool fail(std::string* error, const std::filesystem::path& file, const std::string& what) {
    if (error)
        *error = file.string() + ": " + what;
    return false;
}

/// OpenImageIO reports problems through per-object and global error queues; take whichever has
/// text, trimmed to one line.
std::string oiioMessage(std::string msg) {
    if (msg.empty())
        msg = OIIO::geterror();
    while (!msg.empty() && std::isspace(static_cast<unsigned char>(msg.back())))
        msg.pop_back();
    std::replace(msg.begin(), msg.end(), '\n', ' ');
    return msg.empty() ? std::string("unknown OpenImageIO error") : msg;
}

OIIO::TypeDesc toTypeDesc(PixelFormat format) {
    switch (format) {
    case PixelFormat::UInt8:
        return OIIO::TypeDesc::UINT8;
    case PixelFormat::UInt16:
        return OIIO::TypeDesc::UINT16;
    case PixelFormat::Half:
        return OIIO::TypeDesc::HALF;
    case PixelFormat::Float:
        return OIIO::TypeDesc::FLOAT;
    }
    return OIIO::TypeDesc::FLOAT;
}

std::string lowerExtension(const std::filesystem::path& file) {
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

} // namespace

glm::vec4 Image::rgba(int x, int y) const {
    const float* p = at(x, y);
    switch (channels) {
    case 1:
        return {p[0], p[0], p[0], 1.0f};
    case 2: // grey + alpha
        return {p[0], p[0], p[0], p[1]};
    case 3:
        return {p[0], p[1], p[2], 1.0f};
    default:
        return {p[0], p[1], p[2], p[3]};
    }
}

bool readImage(const std::filesystem::path& file, Image& out, std::string* error,
               const ImageReadLimits& limits) {
    std::error_code ec;
    if (!std::filesystem::exists(file, ec))
        return fail(error, file, "no such file");
    if (std::filesystem::is_directory(file, ec))
        return fail(error, file, "is a folder, not an image");

    // Opening reads the header only; every limit is checked before a pixel is decoded.
    // Straight (unassociated) alpha in memory: no premultiplication behind the caller's back.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(file.string(), &config);
    if (!in)
        return fail(error, file, "cannot read as an image: " + oiioMessage({}));
    const OIIO::ImageSpec spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
        return fail(error, file, "the header declares an empty image");
    if (spec.depth > 1)
        return fail(error, file, "volume images are not supported");
    if (spec.width > limits.maxSide || spec.height > limits.maxSide)
        return fail(error, file,
                    "image is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                        ", larger than the limit of " + std::to_string(limits.maxSide) +
                        " pixels a side");
    const std::uint64_t decodedBytes =
        std::uint64_t(spec.width) * std::uint64_t(spec.height) * 4u * sizeof(float);
    if (decodedBytes > limits.maxDecodedBytes)
        return fail(error, file,
                    "image would need " + std::to_string(decodedBytes >> 20) +
                        " MiB decoded, more than the limit of " +
                        std::to_string(limits.maxDecodedBytes >> 20) + " MiB");

    const int channels = std::min(spec.nchannels, 4);
    Image img(spec.width, spec.height, channels);
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, img.pixels.data()))
        return fail(error, file,
                    "cannot decode pixels (truncated or corrupt?): " + oiioMessage(in->geterror()));
    in->close();

    // EXIF orientation (1 = as stored): turn the pixels so row 0 is the top as displayed.
    const int orientation = spec.get_int_attribute("Orientation", 1);
    if (orientation > 1 && orientation <= 8) {
        OIIO::ImageSpec bufSpec(spec.width, spec.height, channels, OIIO::TypeDesc::FLOAT);
        bufSpec.attribute("Orientation", orientation);
        OIIO::ImageBuf src(bufSpec, img.pixels.data());
        OIIO::ImageBuf turned = OIIO::ImageBufAlgo::reorient(src);
        if (turned.has_error())
            return fail(error, file, "cannot apply orientation: " + oiioMessage(turned.geterror()));
        const OIIO::ImageSpec& ts = turned.spec();
        Image t(ts.width, ts.height, channels);
        turned.get_pixels(OIIO::ROI(0, ts.width, 0, ts.height, 0, 1, 0, channels),
                          OIIO::TypeDesc::FLOAT, t.pixels.data());
        img = std::move(t);
    }
    out = std::move(img);
    return true;
}

bool writeImage(const std::filesystem::path& file, const Image& image, PixelFormat format,
                std::string* error) {
    if (image.empty() || image.channels < 1 || image.channels > 4 ||
        image.pixels.size() != size_t(image.width) * image.height * image.channels)
        return fail(error, file, "nothing to write (empty or inconsistent image)");

    const std::string ext = lowerExtension(file);
    auto out = OIIO::ImageOutput::create(file.string());
    if (!out)
        return fail(error, file, "no image writer for extension '" + ext + "'");

    OIIO::TypeDesc type = toTypeDesc(format);
    // Formats with fixed sample types: keep the request where the writer supports it.
    if (ext == ".png" && format != PixelFormat::UInt16)
        type = OIIO::TypeDesc::UINT8;
    else if ((ext == ".jpg" || ext == ".jpeg" || ext == ".bmp") && format != PixelFormat::UInt8)
        type = OIIO::TypeDesc::UINT8;
    else if (ext == ".hdr")
        type = OIIO::TypeDesc::FLOAT;

    int channels = image.channels;
    if ((ext == ".jpg" || ext == ".jpeg" || ext == ".hdr") && channels == 4)
        channels = 3; // these formats have no alpha
    OIIO::ImageSpec spec(image.width, image.height, channels, type);
    if (ext == ".exr")
        spec.attribute("compression", "zip");
    spec.attribute("oiio:UnassociatedAlpha", 1); // our pixels carry straight alpha

    // Temp file beside the target (same file system, so the rename is atomic), same extension so
    // the writer is chosen the same way.
    static std::atomic<unsigned> counter{0};
    const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
    std::filesystem::path tmp = file;
    std::string tmpName(1, '.'); // appended piecewise: GCC 12 warns falsely on "." + string
    tmpName += file.stem().string();
    tmpName += ".tmp" + std::to_string(stamp) + "-" + std::to_string(counter++);
    tmpName += file.extension().string();
    tmp.replace_filename(tmpName);

    auto cleanup = [&] {
        std::error_code ec;
        std::filesystem::remove(tmp, ec);
    };
    if (!out->open(tmp.string(), spec))
        return cleanup(),
               fail(error, file, "cannot open for writing: " + oiioMessage(out->geterror()));
    const OIIO::stride_t xstride = OIIO::stride_t(image.channels) * sizeof(float);
    bool ok = out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data(), xstride);
    const std::string writeError = ok ? std::string() : oiioMessage(out->geterror());
    ok = out->close() && ok;
    if (!ok)
        return cleanup(), fail(error, file,
                               "cannot write: " + (writeError.empty() ? oiioMessage(out->geterror())
                                                                      : writeError));

    std::error_code ec;
    std::filesystem::rename(tmp, file, ec);
    if (ec)
        return cleanup(), fail(error, file, "cannot replace the file: " + ec.message());
    return true;
}

} // namespace velvet

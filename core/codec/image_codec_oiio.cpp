// The OpenImageIO side of core/image_codec.h: built as the module velvet-image-codec.so (or into
// velvet_core where VELVET_IMAGE_CODEC_MODULE is OFF). Self-contained: it links OpenImageIO and
// nothing of velvet_core (a module cannot take the executable's symbols), so what it needs of
// core's types is in their headers.
#include "core/image_codec.h"
#include "core/mip_cache.h"

#include <algorithm>
#include <cctype>
#include <memory>

// OpenImageIO stays inside this file (DESIGN.md, "Heavy dependencies behind a .cpp").
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

namespace velvet::codec {
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

/// "1536 MiB", or KiB below one MiB (small limits still give a useful message).
std::string formatBytes(std::uint64_t bytes) {
    return bytes >= (std::uint64_t(1) << 20) ? std::to_string(bytes >> 20) + " MiB"
                                             : std::to_string((bytes + 1023) >> 10) + " KiB";
}

/// Opens @p file, reading its header only, and checks it against @p limits. Every limit is
/// checked here, before a pixel is decoded (DESIGN.md, "Data safety").
std::unique_ptr<OIIO::ImageInput> openChecked(const std::filesystem::path& file,
                                              const ImageReadLimits& limits, ImageInfo& info,
                                              std::string* error) {
    std::error_code ec;
    const auto status = std::filesystem::status(file, ec);
    if (!std::filesystem::exists(status))
        return fail(error, file, "no such file"), nullptr;
    if (std::filesystem::is_directory(status))
        return fail(error, file, "is a folder, not an image"), nullptr;
    const auto bytes = std::filesystem::file_size(file, ec);
    if (!ec && bytes == 0)
        return fail(error, file, "the file is empty (0 bytes)"), nullptr;

    // Straight (unassociated) alpha in memory: no premultiplication behind the caller's back.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(file.string(), &config);
    if (!in) // OIIO tries the extension's reader first, then every reader on the content
        return fail(error, file,
                    "not a readable image: unknown format, or a damaged or truncated header "
                    "(OpenImageIO: " +
                        oiioMessage({}) + ")"),
               nullptr;
    const OIIO::ImageSpec& spec = in->spec();
    info.format = in->format_name();
    info.width = spec.width;
    info.height = spec.height;
    info.channels = spec.nchannels;
    info.bitsPerSample = int(spec.format.size() * 8);
    info.isFloat = spec.format.is_floating_point();
    info.orientation = spec.get_int_attribute("Orientation", 1);
    if (info.orientation < 1 || info.orientation > 8)
        info.orientation = 1; // out of range: ignored, as EXIF readers do

    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
        return fail(error, file, "the header declares an empty image"), nullptr;
    if (spec.depth > 1)
        return fail(error, file, "volume images are not supported"), nullptr;
    if (spec.width > limits.maxSide || spec.height > limits.maxSide)
        return fail(error, file,
                    "image is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                        ", larger than the limit of " + std::to_string(limits.maxSide) +
                        " pixels a side (VELVET_MAX_IMAGE_SIDE raises it)"),
               nullptr;
    const std::uint64_t decodedBytes =
        std::uint64_t(spec.width) * std::uint64_t(spec.height) * 4u * sizeof(float);
    if (decodedBytes > limits.maxDecodedBytes)
        return fail(error, file,
                    "image is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                        " and would need " + formatBytes(decodedBytes) +
                        " decoded, more than the limit of " + formatBytes(limits.maxDecodedBytes) +
                        " (VELVET_MAX_IMAGE_BYTES raises it)"),
               nullptr;
    return in;
}

const char* libraryVersion() {
    static const std::string text = [] {
        const int v = OIIO::openimageio_version(); // 20407 = 2.4.7
        return std::to_string(v / 10000) + "." + std::to_string(v / 100 % 100) + "." +
               std::to_string(v % 100);
    }();
    return text.c_str();
}

bool readInfo(const std::filesystem::path& file, ImageInfo& out, std::string* error,
              const ImageReadLimits& limits) {
    ImageInfo info;
    auto in = openChecked(file, limits, info, error);
    if (!in)
        return false;
    in->close();
    out = std::move(info);
    return true;
}

bool read(const std::filesystem::path& file, Image& out, std::string* error,
          const ImageReadLimits& limits) {
    ImageInfo info;
    auto in = openChecked(file, limits, info, error);
    if (!in)
        return false;

    const int channels = std::min(info.channels, 4);
    Image img(info.width, info.height, channels);
    // Some readers (libtiff strips, libjpeg's "premature end of file") fill what is missing and
    // still report success, with the problem queued as an error: that is a failure too.
    const bool ok = in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, img.pixels.data());
    if (!ok || in->has_error())
        return fail(error, file,
                    "the pixel data is truncated or corrupt (OpenImageIO: " +
                        oiioMessage(in->geterror()) + ")");
    in->close();

    // EXIF orientation (TIFF 6.0 tag 274; 1 = as stored): turn the pixels so row 0 is the top as
    // displayed. ImageBufAlgo::reorient reads the "Orientation" attribute of its source, but in
    // OpenImageIO before 3.1 it swaps 5 and 7 (OIIO issue #4661, fixed by PR #5350), so those
    // two are done here from their TIFF 6.0 definitions: 5 is the transpose (stored row 0 is the
    // left column), 7 the transverse (stored row 0 is the right column, read upwards).
    if (info.orientation > 1) {
        OIIO::ImageSpec bufSpec(info.width, info.height, channels, OIIO::TypeDesc::FLOAT);
        bufSpec.attribute("Orientation", info.orientation);
        OIIO::ImageBuf src(bufSpec, img.pixels.data());
        OIIO::ImageBuf turned;
        if (info.orientation == 5)
            turned = OIIO::ImageBufAlgo::transpose(src);
        else if (info.orientation == 7)
            turned = OIIO::ImageBufAlgo::rotate180(OIIO::ImageBufAlgo::transpose(src));
        else
            turned = OIIO::ImageBufAlgo::reorient(src);
        if (turned.has_error())
            return fail(error, file,
                        "cannot apply orientation " + std::to_string(info.orientation) + ": " +
                            oiioMessage(turned.geterror()));
        const OIIO::ImageSpec& ts = turned.spec();
        Image t(ts.width, ts.height, channels);
        // reorient may leave a display window offset: read the whole data window.
        turned.get_pixels(
            OIIO::ROI(ts.x, ts.x + ts.width, ts.y, ts.y + ts.height, 0, 1, 0, channels),
            OIIO::TypeDesc::FLOAT, t.pixels.data());
        img = std::move(t);
    }
    out = std::move(img);
    return true;
}

bool read8(const std::filesystem::path& file, std::vector<std::uint8_t>& rgba, ImageInfo& info,
           std::string* error, const ImageReadLimits& limits) {
    auto in = openChecked(file, limits, info, error);
    if (!in)
        return false;
    if (info.bitsPerSample != 8 || info.isFloat)
        return fail(error, file, "not 8-bit samples");
    if (info.orientation != 1)
        return fail(error, file, "has an EXIF orientation");
    const int channels = std::min(info.channels, 4);
    const size_t pixels = size_t(info.width) * size_t(info.height);
    rgba.assign(pixels * 4, 255);
    // The file's channels land in the first ones of each RGBA pixel (xstride 4 bytes); grey and
    // grey + alpha are spread below.
    const bool ok = in->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, rgba.data(), 4);
    if (!ok || in->has_error()) {
        rgba = {};
        return fail(error, file,
                    "the pixel data is truncated or corrupt (OpenImageIO: " +
                        oiioMessage(in->geterror()) + ")");
    }
    in->close();
    if (channels <= 2)
        for (size_t i = 0; i < pixels; ++i) {
            std::uint8_t* p = rgba.data() + i * 4;
            const std::uint8_t alpha = channels == 2 ? p[1] : 255;
            p[1] = p[2] = p[0];
            p[3] = alpha;
        }
    return true;
}

/// The pixel at @p i as RGBA, as Image::rgba() reads it (grey -> RRR, missing alpha -> 1).
void rgbaAt(const Image& image, size_t i, float out[4]) {
    const float* p = image.pixels.data() + i * size_t(image.channels);
    switch (image.channels) {
    case 1:
        out[0] = out[1] = out[2] = p[0], out[3] = 1.0f;
        return;
    case 2: // grey + alpha
        out[0] = out[1] = out[2] = p[0], out[3] = p[1];
        return;
    case 3:
        out[0] = p[0], out[1] = p[1], out[2] = p[2], out[3] = 1.0f;
        return;
    default:
        out[0] = p[0], out[1] = p[1], out[2] = p[2], out[3] = p[3];
    }
}

/// @p image with @p channels channels, mapped the way Image::rgba() reads it (grey -> RRR,
/// missing alpha -> 1); 1 channel from grey + alpha keeps the grey.
std::vector<float> remapChannels(const Image& image, int channels) {
    const size_t n = size_t(image.width) * size_t(image.height);
    std::vector<float> out(n * size_t(channels));
    float* o = out.data();
    for (size_t i = 0; i < n; ++i) {
        float p[4];
        rgbaAt(image, i, p);
        for (int c = 0; c < channels; ++c)
            *o++ = p[c];
    }
    return out;
}

/// What writeImage() and encodeImage() hand to an OpenImageIO writer: the spec for the format
/// of @p ext, and the pixels in the channel layout the format can hold.
struct PreparedImage {
    OIIO::ImageSpec spec;
    std::vector<float> remapped;
    const float* pixels = nullptr;
    OIIO::stride_t xstride = 0;
};

void prepareImage(const Image& image, std::string_view ext, PixelFormat format,
                  const ImageWriteOptions& options, PreparedImage& p) {
    OIIO::TypeDesc type = toTypeDesc(format);
    // Formats with fixed sample types: keep the request where the writer supports it.
    const bool jpeg = ext == ".jpg" || ext == ".jpeg";
    if (ext == ".png" && format != PixelFormat::UInt16)
        type = OIIO::TypeDesc::UINT8;
    else if ((jpeg || ext == ".bmp" || ext == ".tga") && format != PixelFormat::UInt8)
        type = OIIO::TypeDesc::UINT8;
    else if (ext == ".hdr")
        type = OIIO::TypeDesc::FLOAT;

    // Channel layouts the format cannot hold become the nearest one it can.
    int channels = image.channels;
    if (ext == ".hdr")
        channels = 3; // RGBE: RGB only (grey -> RRR, alpha dropped)
    else if (jpeg && (channels == 2 || channels == 4))
        channels -= 1; // JPEG has no alpha
    else if (ext == ".bmp" && channels == 2)
        channels = 4; // BMP has no grey + alpha: RRRA
    p.pixels = image.pixels.data();
    p.xstride = OIIO::stride_t(image.channels) * sizeof(float);
    if (channels > image.channels || (channels < image.channels && channels != 3)) {
        p.remapped = remapChannels(image, channels);
        p.pixels = p.remapped.data();
        p.xstride = OIIO::stride_t(channels) * sizeof(float);
    } // else the first `channels` of each pixel are written, through the stride

    p.spec = OIIO::ImageSpec(image.width, image.height, channels, type);
    // Channel names as readers expect them: grey is "Y" (OpenEXR's luminance), alpha "A".
    static const std::vector<std::string> kNames[4] = {
        {"Y"}, {"Y", "A"}, {"R", "G", "B"}, {"R", "G", "B", "A"}};
    p.spec.channelnames = kNames[channels - 1];
    p.spec.alpha_channel = channels == 2 ? 1 : channels == 4 ? 3 : -1;
    if (ext == ".exr")
        p.spec.attribute("compression", "zip");
    if (jpeg)
        p.spec.attribute("CompressionQuality", std::clamp(options.jpegQuality, 1, 100));
    if (options.orientation > 1 && options.orientation <= 8)
        p.spec.attribute("Orientation", options.orientation);
    p.spec.attribute("oiio:UnassociatedAlpha", 1); // our pixels carry straight alpha
}

bool encodesToMemory(std::string_view extension) {
    auto out = OIIO::ImageOutput::create("image" + std::string(extension));
    return out && out->supports("ioproxy");
}

bool encode(const Image& image, std::string_view extension, PixelFormat format, std::string& bytes,
            std::string* error, const ImageWriteOptions& options) {
    const std::filesystem::path name = "image" + std::string(extension);
    auto out = OIIO::ImageOutput::create(name.string());
    if (!out || !out->supports("ioproxy"))
        return fail(error, name,
                    "no in-memory image writer for extension '" + std::string(extension) + "'");
    PreparedImage p;
    prepareImage(image, extension, format, options, p);
    // The writer streams into memory through an IOProxy (OpenImageIO 2.3+), so a container such
    // as GLB can embed the file without a temporary on disk.
    std::vector<unsigned char> buffer;
    OIIO::Filesystem::IOVecOutput proxy(buffer);
    void* proxyPointer = &proxy;
    p.spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxyPointer);
    bool ok = out->open(name.string(), p.spec) &&
              out->write_image(OIIO::TypeDesc::FLOAT, p.pixels, p.xstride);
    ok = out->close() && ok;
    if (!ok)
        return fail(error, name, "cannot encode: " + oiioMessage(out->geterror()));
    bytes.assign(reinterpret_cast<const char*>(buffer.data()), buffer.size());
    return true;
}

bool writeFile(const std::filesystem::path& path, std::string_view extension, const Image& image,
               PixelFormat format, std::string* error, const ImageWriteOptions& options) {
    auto out = OIIO::ImageOutput::create("image" + std::string(extension));
    if (!out) {
        if (error)
            *error = "no image writer for extension '" + std::string(extension) + "'";
        return false;
    }
    PreparedImage prepared;
    prepareImage(image, extension, format, options, prepared);
    if (!out->open(path.string(), prepared.spec)) {
        if (error)
            *error = "cannot open for writing: " + oiioMessage(out->geterror());
        return false;
    }
    bool ok = out->write_image(OIIO::TypeDesc::FLOAT, prepared.pixels, prepared.xstride);
    const std::string writeError = ok ? std::string() : oiioMessage(out->geterror());
    ok = out->close() && ok;
    if (!ok && error)
        *error =
            "cannot write: " + (writeError.empty() ? oiioMessage(out->geterror()) : writeError);
    return ok;
}

bool resize(const Image& image, Image& out, const char* filter, std::string* error) {
    // Wraps the caller's pixels without copying (ImageBuf over application memory).
    OIIO::ImageSpec srcSpec(image.width, image.height, image.channels, OIIO::TypeDesc::FLOAT);
    OIIO::ImageBuf src(srcSpec, const_cast<float*>(image.pixels.data()));
    OIIO::ImageSpec dstSpec(out.width, out.height, out.channels, OIIO::TypeDesc::FLOAT);
    OIIO::ImageBuf dst(dstSpec, out.pixels.data());
    if (OIIO::ImageBufAlgo::resize(dst, src, filter))
        return true;
    if (error)
        *error = "resize: " + dst.geterror();
    return false;
}

bool writeMipFile(const std::filesystem::path& path, const std::string& description, bool half,
                  bool srgb, const std::vector<MipLevel>& levels, std::string* error) {
    auto out = OIIO::ImageOutput::create("tiff");
    if (!out || !out->supports("tiles") ||
        !(out->supports("mipmap") || out->supports("multiimage"))) {
        if (error)
            *error = "OpenImageIO's TIFF writer cannot write tiled MIP-mapped files";
        return false;
    }
    // OpenImageIO's TIFF writer takes the levels as appended subimages, as maketx writes them:
    // with "textureformat" set its reader presents the reduced-resolution directories as MIP
    // levels of subimage 0.
    const auto appendMode = out->supports("mipmap") ? OIIO::ImageOutput::AppendMIPLevel
                                                    : OIIO::ImageOutput::AppendSubimage;
    const OIIO::TypeDesc type = half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::UINT8;
    for (size_t m = 0; m < levels.size(); ++m) {
        const MipLevel& level = levels[m];
        OIIO::ImageSpec spec(level.width, level.height, 4, type);
        // maketx's layout: 64x64 tiles, every level a MIP level of subimage 0.
        spec.tile_width = spec.tile_height = kMipCacheTileSide;
        spec.tile_depth = 1;
        spec.channelnames = {"R", "G", "B", "A"};
        spec.alpha_channel = 3;
        spec.attribute("oiio:UnassociatedAlpha", 1);
        spec.attribute("compression", "none"); // BENCHMARKS.md, "Texture loading"
        spec.attribute("textureformat", "Plain Texture");
        spec.attribute("wrapmodes", "periodic,periodic");
        if (srgb)
            spec.attribute("oiio:ColorSpace", "sRGB");
        spec.attribute("ImageDescription", description);
        const bool opened =
            out->open(path.string(), spec, m == 0 ? OIIO::ImageOutput::Create : appendMode);
        if (!opened || !out->write_image(type, level.bytes.data())) {
            if (error)
                *error = oiioMessage(out->geterror());
            out->close();
            return false;
        }
    }
    if (!out->close()) {
        if (error)
            *error = oiioMessage(out->geterror());
        return false;
    }
    return true;
}

bool readMipFile(const std::filesystem::path& path, std::string& description, bool& half,
                 std::vector<MipLevel>& levels, int firstLevel, std::string* why) {
    auto failed = [&](const std::string& what) {
        if (why)
            *why = what;
        return false;
    };
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1); // stored straight; never premultiplied
    auto in = OIIO::ImageInput::open(path.string(), &config);
    if (!in)
        return failed("not a readable texture file (" + oiioMessage({}) + ")");
    const OIIO::ImageSpec top = in->spec(); // a copy: seek_subimage replaces in->spec()
    description = top.get_string_attribute("ImageDescription");
    if (top.format != OIIO::TypeDesc::HALF && top.format != OIIO::TypeDesc::UINT8)
        return failed("level 0 holds neither half nor 8-bit samples");
    half = top.format == OIIO::TypeDesc::HALF;
    levels.clear();
    for (int m = 0; in->seek_subimage(0, m); ++m) {
        const OIIO::ImageSpec& s = in->spec();
        if (s.nchannels != 4 || s.width < 1 || s.height < 1)
            return failed("mip level " + std::to_string(m) + " is not RGBA");
        MipLevel level;
        level.width = s.width;
        level.height = s.height;
        if (m < firstLevel) { // its size only: the caller reads it in bands (readMipRows)
            levels.push_back(std::move(level));
            continue;
        }
        level.bytes.resize(size_t(s.width) * size_t(s.height) * (half ? 8u : 4u));
        if (!in->read_image(0, m, 0, 4, top.format, level.bytes.data()) || in->has_error())
            return failed("mip level " + std::to_string(m) +
                          " is truncated or corrupt (OpenImageIO: " + oiioMessage(in->geterror()) +
                          ")");
        levels.push_back(std::move(level));
    }
    return true;
}

bool readMipRows(const std::filesystem::path& path, int level, int width, int y0, int rows,
                 bool half, std::uint8_t* out, std::string* why) {
    auto failed = [&](const std::string& what) {
        if (why)
            *why = what;
        return false;
    };
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(path.string(), &config);
    if (!in)
        return failed("not a readable texture file (" + oiioMessage({}) + ")");
    const OIIO::TypeDesc type = half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::UINT8;
    if (in->spec().format != type)
        return failed("level 0 is not of the expected sample type");
    if (!in->seek_subimage(0, level))
        return failed("has no mip level " + std::to_string(level));
    const OIIO::ImageSpec& s = in->spec();
    if (s.nchannels != 4 || s.width != width || y0 < 0 || rows < 1 || y0 + rows > s.height)
        return failed("mip level " + std::to_string(level) + " is not the " +
                      std::to_string(width) + "-pixel-wide RGBA level it was");
    // Whole tiles: read_tiles takes tile-aligned bounds (or the image's edge).
    if (!in->read_tiles(0, level, 0, s.width, y0, y0 + rows, 0, 1, 0, 4, type, out) ||
        in->has_error())
        return failed("mip level " + std::to_string(level) + " rows " + std::to_string(y0) + "-" +
                      std::to_string(y0 + rows - 1) + " are truncated or corrupt (OpenImageIO: " +
                      oiioMessage(in->geterror()) + ")");
    return true;
}

} // namespace

const ImageCodec kOiioCodec = {kImageCodecAbi, libraryVersion,  readInfo,    read,
                               read8,          encodesToMemory, encode,      writeFile,
                               resize,         writeMipFile,    readMipFile, readMipRows};

} // namespace velvet::codec

/// The module's one entry point (dlsym'd by core/image_codec.cpp).
extern "C" __attribute__((visibility("default"))) const velvet::codec::ImageCodec*
velvet_image_codec() {
    return &velvet::codec::kOiioCodec;
}

// The glTF import's files: container, buffers, images. References: the glTF 2.0 specification
// (Khronos, 2021): 3.6.1 buffers, 3.6.1.2 data: URIs, 4.4 GLB, 5.18 images; the PNG
// specification 11.2.2 (colour types). No JSON here: core/gltf_import.cpp hands in descriptors.
#include "core/gltf_asset_files.h"

#include "core/atomic_file.h"
#include "core/import_text.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <unistd.h>

namespace velvet::gltf {

namespace fs = std::filesystem;

namespace {

constexpr std::uintmax_t kMaxFileBytes = std::uintmax_t(2) << 30; // 2 GiB: a .glb, a .bin

std::string extensionForMime(std::string_view mime) {
    if (mime == "image/png")
        return ".png";
    if (mime == "image/jpeg")
        return ".jpg";
    return {};
}

} // namespace

void fail(std::string place, std::string message, ImportProblem::Kind kind) {
    throw Failure{{kind, std::move(place), std::move(message)}};
}

std::string at(const std::string& place, std::string_view key) {
    return place.empty() ? std::string(key) : place + "." + std::string(key);
}
std::string at(const std::string& place, size_t index) {
    return place + "[" + std::to_string(index) + "]";
}

std::string formatValue(float v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", double(v));
    return text;
}

const char* wrapName(int mode) {
    switch (mode) {
    case 33071:
        return "CLAMP_TO_EDGE";
    case 33648:
        return "MIRRORED_REPEAT";
    default:
        return "REPEAT";
    }
}

void setScalar(Material& material, ParamId id, double v, const std::string& place,
               std::vector<std::string>& warnings) {
    const ParamMeta& meta = paramMeta(id);
    const float f = float(v);
    if (f < meta.min || f > meta.max)
        warnings.push_back(place + ": " + formatValue(f) + " is outside Velvet's range of " +
                           std::string(meta.id) + " [" + formatValue(meta.min) + ", " +
                           formatValue(meta.max) + "]; clamped");
    material.setScalar(id, f);
}

void setColor(Material& material, ParamId id, glm::vec3 c, const std::string& place,
              std::vector<std::string>& warnings) {
    const ParamMeta& meta = paramMeta(id);
    for (int i = 0; i < 3; ++i)
        if (c[i] < meta.min || c[i] > meta.max) {
            warnings.push_back(place + ": a component outside Velvet's range of " +
                               std::string(meta.id) + " [" + formatValue(meta.min) + ", " +
                               formatValue(meta.max) + "]; clamped");
            break;
        }
    material.setColor(id, c);
}

AssetFiles::AssetFiles(fs::path file, fs::path imageFolder, std::string imageStem,
                       std::vector<std::string>& warnings)
    : m_file(std::move(file)), m_imageFolder(std::move(imageFolder)), m_stem(std::move(imageStem)),
      m_warnings(&warnings) {}

std::string AssetFiles::load() {
    std::string reason;
    auto bytes = readFileWithLimit(m_file, kMaxFileBytes, &reason);
    if (!bytes)
        fail("", reason);
    if (!isGlb(*bytes))
        return std::move(*bytes);
    GlbChunks chunks;
    std::string place, message;
    if (!splitGlb(*bytes, chunks, place, message))
        fail(place, message);
    m_bin = std::move(chunks.bin);
    m_hasBin = chunks.hasBin;
    return std::move(chunks.json);
}

void AssetFiles::addBuffer(size_t i, BufferDesc buffer) {
    const std::string p = at("buffers", i);
    std::uintmax_t have = 0;
    if (!buffer.uri) {
        if (i != 0 || !m_hasBin)
            fail(p, "has no uri and is not the GLB's binary chunk");
        have = m_bin.size();
    } else if (buffer.uri->rfind("data:", 0) == 0) {
        have = dataUri(*buffer.uri, at(p, "uri")).size();
    } else {
        const fs::path f = resolve(*buffer.uri, at(p, "uri"));
        std::error_code ec;
        if (!fs::is_regular_file(f, ec))
            fail(at(p, "uri"), "missing buffer file " + f.string());
        have = fs::file_size(f, ec);
    }
    if (have < std::uintmax_t(buffer.byteLength))
        fail(p, "holds " + std::to_string(have) + " bytes, byteLength says " +
                    std::to_string(std::uintmax_t(buffer.byteLength)));
    m_buffers.resize(std::max(m_buffers.size(), i + 1));
    m_buffers[i] = std::move(buffer);
}

void AssetFiles::addView(size_t i, ViewDesc view) {
    const double size = double(std::uintmax_t(m_buffers.at(view.buffer).byteLength));
    if (view.byteOffset + view.byteLength > size)
        fail(at("bufferViews", i),
             "bytes " + std::to_string(std::uintmax_t(view.byteOffset)) + " to " +
                 std::to_string(std::uintmax_t(view.byteOffset + view.byteLength)) +
                 " lie outside buffers[" + std::to_string(view.buffer) + "] (" +
                 std::to_string(std::uintmax_t(size)) + " bytes)");
    m_views.resize(std::max(m_views.size(), i + 1));
    m_views[i] = view;
}

std::string AssetFiles::dataUri(const std::string& uri, const std::string& place) const {
    const size_t comma = uri.find(',');
    if (comma == std::string::npos || uri.find(";base64") > comma)
        fail(place, "a data: URI must be base64 (glTF 2.0 section 3.6.1.2)");
    auto bytes = decodeBase64(std::string_view(uri).substr(comma + 1));
    if (!bytes)
        fail(place, "broken base64 in the data: URI");
    return *bytes;
}

fs::path AssetFiles::resolve(const std::string& uri, const std::string& place) {
    // RFC 3986 section 3.1: a scheme is a letter, then letters, digits, '+', '-' or '.', then ':'.
    // (A Windows drive, "C:/", reads as one too, and is refused as the absolute path it is.)
    const size_t colon = uri.find(':');
    const bool hasScheme =
        colon != std::string::npos && colon > 0 && std::isalpha((unsigned char)uri[0]) &&
        std::all_of(uri.begin(), uri.begin() + colon, [](char c) {
            return std::isalnum((unsigned char)c) || c == '+' || c == '-' || c == '.';
        });
    if (hasScheme)
        fail(place, "\"" + uri.substr(0, 64) +
                        "\" is not a relative path: Velvet reads relative paths and data: URIs "
                        "only (glTF 2.0 section 3.6.1)");
    const fs::path relative(percentDecode(uri));
    if (relative.is_absolute() || relative.has_root_path())
        fail(place, "\"" + uri.substr(0, 64) +
                        "\" is an absolute path: glTF URIs are relative to the asset (glTF 2.0 "
                        "section 3.6.1)");
    const fs::path folder = m_file.parent_path().lexically_normal();
    const fs::path f = (folder / relative).lexically_normal();
    const fs::path inside = f.lexically_relative(folder);
    if (inside.empty() || *inside.begin() == "..")
        m_warnings->push_back(place + ": reads " + f.string() + ", outside the asset's folder " +
                              folder.string());
    return f;
}

std::string AssetFiles::bufferBytes(size_t buffer) {
    if (auto it = m_loaded.find(buffer); it != m_loaded.end())
        return it->second;
    const BufferDesc& b = m_buffers.at(buffer);
    std::string bytes;
    if (!b.uri) {
        bytes = m_bin;
    } else if (b.uri->rfind("data:", 0) == 0) {
        bytes = dataUri(*b.uri, at(at("buffers", buffer), "uri"));
    } else {
        std::string reason;
        const fs::path f = (m_file.parent_path() / percentDecode(*b.uri)).lexically_normal();
        auto read = readFileWithLimit(f, kMaxFileBytes, &reason); // checked by addBuffer
        if (!read)
            fail(at(at("buffers", buffer), "uri"), reason);
        bytes = std::move(*read);
    }
    return m_loaded[buffer] = std::move(bytes);
}

const std::string* AssetFiles::plannedImageFile(size_t i) const {
    const auto it = m_imageFiles.find(i);
    return it == m_imageFiles.end() ? nullptr : &it->second;
}

std::string AssetFiles::imageFile(size_t i, const ImageDesc& image,
                                  std::vector<ExportFile>& images) {
    if (const std::string* planned = plannedImageFile(i))
        return *planned;
    const std::string p = at("images", i);
    std::string bytes, ext;
    if (image.uri && image.uri->rfind("data:", 0) != 0) {
        const fs::path f = resolve(*image.uri, at(p, "uri"));
        std::error_code ec;
        if (!fs::is_regular_file(f, ec))
            fail(at(p, "uri"), "missing image file " + f.string());
        return m_imageFiles[i] = f.string();
    }
    if (image.uri) {
        const std::string& u = *image.uri;
        bytes = dataUri(u, at(p, "uri"));
        ext = extensionForMime(u.substr(5, u.find(';') - 5));
    } else if (image.bufferView) {
        const ViewDesc& v = m_views.at(*image.bufferView);
        const std::string buffer = bufferBytes(v.buffer);
        bytes = buffer.substr(size_t(v.byteOffset), size_t(v.byteLength));
        if (!image.mimeType)
            fail(at(p, "mimeType"), "required with a bufferView (glTF 2.0 section 5.18)");
        ext = extensionForMime(*image.mimeType);
    } else {
        fail(p, "has neither uri nor bufferView");
    }
    if (ext.empty())
        fail(p, "an image type glTF 2.0 does not define (image/png and image/jpeg only)");
    // STEM_<image name or index>.<ext>: a sanitised stem, never a path from the file.
    const std::string label = image.name
                                  ? sanitizeFileStem(*image.name, "image" + std::to_string(i))
                                  : "image" + std::to_string(i);
    std::string name = m_stem + "_" + label + ext;
    for (int n = 2; m_usedNames.count(name); ++n)
        name = m_stem + "_" + label + "_" + std::to_string(n) + ext;
    m_usedNames.insert(name);
    images.push_back({name, std::move(bytes)});
    return m_imageFiles[i] = (m_imageFolder / name).lexically_normal().string();
}

void AssetFiles::decodeImage(size_t i, const ImageDesc& image, const std::string& place,
                             std::vector<ExportFile>& images, Image& out) {
    const size_t before = images.size();
    const std::string file = imageFile(i, image, images);
    std::string error;
    if (images.size() > before) { // embedded: decode from a private temporary
        const ExportFile embedded = images.back();
        images.pop_back();
        m_imageFiles.erase(i);
        m_usedNames.erase(embedded.name);
        const fs::path tmp = fs::temp_directory_path() /
                             ("velvet-import-" + std::to_string(::getpid()) + "-" +
                              std::to_string(i) + fs::path(embedded.name).extension().string());
        if (!writeFileAtomically(tmp, embedded.bytes, &error))
            fail(place, error);
        const bool ok = readImage(tmp, out, &error);
        std::error_code ec;
        fs::remove(tmp, ec);
        if (!ok)
            fail(at("images", i), "cannot be decoded: " + error);
    } else if (!readImage(file, out, &error)) {
        fail(at("images", i), "cannot be decoded: " + error);
    }
}

std::string AssetFiles::addConvertedImage(const Image& image, std::string_view label,
                                          const std::string& place,
                                          std::vector<ExportFile>& images) {
    std::string png, error;
    if (!encodeImage(image, ".png", PixelFormat::UInt8, png, &error))
        fail(place, "cannot encode the converted " + std::string(label) + " image: " + error);
    const std::string name = m_stem + "_" + std::string(label) + "_converted.png";
    images.push_back({name, png});
    return (m_imageFolder / name).lexically_normal().string();
}

bool AssetFiles::hasAlpha(const std::string& file, const std::vector<ExportFile>& images) const {
    if (file.empty())
        return false;
    for (const ExportFile& f : images)
        if ((m_imageFolder / f.name).lexically_normal().string() == file)
            return f.bytes.size() > 25 && f.bytes.compare(1, 3, "PNG") == 0 &&
                   (f.bytes[25] == 4 || f.bytes[25] == 6);
    ImageInfo info;
    std::string error;
    return readImageInfo(file, info, &error) && (info.channels == 2 || info.channels == 4);
}

} // namespace velvet::gltf

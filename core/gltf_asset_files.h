#pragma once
/// @file gltf_asset_files.h
/// Internal to core's glTF import (core/gltf_import.cpp reads the JSON and maps the material):
/// the asset's files, with no JSON in sight — the container (a .glb's chunks, or the .gltf's
/// text), every buffer checked against its byteLength and every buffer view against its buffer,
/// data: URIs, images planned as files in the image folder (embedded ones under sanitised names)
/// and decoded; and the plain helpers both sides share (places, clamped values). The JSON side
/// hands in the plain descriptors below, so nlohmann's header stays in its .cpp file. Failures are
/// thrown as gltf::Failure with the glTF place ("buffers[0].uri").

#include "core/export_files.h"
#include "core/image.h"
#include "core/material_import.h"

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace velvet::gltf {

/// Thrown inside the glTF import only; importGltfMaterial turns it into an ImportProblem.
struct Failure {
    ImportProblem problem;
};
[[noreturn]] void fail(std::string place, std::string message,
                       ImportProblem::Kind kind = ImportProblem::Kind::Malformed);

/// "a.b" and "a[3]": the places failures and warnings name.
std::string at(const std::string& place, std::string_view key);
std::string at(const std::string& place, size_t index);
/// A number as warnings print it (%g).
std::string formatValue(float v);
/// A sampler's wrap mode (glTF 2.0 section 5.26) by name: "CLAMP_TO_EDGE", "MIRRORED_REPEAT",
/// else "REPEAT".
const char* wrapName(int mode);
/// A value into @p material, clamped to Velvet's range of @p id; a line appended to @p warnings
/// (naming @p place) says when it was clamped.
void setScalar(Material& material, ParamId id, double v, const std::string& place,
               std::vector<std::string>& warnings);
void setColor(Material& material, ParamId id, glm::vec3 c, const std::string& place,
              std::vector<std::string>& warnings);

/// A buffer as the JSON describes it (glTF 2.0 section 5.10); byteLength already checked.
struct BufferDesc {
    double byteLength = 0.0;
    std::optional<std::string> uri; ///< absent: the GLB's binary chunk
};
/// A buffer view (section 5.11); its buffer index already checked.
struct ViewDesc {
    size_t buffer = 0;
    double byteOffset = 0.0;
    double byteLength = 0.0;
};
/// An image (section 5.18) as far as the JSON side read it: a string uri (external or data:),
/// else a bufferView (index checked) with its mimeType when that is a string.
struct ImageDesc {
    std::optional<std::string> uri;
    std::optional<size_t> bufferView;
    std::optional<std::string> mimeType;
    std::optional<std::string> name;
};

class AssetFiles {
public:
    /// @p warnings receives the lines the files give rise to (a file outside the asset's folder).
    AssetFiles(std::filesystem::path file, std::filesystem::path imageFolder, std::string imageStem,
               std::vector<std::string>& warnings);

    /// Reads the file (2 GiB at most) and returns its JSON text: a .glb's JSON chunk (glTF 2.0
    /// section 4.4, its BIN chunk kept for buffer 0), else the whole file.
    std::string load();

    /// Checks buffer @p i (they come in order): there and as long as it says (section 3.6.1),
    /// so a missing .bin is malformed, not a quiet empty mesh.
    void addBuffer(size_t i, BufferDesc buffer);
    /// Checks view @p i lies inside its buffer.
    void addView(size_t i, ViewDesc view);

    /// The file a texture slot reads for images[@p i]: an external file as it is, an embedded
    /// image as a file planned in the image folder (appended to @p images once, whatever the
    /// number of slots reading it).
    std::string imageFile(size_t i, const ImageDesc& image, std::vector<ExportFile>& images);
    /// The file already planned for images[@p i], if any.
    const std::string* plannedImageFile(size_t i) const;
    /// Decodes images[@p i] (an embedded one through a private temporary file, as core's image
    /// reader takes files; it is not planned for writing). @p place names the textureInfo.
    void decodeImage(size_t i, const ImageDesc& image, const std::string& place,
                     std::vector<ExportFile>& images, Image& out);
    /// Encodes a converted image (KHR_materials_pbrSpecularGlossiness) as STEM_LABEL_converted.png
    /// into @p images and returns the file a slot reads.
    std::string addConvertedImage(const Image& image, std::string_view label,
                                  const std::string& place, std::vector<ExportFile>& images);
    /// Whether @p file (a slot's) has an alpha channel: an embedded PNG's colour type (grey or
    /// RGB with alpha, PNG specification 11.2.2), else the file's header.
    bool hasAlpha(const std::string& file, const std::vector<ExportFile>& images) const;

private:
    std::string dataUri(const std::string& uri, const std::string& place) const;
    /// The file a relative-path URI names (glTF 2.0 section 3.6.1: relative to the asset). An
    /// absolute path or another scheme than data: fails at @p place; a path that leaves the
    /// asset's folder is read with a warning (shared texture folders are common, but a file from
    /// outside should not pass unnoticed: docs/reliability.md).
    std::filesystem::path resolve(const std::string& uri, const std::string& place);
    std::string bufferBytes(size_t buffer);

    std::filesystem::path m_file, m_imageFolder;
    std::string m_stem;
    std::vector<std::string>* m_warnings;
    std::string m_bin;
    bool m_hasBin = false;
    std::vector<BufferDesc> m_buffers;
    std::vector<ViewDesc> m_views;
    std::map<size_t, std::string> m_loaded;
    std::map<size_t, std::string> m_imageFiles;
    std::set<std::string> m_usedNames;
};

} // namespace velvet::gltf

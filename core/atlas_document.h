#pragma once
/// @file atlas_document.h
/// The atlases a scene is authored with (issue 5, "Atlas panel"): the albedo, material
/// (R specular, G roughness, B metallic, the seeds' packing) and normal atlases, each a list of
/// source images with the region each one covers, the atlas size and padding, and the composed
/// image. Saved as a versioned JSON document of its own (`velvet.atlas`, docs/file-formats.md,
/// resources/schemas/atlas.schema.json) that a scene names in its `atlases` key; the pixels stay
/// in the source image files the document names (sources that exist only in memory are written
/// next to the document as OpenEXR files on save, losslessly). The composed image is not stored:
/// loading composes it again from the sources, so save then load gives back an equal set.
///
/// Loading validates everything first (every problem with its JSON path) and builds the set only
/// when there is no error. A source file that cannot be read is a warning: its entry keeps its
/// region and file and composes as empty, so saving again loses nothing.

#include "core/atlas_packing.h"
#include "core/diagnostics.h"
#include "core/image.h"
#include "core/texture_ref.h"

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace velvet {

inline constexpr std::string_view kAtlasFormat = "velvet.atlas";
inline constexpr int kAtlasVersion = 1;

enum class AtlasKind : int { Albedo = 0, Material = 1, Normal = 2 };
inline constexpr int kAtlasKindCount = 3;
/// "albedo", "material", "normal": the keys of the document's `atlases` object.
std::string_view atlasKindId(AtlasKind kind);

/// One image in an atlas: its source pixels and where they lie (without the padding).
struct AtlasEntry {
    std::string name;   ///< shown in the panel (the source's file name)
    std::string file;   ///< the source image (absolute); empty: pixels not saved yet
    Image source;       ///< the source pixels (empty when the file could not be read)
    AtlasRegion region; ///< texels of the atlas the source is stretched over
    bool operator==(const AtlasEntry& other) const;
};

/// One atlas: entries, size, padding and the composed image.
struct AtlasDocument {
    std::vector<AtlasEntry> entries;
    int width = 0;
    int height = 0;
    int padding = 4;
    Image image;          ///< composed from the entries (composeAtlas); empty without entries
    std::string filePath; ///< where the composed image was last exported; empty: never
    /// Same entries, size, padding and export path (the image follows from the entries).
    bool operator==(const AtlasDocument& other) const;
};

struct AtlasSet {
    std::array<AtlasDocument, kAtlasKindCount> atlases;
    AtlasDocument& operator[](AtlasKind kind) { return atlases[size_t(kind)]; }
    const AtlasDocument& operator[](AtlasKind kind) const { return atlases[size_t(kind)]; }
    /// No atlas has an entry.
    bool empty() const;
    bool operator==(const AtlasSet&) const = default;
};

/// Composes @p atlas.image from its entries: each source stretched (nearest) over its region,
/// with the padding replicated from the edge texels; texels outside every padded region are 0.
void composeAtlas(AtlasDocument& atlas);

/// Parses an atlas document; relative paths resolve against @p baseDir, and sources are read
/// (and the atlases composed) only when the document has no error.
std::optional<AtlasSet> parseAtlasSet(std::string_view text, const std::string& fileName,
                                      const std::filesystem::path& baseDir, Problems& problems);
std::optional<AtlasSet> loadAtlasFile(const std::filesystem::path& file, Problems& problems);
/// Pretty JSON of the current version; files under @p baseDir are written relative to it.
std::string atlasSetToJson(const AtlasSet& set, const std::filesystem::path& baseDir = {});
/// Saves @p set to @p file: first every source that has no file yet is written next to it as
/// `<stem>.<kind>-<n>.exr` (the stem without ".atlas"; 32-bit float, atomic) and @p set is updated
/// to name it, then the JSON is written atomically. False + @p error on failure (the JSON is then
/// not written).
bool saveAtlasFile(AtlasSet& set, const std::filesystem::path& file, std::string* error);

/// Writes the composed image of every non-empty atlas to @p folder as `<stem>-<kind>.<ext>`
/// through OpenImageIO, atomically (EXR as half; PNG and TIFF 8 bit for albedo, 16 bit for the
/// data atlases). @p written gets the paths. False + @p error at the first failure.
bool exportAtlasImages(const AtlasSet& set, const std::filesystem::path& folder,
                       const std::string& stem, const std::string& extension,
                       std::vector<std::filesystem::path>* written, std::string* error);
/// The pixel format exportAtlasImages() uses for @p kind and @p extension ("png", "exr", …).
PixelFormat atlasExportFormat(AtlasKind kind, const std::string& extension);

/// The JSON Schema (draft 2020-12) of atlas documents (resources/schemas/atlas.schema.json).
std::string atlasJsonSchema();

} // namespace velvet

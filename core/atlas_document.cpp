// Atlas documents: compose, read (validate everything, then read sources and build), write
// (in-memory sources first, then the JSON, each atomically), export, and the schema.
#include "core/atlas_document.h"

#include "core/atomic_file.h"
#include "core/document_io.h"
#include "core/document_paths.h"
#include "core/json_read.h"
#include "core/json_value.h"
#include "core/material_json.h"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace velvet {
namespace fs = std::filesystem;
namespace {

constexpr std::array<std::string_view, 3> kRootKeys{"format", "version", "atlases"};
constexpr std::array<std::string_view, kAtlasKindCount> kKindIds{"albedo", "material", "normal"};
constexpr std::array<std::string_view, 5> kAtlasKeys{"width", "height", "padding", "entries",
                                                     "exported"};
constexpr std::array<std::string_view, 3> kEntryKeys{"name", "file", "region"};
constexpr int kMaxAtlasSide = 16384; ///< core/image.h's read limit
constexpr int kMaxPadding = 256;

JsonValue str(std::string_view s) {
    return JsonValue::makeString(std::string(s));
}

bool sameImage(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height && (a.empty() || a.channels == b.channels) &&
           a.pixels == b.pixels;
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

/// What one entry of the file says, before any pixel is read.
struct EntrySpec {
    std::string name, file;
    AtlasRegion region;
};

void readAtlas(JsonReader& r, const JsonValue& v, const std::string& path, const fs::path& baseDir,
               AtlasDocument& atlas, std::vector<EntrySpec>& entries) {
    if (!r.expectObject(v, path, kAtlasKeys))
        return;
    const NumberRange side = closedRange(0, kMaxAtlasSide);
    if (const JsonValue* w = r.require(v, path, "width"))
        if (auto x = r.integer(*w, jsonPathKey(path, "width"), side))
            atlas.width = int(*x);
    if (const JsonValue* h = r.require(v, path, "height"))
        if (auto x = r.integer(*h, jsonPathKey(path, "height"), side))
            atlas.height = int(*x);
    if (const JsonValue* p = v.find("padding"))
        if (auto x = r.integer(*p, jsonPathKey(path, "padding"), closedRange(0, kMaxPadding)))
            atlas.padding = int(*x);
    if (const JsonValue* e = v.find("exported"))
        if (auto x = r.string(*e, jsonPathKey(path, "exported")))
            atlas.filePath = x->empty() ? std::string() : resolveDocumentPath(*x, baseDir);
    const JsonValue* list = r.require(v, path, "entries");
    if (!list || list->kind == JsonValue::Kind::Invalid)
        return;
    const std::string listPath = jsonPathKey(path, "entries");
    if (!list->isArray()) {
        r.error(listPath, "expected an array of entries, got " + describeValue(*list));
        return;
    }
    for (size_t i = 0; i < list->items.size(); ++i) {
        const JsonValue& e = list->items[i];
        const std::string ePath = jsonPathIndex(listPath, i);
        if (!r.expectObject(e, ePath, kEntryKeys)) {
            if (e.kind != JsonValue::Kind::Invalid)
                r.error(ePath, "expected an entry object, got " + describeValue(e));
            continue;
        }
        EntrySpec spec;
        if (const JsonValue* n = e.find("name"))
            if (auto x = r.string(*n, jsonPathKey(ePath, "name")))
                spec.name = *x;
        if (const JsonValue* f = r.require(e, ePath, "file"))
            if (auto x = r.string(*f, jsonPathKey(ePath, "file"), false))
                spec.file = resolveDocumentPath(*x, baseDir);
        if (const JsonValue* g = r.require(e, ePath, "region")) {
            const std::string gPath = jsonPathKey(ePath, "region");
            if (auto xs = r.numbers(*g, gPath, 4, closedRange(0, kMaxAtlasSide))) {
                const auto& n = *xs;
                bool integral = true;
                for (double x : n)
                    integral = integral && x == std::floor(x);
                if (!integral)
                    r.error(gPath, "expected 4 whole numbers of texels [x, y, width, height]");
                spec.region = {int(n[0]), int(n[1]), int(n[2]), int(n[3])};
                if (integral && (spec.region.width < 1 || spec.region.height < 1))
                    r.error(gPath, "a region is at least 1 x 1 texel");
                else if (integral && (spec.region.x + spec.region.width > atlas.width ||
                                      spec.region.y + spec.region.height > atlas.height))
                    r.error(gPath, "the region [" + std::to_string(spec.region.x) + ", " +
                                       std::to_string(spec.region.y) + ", " +
                                       std::to_string(spec.region.width) + ", " +
                                       std::to_string(spec.region.height) +
                                       "] does not fit in the " + std::to_string(atlas.width) +
                                       " x " + std::to_string(atlas.height) + " atlas");
            }
        }
        entries.push_back(std::move(spec));
    }
}

JsonValue numberSchema(double lo, double hi, const char* description) {
    JsonValue o = JsonValue::makeObject();
    o.add("type", str("integer"));
    o.add("minimum", JsonValue::makeNumber(lo));
    o.add("maximum", JsonValue::makeNumber(hi));
    o.add("description", str(description));
    return o;
}

} // namespace

std::string_view atlasKindId(AtlasKind kind) {
    return kKindIds[size_t(kind)];
}

bool AtlasEntry::operator==(const AtlasEntry& o) const {
    return name == o.name && file == o.file && region == o.region && sameImage(source, o.source);
}

bool AtlasDocument::operator==(const AtlasDocument& o) const {
    return entries == o.entries && width == o.width && height == o.height && padding == o.padding &&
           filePath == o.filePath;
}

bool AtlasSet::empty() const {
    return std::all_of(atlases.begin(), atlases.end(),
                       [](const AtlasDocument& a) { return a.entries.empty(); });
}

void composeAtlas(AtlasDocument& atlas) {
    if (atlas.entries.empty() || atlas.width <= 0 || atlas.height <= 0) {
        atlas.image = Image();
        return;
    }
    Image image(atlas.width, atlas.height, 4);
    const int pad = std::max(0, atlas.padding);
    for (const AtlasEntry& e : atlas.entries) {
        const AtlasRegion& r = e.region;
        if (e.source.empty() || r.width <= 0 || r.height <= 0)
            continue;
        const int x0 = std::max(0, r.x - pad), x1 = std::min(atlas.width, r.x + r.width + pad);
        const int y0 = std::max(0, r.y - pad), y1 = std::min(atlas.height, r.y + r.height + pad);
        for (int y = y0; y < y1; ++y) {
            // Nearest source texel; outside the region the clamp replicates the edge (padding).
            const int ly = std::clamp(y - r.y, 0, r.height - 1);
            const int sy = std::min(e.source.height - 1, ly * e.source.height / r.height);
            for (int x = x0; x < x1; ++x) {
                const int lx = std::clamp(x - r.x, 0, r.width - 1);
                const int sx = std::min(e.source.width - 1, lx * e.source.width / r.width);
                const glm::vec4 c = e.source.rgba(sx, sy);
                float* out = image.at(x, y);
                out[0] = c.r, out[1] = c.g, out[2] = c.b, out[3] = c.a;
            }
        }
    }
    atlas.image = std::move(image);
}

std::optional<AtlasSet> parseAtlasSet(std::string_view text, const std::string& fileName,
                                      const fs::path& baseDir, Problems& problems) {
    auto root = parseJson(text, fileName, problems, kMaxJsonDepth);
    if (!root || root->kind == JsonValue::Kind::Invalid)
        return std::nullopt;
    JsonReader r(fileName, problems);
    if (!root->isObject()) {
        r.error("", "expected an atlas document object, got " + describeValue(*root));
        return std::nullopt;
    }
    // Version 1 is the first; a later version migrates older documents here, before reading.
    if (!readFormatAndVersion(r, *root, "", kAtlasFormat, kAtlasVersion, true))
        return std::nullopt;
    r.expectObject(*root, "", kRootKeys);
    AtlasSet set;
    std::array<std::vector<EntrySpec>, kAtlasKindCount> specs;
    if (const JsonValue* atlases = r.require(*root, "", "atlases")) {
        if (r.expectObject(*atlases, "atlases", kKindIds)) {
            for (int k = 0; k < kAtlasKindCount; ++k)
                if (const JsonValue* a = atlases->find(kKindIds[size_t(k)]))
                    readAtlas(r, *a, jsonPathKey("atlases", kKindIds[size_t(k)]), baseDir,
                              set.atlases[size_t(k)], specs[size_t(k)]);
        } else if (atlases->kind != JsonValue::Kind::Invalid) {
            r.error("atlases", "expected an object with albedo, material and normal atlases, got " +
                                   describeValue(*atlases));
        }
    }
    if (r.failed())
        return std::nullopt;
    // Valid: read the sources (size-checked before decoding by readImage) and compose.
    for (int k = 0; k < kAtlasKindCount; ++k) {
        AtlasDocument& atlas = set.atlases[size_t(k)];
        for (size_t i = 0; i < specs[size_t(k)].size(); ++i) {
            EntrySpec& spec = specs[size_t(k)][i];
            AtlasEntry e;
            e.name = std::move(spec.name);
            e.file = std::move(spec.file);
            e.region = spec.region;
            std::string error;
            if (!readImage(e.file, e.source, &error)) {
                e.source = Image();
                r.warning(
                    jsonPathKey(
                        jsonPathIndex(
                            jsonPathKey(jsonPathKey("atlases", kKindIds[size_t(k)]), "entries"), i),
                        "file"),
                    "source not read (" + error + "); its region stays empty");
            }
            atlas.entries.push_back(std::move(e));
        }
        composeAtlas(atlas);
    }
    return set;
}

std::optional<AtlasSet> loadAtlasFile(const fs::path& file, Problems& problems) {
    std::string reason;
    const auto text = readFileWithLimit(file, kMaxDocumentBytes, &reason);
    if (!text) {
        problems.error(file.string(), "", reason);
        return std::nullopt;
    }
    return parseAtlasSet(*text, file.string(), file.parent_path(), problems);
}

std::string atlasSetToJson(const AtlasSet& set, const fs::path& baseDir) {
    JsonValue o = JsonValue::makeObject();
    o.add("format", str(kAtlasFormat));
    o.add("version", JsonValue::makeNumber(kAtlasVersion));
    JsonValue& atlases = o.add("atlases", JsonValue::makeObject());
    for (int k = 0; k < kAtlasKindCount; ++k) {
        const AtlasDocument& a = set.atlases[size_t(k)];
        if (a.entries.empty() && a.filePath.empty())
            continue;
        JsonValue& ja = atlases.add(std::string(kKindIds[size_t(k)]), JsonValue::makeObject());
        ja.add("width", JsonValue::makeNumber(a.width));
        ja.add("height", JsonValue::makeNumber(a.height));
        ja.add("padding", JsonValue::makeNumber(a.padding));
        if (!a.filePath.empty())
            ja.add("exported", JsonValue::makeString(relativeDocumentPath(a.filePath, baseDir)));
        JsonValue& entries = ja.add("entries", JsonValue::makeArray());
        for (const AtlasEntry& e : a.entries) {
            JsonValue& je = entries.push(JsonValue::makeObject());
            je.add("name", JsonValue::makeString(e.name));
            je.add("file", JsonValue::makeString(relativeDocumentPath(e.file, baseDir)));
            JsonValue& region = je.add("region", JsonValue::makeArray());
            for (int v : {e.region.x, e.region.y, e.region.width, e.region.height})
                region.push(JsonValue::makeNumber(v));
        }
    }
    return writeJson(o);
}

bool saveAtlasFile(AtlasSet& set, const fs::path& file, std::string* error) {
    const fs::path dir = file.parent_path();
    std::string stem = file.stem().string(); // "look" for look.atlas.json
    if (stem.size() > 6 && stem.ends_with(".atlas"))
        stem.resize(stem.size() - 6);
    for (int k = 0; k < kAtlasKindCount; ++k) {
        AtlasDocument& a = set.atlases[size_t(k)];
        for (size_t i = 0; i < a.entries.size(); ++i) {
            AtlasEntry& e = a.entries[i];
            if (!e.file.empty())
                continue;
            if (e.source.empty()) {
                if (error)
                    *error = file.string() + ": atlases." + std::string(kKindIds[size_t(k)]) +
                             ".entries[" + std::to_string(i) + "] has neither a file nor pixels";
                return false;
            }
            const fs::path source = dir / (stem + "." + std::string(kKindIds[size_t(k)]) + "-" +
                                           std::to_string(i) + ".exr");
            if (!writeImage(source, e.source, PixelFormat::Float, error)) // atomic, lossless
                return false;
            e.file = fs::absolute(source).lexically_normal().generic_string();
        }
    }
    return writeFileAtomically(file, atlasSetToJson(set, dir), error, /*keepBackup=*/true);
}

PixelFormat atlasExportFormat(AtlasKind kind, const std::string& extension) {
    const std::string ext = lower(extension);
    if (ext == "exr")
        return PixelFormat::Half;
    return kind == AtlasKind::Albedo ? PixelFormat::UInt8 : PixelFormat::UInt16;
}

bool exportAtlasImages(const AtlasSet& set, const fs::path& folder, const std::string& stem,
                       const std::string& extension, std::vector<fs::path>* written,
                       std::string* error) {
    bool any = false;
    for (int k = 0; k < kAtlasKindCount; ++k) {
        const AtlasDocument& a = set.atlases[size_t(k)];
        if (a.image.empty())
            continue;
        any = true;
        // The name is built here from a stem and a fixed kind id: it never leaves @p folder.
        const fs::path out =
            folder / (stem + "-" + std::string(kKindIds[size_t(k)]) + "." + lower(extension));
        if (!writeImage(out, a.image, atlasExportFormat(AtlasKind(k), extension), error))
            return false;
        if (written)
            written->push_back(out);
    }
    if (!any && error)
        *error = "every atlas is empty: nothing to export";
    return any;
}

std::string atlasJsonSchema() {
    JsonValue o = JsonValue::makeObject();
    o.add("$schema", str("https://json-schema.org/draft/2020-12/schema"));
    o.add("title", str("Velvet atlases"));
    o.add("description",
          str("The albedo, material (R specular, G roughness, B metallic) and normal atlases of a "
              "scene (core/atlas_document.h): source images and the region of the atlas each "
              "covers. The composed images are not stored; Velvet composes them on load."));
    o.add("type", str("object"));
    JsonValue& required = o.add("required", JsonValue::makeArray());
    for (std::string_view k : {"format", "version", "atlases"})
        required.push(str(k));
    o.add("additionalProperties", JsonValue::makeBool(false));
    JsonValue& p = o.add("properties", JsonValue::makeObject());
    p.add("format", JsonValue::makeObject()).add("const", str(kAtlasFormat));
    JsonValue& version = p.add("version", JsonValue::makeObject());
    version.add("type", str("integer"));
    version.add("minimum", JsonValue::makeNumber(1));
    version.add("maximum", JsonValue::makeNumber(kAtlasVersion));

    JsonValue entry = JsonValue::makeObject();
    entry.add("type", str("object"));
    entry.add("additionalProperties", JsonValue::makeBool(false));
    JsonValue& entryRequired = entry.add("required", JsonValue::makeArray());
    entryRequired.push(str("file"));
    entryRequired.push(str("region"));
    JsonValue& ep = entry.add("properties", JsonValue::makeObject());
    ep.add("name", JsonValue::makeObject()).add("type", str("string"));
    JsonValue& file = ep.add("file", JsonValue::makeObject());
    file.add("type", str("string"));
    file.add("minLength", JsonValue::makeNumber(1));
    file.add("description", str("The source image, relative to this document or absolute."));
    JsonValue& region = ep.add("region", JsonValue::makeObject());
    region.add("type", str("array"));
    region.add("items", numberSchema(0, kMaxAtlasSide, "Texels."));
    region.add("minItems", JsonValue::makeNumber(4));
    region.add("maxItems", JsonValue::makeNumber(4));
    region.add("description", str("[x, y, width, height] in texels of the atlas, top-left origin, "
                                  "without the padding; inside the atlas, at least 1 x 1."));

    JsonValue atlas = JsonValue::makeObject();
    atlas.add("type", str("object"));
    atlas.add("additionalProperties", JsonValue::makeBool(false));
    JsonValue& atlasRequired = atlas.add("required", JsonValue::makeArray());
    for (std::string_view k : {"width", "height", "entries"})
        atlasRequired.push(str(k));
    JsonValue& ap = atlas.add("properties", JsonValue::makeObject());
    ap.add("width", numberSchema(0, kMaxAtlasSide, "Atlas width in texels."));
    ap.add("height", numberSchema(0, kMaxAtlasSide, "Atlas height in texels."));
    JsonValue padding =
        numberSchema(0, kMaxPadding, "Texels around each region replicated from its edge.");
    padding.add("default", JsonValue::makeNumber(4));
    ap.add("padding", std::move(padding));
    JsonValue& exported = ap.add("exported", JsonValue::makeObject());
    exported.add("type", str("string"));
    exported.add("description", str("Where the composed image was last exported (material "
                                    "texture slots name this file)."));
    JsonValue& entries = ap.add("entries", JsonValue::makeObject());
    entries.add("type", str("array"));
    entries.add("items", std::move(entry));

    JsonValue& atlases = p.add("atlases", JsonValue::makeObject());
    atlases.add("type", str("object"));
    atlases.add("additionalProperties", JsonValue::makeBool(false));
    JsonValue& kinds = atlases.add("properties", JsonValue::makeObject());
    for (std::string_view k : kKindIds)
        kinds.add(std::string(k), atlas);
    return writeJson(o);
}

} // namespace velvet

#pragma once
/// @file import_text.h
/// Small readers the interchange importers share (internal to core): a byte offset as "line L,
/// column C", RFC 4648 base64 (glTF data: URIs), RFC 3986 percent-decoding (glTF URIs), and the
/// GLB container's chunks (glTF 2.0 section 4.4).

#include <optional>
#include <string>
#include <string_view>

namespace velvet {

/// "line L, column C" (both from 1) of byte @p offset of @p text.
std::string lineColumn(std::string_view text, size_t offset);

/// Base64, standard or URL-safe alphabet, padding and line breaks ignored; nullopt on any other
/// character.
std::optional<std::string> decodeBase64(std::string_view in);

/// %XX escapes decoded; everything else kept.
std::string percentDecode(std::string_view s);

/// A .glb's JSON chunk and its optional BIN chunk. False + @p place ("GLB header", "GLB chunk
/// 1") and @p message when the container is broken.
struct GlbChunks {
    std::string json;
    std::string bin;
    bool hasBin = false;
};
bool splitGlb(const std::string& bytes, GlbChunks& out, std::string& place, std::string& message);

/// True when @p bytes start with the GLB magic "glTF".
inline bool isGlb(std::string_view bytes) {
    return bytes.substr(0, 4) == "glTF";
}

} // namespace velvet

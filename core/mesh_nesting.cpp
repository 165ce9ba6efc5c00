#include "core/mesh_nesting.h"

#include <algorithm>

namespace velvet {

std::size_t jsonNestingDepth(std::string_view text, std::size_t stopAt) {
    std::size_t depth = 0, deepest = 0;
    bool inString = false, escaped = false;
    for (const char c : text) {
        if (inString) {
            if (escaped)
                escaped = false;
            else if (c == '\\')
                escaped = true;
            else if (c == '"')
                inString = false;
            continue;
        }
        if (c == '"') {
            inString = true;
        } else if (c == '{' || c == '[') {
            deepest = std::max(deepest, ++depth);
            if (deepest >= stopAt)
                return deepest;
        } else if ((c == '}' || c == ']') && depth > 0) {
            --depth;
        }
    }
    return deepest;
}

std::size_t xmlNestingDepth(std::string_view text, std::size_t stopAt) {
    std::size_t depth = 0, deepest = 0;
    std::size_t i = 0;
    const auto skipPast = [&](std::string_view end) {
        const std::size_t found = text.find(end, i);
        i = found == std::string_view::npos ? text.size() : found + end.size();
    };
    while ((i = text.find('<', i)) != std::string_view::npos) {
        const std::string_view rest = text.substr(i);
        if (rest.starts_with("<!--")) {
            skipPast("-->");
        } else if (rest.starts_with("<![CDATA[")) {
            skipPast("]]>");
        } else if (rest.starts_with("<?")) {
            skipPast("?>");
        } else if (rest.starts_with("<!")) {
            skipPast(">");
        } else if (rest.starts_with("</")) {
            if (depth > 0)
                --depth;
            skipPast(">");
        } else {
            // An opening tag: find its end, skipping quoted attribute values (which may hold '>').
            std::size_t j = i + 1;
            char quote = '\0';
            for (; j < text.size(); ++j) {
                const char c = text[j];
                if (quote) {
                    if (c == quote)
                        quote = '\0';
                } else if (c == '"' || c == '\'') {
                    quote = c;
                } else if (c == '>') {
                    break;
                }
            }
            const bool selfClosing = j < text.size() && j > i + 1 && text[j - 1] == '/';
            if (!selfClosing) {
                deepest = std::max(deepest, ++depth);
                if (deepest >= stopAt)
                    return deepest;
            }
            i = j < text.size() ? j + 1 : text.size();
        }
    }
    return deepest;
}

} // namespace velvet

#include <cstdint>
#include <fstream>
#include <iterator>

namespace velvet {

namespace {

std::string readRange(const std::filesystem::path& file, std::uint64_t offset, std::uint64_t size) {
    std::ifstream in(file, std::ios::binary);
    in.seekg(std::streamoff(offset));
    std::string bytes(size, '\0');
    in.read(bytes.data(), std::streamsize(size));
    bytes.resize(std::size_t(in.gcount()));
    return bytes;
}

} // namespace

bool checkMeshNesting(const std::filesystem::path& file, const std::string& ext,
                      std::string* error) {
    std::string text;
    bool xml = false;
    if (ext == ".gltf") {
        std::ifstream in(file, std::ios::binary);
        text.assign(std::istreambuf_iterator<char>(in), {});
    } else if (ext == ".glb") {
        // glTF 2.0 binary: 12-byte header, then the JSON chunk's length (uint32 LE) and type.
        const std::string header = readRange(file, 12, 4);
        if (header.size() < 4)
            return true; // too short to nest; the importer reports the truncation
        std::uint32_t length = 0;
        for (int i = 3; i >= 0; --i)
            length = (length << 8) | std::uint8_t(header[std::size_t(i)]);
        text = readRange(file, 20, length);
    } else if (ext == ".dae") {
        std::ifstream in(file, std::ios::binary);
        text.assign(std::istreambuf_iterator<char>(in), {});
        xml = true;
    } else {
        return true;
    }
    const std::size_t depth = xml ? xmlNestingDepth(text) : jsonNestingDepth(text);
    if (depth <= kMaxMeshFileNesting)
        return true;
    if (error)
        *error = file.string() + ": nested more than " + std::to_string(kMaxMeshFileNesting) +
                 " levels deep (" + (xml ? "XML elements" : "JSON objects and arrays") +
                 "); no mesh file needs that, refused";
    return false;
}

} // namespace velvet

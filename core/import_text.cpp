#include "core/import_text.h"

#include <cctype>
#include <cstdint>

namespace velvet {
namespace {

std::uint32_t u32(const std::string& b, size_t o) {
    return std::uint32_t(std::uint8_t(b[o])) | std::uint32_t(std::uint8_t(b[o + 1])) << 8 |
           std::uint32_t(std::uint8_t(b[o + 2])) << 16 |
           std::uint32_t(std::uint8_t(b[o + 3])) << 24;
}

int hexValue(char c) {
    if (c >= '0' && c <= '9')
        return c - '0';
    return std::tolower(static_cast<unsigned char>(c)) - 'a' + 10;
}

} // namespace

std::string lineColumn(std::string_view text, size_t offset) {
    size_t line = 1, column = 1;
    for (size_t i = 0; i < offset && i < text.size(); ++i) {
        if (text[i] == '\n') {
            ++line;
            column = 1;
        } else {
            ++column;
        }
    }
    return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

std::optional<std::string> decodeBase64(std::string_view in) {
    std::string out;
    unsigned acc = 0;
    int bits = 0;
    for (const char ch : in) {
        int v;
        if (ch >= 'A' && ch <= 'Z')
            v = ch - 'A';
        else if (ch >= 'a' && ch <= 'z')
            v = ch - 'a' + 26;
        else if (ch >= '0' && ch <= '9')
            v = ch - '0' + 52;
        else if (ch == '+' || ch == '-')
            v = 62;
        else if (ch == '/' || ch == '_')
            v = 63;
        else if (ch == '=' || ch == '\n' || ch == '\r')
            continue;
        else
            return std::nullopt;
        acc = ((acc << 6) | unsigned(v)) & 0xffffff;
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out.push_back(char((acc >> bits) & 0xff));
        }
    }
    return out;
}

std::string percentDecode(std::string_view s) {
    std::string out;
    for (size_t i = 0; i < s.size(); ++i) {
        if (s[i] == '%' && i + 2 < s.size() &&
            std::isxdigit(static_cast<unsigned char>(s[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(s[i + 2]))) {
            out.push_back(char(hexValue(s[i + 1]) * 16 + hexValue(s[i + 2])));
            i += 2;
        } else {
            out.push_back(s[i]);
        }
    }
    return out;
}

bool splitGlb(const std::string& b, GlbChunks& out, std::string& place, std::string& message) {
    place = "GLB header";
    if (b.size() < 20) {
        message = "the file is shorter than a GLB header (20 bytes)";
        return false;
    }
    if (u32(b, 4) != 2) {
        message =
            "container version " + std::to_string(u32(b, 4)) + "; glTF 2.0 binaries are version 2";
        return false;
    }
    if (u32(b, 8) > b.size()) {
        message = "the header says " + std::to_string(u32(b, 8)) + " bytes, the file has " +
                  std::to_string(b.size());
        return false;
    }
    const size_t jsonLength = u32(b, 12);
    if (u32(b, 16) != 0x4E4F534A || 20 + jsonLength > b.size()) {
        place = "GLB chunk 0";
        message = "the first chunk must be JSON and lie inside the file";
        return false;
    }
    out.json = b.substr(20, jsonLength);
    const size_t next = 20 + ((jsonLength + 3) & ~size_t(3));
    if (next + 8 <= b.size() && u32(b, next + 4) == 0x004E4942) {
        const size_t binLength = u32(b, next);
        if (next + 8 + binLength > b.size()) {
            place = "GLB chunk 1";
            message = "the BIN chunk runs past the end of the file";
            return false;
        }
        out.bin = b.substr(next + 8, binLength);
        out.hasBin = true;
    }
    return true;
}

} // namespace velvet

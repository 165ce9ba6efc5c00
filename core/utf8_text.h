#pragma once
/// @file utf8_text.h
/// Whether bytes are text: the check every reader of a text document shares (the JSON reader,
/// core/json_value.cpp, where it is defined; the MaterialX reader), so a name or path read from
/// one never reaches a preset as bytes that Velvet's own JSON reader refuses.

#include <cstddef>
#include <optional>
#include <string_view>

namespace velvet {

/// The offset of the first byte of @p s that is not well-formed UTF-8 (RFC 3629: no overlongs, no
/// surrogates, nothing above U+10FFFF) or is a NUL, which no text document contains; nullopt when
/// all of it is text.
std::optional<size_t> firstNonText(std::string_view s);

} // namespace velvet

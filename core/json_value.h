#pragma once
/// @file json_value.h
/// Velvet's own small JSON tree, internal to core's document readers and writers. It keeps the
/// JSON library (nlohmann-json) inside json_value.cpp, keeps object keys in document order (so
/// files are written in metadata order), and lets the parser mark values it already reported.

#include "core/diagnostics.h"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace velvet {

struct JsonMember;

/// One JSON value. Plain data; containers own their children.
struct JsonValue {
    enum class Kind {
        Null,
        Bool,
        Number,
        String,
        Array,
        Object,
        Invalid, ///< a value the parser already reported (e.g. 1e999); readers stay silent on it
    };
    Kind kind = Kind::Null;
    bool boolean = false;
    double number = 0.0;
    bool integral = false; ///< the number is a whole number (version fields need integers)
    std::string text;      ///< string value, or the number as written (for messages)
    std::vector<JsonValue> items;
    std::vector<JsonMember> members;

    static JsonValue makeBool(bool b);
    static JsonValue makeNumber(double d);
    /// The shortest decimal that reads back as @p f, so 0.8f is written "0.8", not
    /// 0.800000011920929.
    static JsonValue makeFloat(float f);
    static JsonValue makeString(std::string s);
    static JsonValue makeArray();
    static JsonValue makeObject();

    bool isObject() const { return kind == Kind::Object; }
    bool isArray() const { return kind == Kind::Array; }
    /// The member named @p key of an object, or nullptr.
    const JsonValue* find(std::string_view key) const;
    /// Appends a member to an object (callers write each key once).
    JsonValue& add(std::string key, JsonValue value);
    /// Appends an item to an array.
    JsonValue& push(JsonValue value);
};

struct JsonMember {
    std::string key;
    JsonValue value;
};

/// Parses @p text. Problems name @p fileName and the JSON path where they occur: invalid UTF-8 or
/// binary data, syntax errors (with line and column), nesting deeper than @p maxDepth (checked
/// while parsing, so 100000 nested '[' cost no stack), duplicate keys, numbers out of the double
/// range. Returns nullopt when the text is not JSON at all; with a tree, problems may still hold
/// errors for Invalid values.
std::optional<JsonValue> parseJson(std::string_view text, const std::string& fileName,
                                   Problems& problems, int maxDepth);

/// Pretty text: two-space indent, short lists of scalars on one line, a final newline.
std::string writeJson(const JsonValue& value);

/// JSON paths as problems show them: "lobes.base.roughness", "lights[2].intensity". Keys that are
/// not plain identifiers are quoted: textures["my key"].
std::string jsonPathKey(std::string_view parent, std::string_view key);
std::string jsonPathIndex(std::string_view parent, size_t index);

} // namespace velvet

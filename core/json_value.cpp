#include "core/json_value.h"

#include "core/utf8_text.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <unordered_set>

namespace velvet {
namespace {

/// More problems than this from one parse add nothing for the reader, and a hostile file with a
/// million duplicate keys must not produce a million lines.
constexpr size_t kMaxParseProblems = 50;

bool isIdentifier(std::string_view key) {
    if (key.empty() || std::isdigit(static_cast<unsigned char>(key[0])))
        return false;
    for (char c : key)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-')
            return false;
    return true;
}

std::string jsonQuoted(std::string_view s) {
    std::string out = "\"";
    for (char c : s) {
        const auto u = static_cast<unsigned char>(c);
        switch (c) {
        case '"':
            out += "\\\"";
            break;
        case '\\':
            out += "\\\\";
            break;
        case '\n':
            out += "\\n";
            break;
        case '\r':
            out += "\\r";
            break;
        case '\t':
            out += "\\t";
            break;
        case '\b':
            out += "\\b";
            break;
        case '\f':
            out += "\\f";
            break;
        default:
            if (u < 0x20) {
                char buf[8];
                std::snprintf(buf, sizeof buf, "\\u%04x", u);
                out += buf;
            } else {
                out += c;
            }
        }
    }
    out += '"';
    return out;
}

} // namespace

std::optional<size_t> firstNonText(std::string_view s) {
    size_t i = 0;
    while (i < s.size()) {
        const auto c = static_cast<unsigned char>(s[i]);
        if (c == 0)
            return i;
        if (c < 0x80) {
            ++i;
            continue;
        }
        int len = 0;
        unsigned lo = 0x80, hi = 0xBF;
        if (c >= 0xC2 && c <= 0xDF) {
            len = 2;
        } else if (c >= 0xE0 && c <= 0xEF) {
            len = 3;
            if (c == 0xE0)
                lo = 0xA0;
            if (c == 0xED)
                hi = 0x9F;
        } else if (c >= 0xF0 && c <= 0xF4) {
            len = 4;
            if (c == 0xF0)
                lo = 0x90;
            if (c == 0xF4)
                hi = 0x8F;
        } else {
            return i;
        }
        if (i + len > s.size())
            return i;
        for (int k = 1; k < len; ++k) {
            const auto d = static_cast<unsigned char>(s[i + k]);
            const unsigned l = k == 1 ? lo : 0x80, h = k == 1 ? hi : 0xBF;
            if (d < l || d > h)
                return i;
        }
        i += len;
    }
    return std::nullopt;
}

namespace {

std::pair<size_t, size_t> lineColumn(std::string_view s, size_t offset) {
    size_t line = 1, column = 1;
    for (size_t i = 0; i < offset && i < s.size(); ++i) {
        if (s[i] == '\n') {
            ++line;
            column = 1;
        } else {
            ++column;
        }
    }
    return {line, column};
}

/// Builds a JsonValue tree from nlohmann's SAX events. Parsing through SAX rather than into
/// nlohmann's own tree lets us stop at the depth limit before anything deep is built, and know
/// the JSON path of every event for duplicate keys and out-of-range numbers.
class TreeBuilder {
public:
    TreeBuilder(std::string_view text, const std::string& file, Problems& problems, int maxDepth)
        : m_text(text), m_file(file), m_problems(problems), m_maxDepth(maxDepth) {}

    using Json = nlohmann::json;

    bool null() { return put(JsonValue{}); }
    bool boolean(bool b) { return put(JsonValue::makeBool(b)); }
    bool number_integer(Json::number_integer_t v) {
        JsonValue j = JsonValue::makeNumber(static_cast<double>(v));
        j.text = std::to_string(v);
        return put(std::move(j));
    }
    bool number_unsigned(Json::number_unsigned_t v) {
        JsonValue j = JsonValue::makeNumber(static_cast<double>(v));
        j.text = std::to_string(v);
        return put(std::move(j));
    }
    bool number_float(Json::number_float_t v, const Json::string_t& raw) {
        if (!std::isfinite(v)) {
            error(currentPath(),
                  "the number " + raw + " is out of range (larger than about 1.8e308)");
            JsonValue invalid;
            invalid.kind = JsonValue::Kind::Invalid;
            return put(std::move(invalid));
        }
        JsonValue j = JsonValue::makeNumber(v);
        j.text = raw;
        return put(std::move(j));
    }
    bool string(Json::string_t& s) { return put(JsonValue::makeString(std::move(s))); }
    bool binary(Json::binary_t&) { return put(JsonValue{}); }
    bool start_object(size_t) { return open(JsonValue::makeObject()); }
    bool start_array(size_t) { return open(JsonValue::makeArray()); }
    bool key(Json::string_t& k) {
        Frame& f = m_stack.back();
        if (!f.keys.insert(k).second)
            error(jsonPathKey(pathOf(m_stack.size() - 1), k),
                  "duplicate key \"" + k + "\" (each key may appear once)");
        f.pendingKey = std::move(k);
        f.hasPendingKey = true;
        return true;
    }
    bool end_object() { return close(); }
    bool end_array() { return close(); }
    bool parse_error(size_t position, const std::string& lastToken,
                     const nlohmann::detail::exception& ex) {
        if (ex.id == 406) { // out_of_range.406: a number beyond the range of double
            error(currentPath(),
                  "the number " + lastToken + " is out of range (larger than about 1.8e308)");
            return false;
        }
        std::string what = ex.what();
        // "[json.exception.parse_error.101] parse error at line 1, column 5: syntax error ..."
        if (auto p = what.find("] "); p != std::string::npos)
            what.erase(0, p + 2);
        if (what.rfind("parse error", 0) == 0)
            what.replace(0, 11, "invalid JSON");
        if (looksLikeNonFinite(position))
            what += " (NaN and Infinity are not numbers in JSON)";
        error(currentPath(), what);
        return false;
    }

    bool depthExceeded() const { return m_depthExceeded; }
    std::optional<JsonValue> takeRoot() { return std::move(m_root); }

private:
    /// Whether the bad literal the parser stopped in is a NaN or an Infinity, which other
    /// languages write into JSON files and which deserve a clearer word than "invalid literal".
    bool looksLikeNonFinite(size_t position) const {
        size_t start = std::min(position, m_text.size());
        while (start > 0 && (std::isalpha(static_cast<unsigned char>(m_text[start - 1])) ||
                             m_text[start - 1] == '-' || m_text[start - 1] == '+'))
            --start;
        std::string word;
        for (size_t i = start; i < m_text.size() && word.size() < 9; ++i) {
            const auto c = static_cast<unsigned char>(m_text[i]);
            if (!std::isalpha(c) && c != '-' && c != '+')
                break;
            if (std::isalpha(c))
                word += static_cast<char>(std::tolower(c));
        }
        return word.rfind("nan", 0) == 0 || word.rfind("inf", 0) == 0;
    }

    struct Frame {
        JsonValue value;
        std::string pendingKey;
        bool hasPendingKey = false;           ///< a key was read and its value not yet stored
        std::unordered_set<std::string> keys; ///< seen keys: duplicates checked in O(1)
    };

    void error(std::string path, std::string message) {
        if (m_reported == kMaxParseProblems)
            m_problems.error(m_file, "", "too many problems; the rest are not shown");
        if (m_reported++ < kMaxParseProblems)
            m_problems.error(m_file, std::move(path), std::move(message));
    }

    std::string pathOf(size_t depth) const {
        std::string path;
        for (size_t i = 0; i < depth; ++i) {
            const Frame& f = m_stack[i];
            if (f.value.isArray())
                path = jsonPathIndex(path, f.value.items.size());
            else if (f.hasPendingKey)
                path = jsonPathKey(path, f.pendingKey);
        }
        return path;
    }
    std::string currentPath() const { return pathOf(m_stack.size()); }

    bool put(JsonValue v) {
        if (m_stack.empty()) {
            m_root = std::move(v);
            return true;
        }
        Frame& f = m_stack.back();
        if (f.value.isArray())
            f.value.items.push_back(std::move(v));
        else
            f.value.add(std::move(f.pendingKey), std::move(v));
        f.hasPendingKey = false;
        return true;
    }
    bool open(JsonValue container) {
        if (static_cast<int>(m_stack.size()) >= m_maxDepth) {
            error(currentPath(), "nesting deeper than " + std::to_string(m_maxDepth) +
                                     " levels of arrays and objects");
            m_depthExceeded = true;
            return false; // stops the parser: nothing deeper is read
        }
        m_stack.push_back({std::move(container), {}, {}});
        return true;
    }
    bool close() {
        JsonValue v = std::move(m_stack.back().value);
        m_stack.pop_back();
        return put(std::move(v));
    }

    std::string_view m_text;
    const std::string& m_file;
    Problems& m_problems;
    int m_maxDepth;
    size_t m_reported = 0;
    bool m_depthExceeded = false;
    std::vector<Frame> m_stack;
    std::optional<JsonValue> m_root;
};

void formatNumber(std::string& out, double d) {
    char buf[32];
    if (d == std::floor(d) && std::fabs(d) < 9007199254740992.0) {
        out += std::to_string(static_cast<long long>(d));
        return;
    }
    const auto r = std::to_chars(buf, buf + sizeof buf, d);
    out.append(buf, r.ptr);
}

bool isScalar(const JsonValue& v) {
    return !v.isArray() && !v.isObject();
}

void write(std::string& out, const JsonValue& v, int indent) {
    const std::string pad(static_cast<size_t>(indent + 1) * 2, ' ');
    const std::string closePad(static_cast<size_t>(indent) * 2, ' ');
    switch (v.kind) {
    case JsonValue::Kind::Null:
    case JsonValue::Kind::Invalid:
        out += "null";
        break;
    case JsonValue::Kind::Bool:
        out += v.boolean ? "true" : "false";
        break;
    case JsonValue::Kind::Number:
        formatNumber(out, v.number);
        break;
    case JsonValue::Kind::String:
        out += jsonQuoted(v.text);
        break;
    case JsonValue::Kind::Array: {
        if (v.items.empty()) {
            out += "[]";
            break;
        }
        // Colours, vectors and enum lists read best on one line.
        const bool inlineList =
            v.items.size() <= 8 && std::all_of(v.items.begin(), v.items.end(), isScalar);
        out += inlineList ? "[" : "[\n";
        for (size_t i = 0; i < v.items.size(); ++i) {
            if (!inlineList)
                out += pad;
            write(out, v.items[i], indent + 1);
            if (i + 1 < v.items.size())
                out += inlineList ? ", " : ",\n";
        }
        out += inlineList ? "]" : "\n" + closePad + "]";
        break;
    }
    case JsonValue::Kind::Object: {
        if (v.members.empty()) {
            out += "{}";
            break;
        }
        out += "{\n";
        for (size_t i = 0; i < v.members.size(); ++i) {
            out += pad + jsonQuoted(v.members[i].key) + ": ";
            write(out, v.members[i].value, indent + 1);
            out += i + 1 < v.members.size() ? ",\n" : "\n";
        }
        out += closePad + "}";
        break;
    }
    }
}

} // namespace

JsonValue JsonValue::makeBool(bool b) {
    JsonValue v;
    v.kind = Kind::Bool;
    v.boolean = b;
    return v;
}

JsonValue JsonValue::makeNumber(double d) {
    JsonValue v;
    v.kind = Kind::Number;
    v.number = d;
    v.integral = std::isfinite(d) && d == std::floor(d);
    return v;
}

JsonValue JsonValue::makeFloat(float f) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, f);
    double d = f;
    std::from_chars(buf, r.ptr, d);
    return makeNumber(d);
}

JsonValue JsonValue::makeString(std::string s) {
    JsonValue v;
    v.kind = Kind::String;
    v.text = std::move(s);
    return v;
}

JsonValue JsonValue::makeArray() {
    JsonValue v;
    v.kind = Kind::Array;
    return v;
}

JsonValue JsonValue::makeObject() {
    JsonValue v;
    v.kind = Kind::Object;
    return v;
}

const JsonValue* JsonValue::find(std::string_view key) const {
    for (const JsonMember& m : members)
        if (m.key == key)
            return &m.value;
    return nullptr;
}

JsonValue& JsonValue::add(std::string key, JsonValue value) {
    members.push_back({std::move(key), std::move(value)});
    return members.back().value;
}

JsonValue& JsonValue::push(JsonValue value) {
    items.push_back(std::move(value));
    return items.back();
}

std::optional<JsonValue> parseJson(std::string_view text, const std::string& fileName,
                                   Problems& problems, int maxDepth) {
    if (text.find_first_not_of(" \t\r\n") == std::string_view::npos) {
        problems.error(fileName, "",
                       text.empty() ? "the file is empty"
                                    : "the file holds only white space, no JSON");
        return std::nullopt;
    }
    if (auto bad = firstNonText(text)) {
        const auto [line, column] = lineColumn(text, *bad);
        char byte[8];
        std::snprintf(byte, sizeof byte, "0x%02X", static_cast<unsigned char>(text[*bad]));
        problems.error(fileName, "",
                       "not a UTF-8 text file (binary data: byte " + std::string(byte) +
                           " at line " + std::to_string(line) + ", column " +
                           std::to_string(column) + ")");
        return std::nullopt;
    }
    TreeBuilder builder(text, fileName, problems, maxDepth);
    const size_t before = problems.items.size();
    const bool ok = nlohmann::json::sax_parse(text.begin(), text.end(), &builder);
    if (!ok) {
        if (problems.items.size() == before)
            problems.error(fileName, "", "invalid JSON");
        return std::nullopt;
    }
    return builder.takeRoot();
}

std::string writeJson(const JsonValue& value) {
    std::string out;
    write(out, value, 0);
    out += '\n';
    return out;
}

std::string jsonPathKey(std::string_view parent, std::string_view key) {
    std::string out(parent);
    if (isIdentifier(key)) {
        if (!out.empty())
            out += '.';
        out += key;
    } else {
        out += '[';
        out += jsonQuoted(key);
        out += ']';
    }
    return out;
}

std::string jsonPathIndex(std::string_view parent, size_t index) {
    return std::string(parent) + "[" + std::to_string(index) + "]";
}

} // namespace velvet

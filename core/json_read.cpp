#include "core/json_read.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>

namespace velvet {
namespace {

/// A document with thousands of bad entries gains nothing from thousands of lines.
constexpr size_t kMaxReportedErrors = 200;

size_t editDistance(std::string_view a, std::string_view b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j)
        row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diag = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t up = row[j];
            const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                              std::tolower(static_cast<unsigned char>(b[j - 1]));
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (same ? 0 : 1)});
            diag = up;
        }
    }
    return row[b.size()];
}

std::string quote(std::string_view s) {
    // Messages are one line: long or multi-line strings are cut short.
    std::string out = "\"";
    for (char c : s.substr(0, 40))
        out += (c == '\n' || c == '\r' || c == '\t') ? ' ' : c;
    if (s.size() > 40)
        out += "…";
    return out + "\"";
}

} // namespace

bool NumberRange::contains(double v) const {
    if (!std::isfinite(v))
        return false;
    if (minExclusive ? !(v > min) : !(v >= min))
        return false;
    if (maxExclusive ? !(v < max) : !(v <= max))
        return false;
    return true;
}

std::string NumberRange::describe() const {
    const bool hasMin = std::isfinite(min), hasMax = std::isfinite(max);
    if (hasMin && hasMax)
        return std::string("a number in ") + (minExclusive ? "(" : "[") + formatNumber(min) + ", " +
               formatNumber(max) + (maxExclusive ? ")" : "]");
    if (hasMin)
        return std::string("a number ") + (minExclusive ? "> " : ">= ") + formatNumber(min);
    if (hasMax)
        return std::string("a number ") + (maxExclusive ? "< " : "<= ") + formatNumber(max);
    return "a number";
}

NumberRange closedRange(double lo, double hi) {
    return {lo, hi, false, false};
}
NumberRange atLeast(double lo) {
    NumberRange r;
    r.min = lo;
    return r;
}
NumberRange greaterThan(double lo) {
    NumberRange r;
    r.min = lo;
    r.minExclusive = true;
    return r;
}

std::string formatNumber(double v) {
    char buf[32];
    // Metadata ranges are floats: print the float's shortest form so 0.03f reads "0.03".
    const float f = static_cast<float>(v);
    const auto r = static_cast<double>(f) == v || std::fabs(v) < 1e30
                       ? std::to_chars(buf, buf + sizeof buf, f)
                       : std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
}

std::string describeValue(const JsonValue& v) {
    switch (v.kind) {
    case JsonValue::Kind::Null:
        return "null";
    case JsonValue::Kind::Bool:
        return v.boolean ? "true" : "false";
    case JsonValue::Kind::Number:
        return v.text.empty() ? formatNumber(v.number) : v.text;
    case JsonValue::Kind::String:
        return quote(v.text);
    case JsonValue::Kind::Array:
        return "an array of " + std::to_string(v.items.size()) +
               (v.items.size() == 1 ? " item" : " items");
    case JsonValue::Kind::Object:
        return "an object";
    case JsonValue::Kind::Invalid:
        return "an invalid value";
    }
    return "?";
}

static size_t commonPrefix(std::string_view a, std::string_view b) {
    size_t n = 0;
    while (n < a.size() && n < b.size() &&
           std::tolower(static_cast<unsigned char>(a[n])) ==
               std::tolower(static_cast<unsigned char>(b[n])))
        ++n;
    return n;
}

std::string didYouMean(std::string_view word, std::span<const std::string_view> candidates) {
    std::string_view best;
    size_t bestDistance = std::numeric_limits<size_t>::max();
    for (std::string_view c : candidates) {
        const size_t d = editDistance(word, c);
        // Close by spelling ("rougness"), or the same start ("blury" for "blurred").
        const bool close = d <= std::max<size_t>(2, word.size() / 3) ||
                           commonPrefix(word, c) >= std::max<size_t>(4, (word.size() + 1) / 2);
        if (close && d < bestDistance) {
            bestDistance = d;
            best = c;
        }
    }
    return best.empty() ? std::string() : " (did you mean \"" + std::string(best) + "\"?)";
}

std::string listNames(std::span<const std::string_view> names) {
    std::string out;
    for (size_t i = 0; i < names.size(); ++i) {
        if (i > 0)
            out += i + 1 == names.size() ? " or " : ", ";
        out += '"';
        out += names[i];
        out += '"';
    }
    return out;
}

JsonReader::JsonReader(std::string fileName, Problems& problems)
    : m_file(std::move(fileName)), m_problems(problems) {}

void JsonReader::error(std::string path, std::string message) {
    if (m_errors == kMaxReportedErrors)
        m_problems.error(m_file, "", "too many problems; the rest are not shown");
    if (m_errors++ < kMaxReportedErrors)
        m_problems.error(m_file, std::move(path), std::move(message));
}

void JsonReader::warning(std::string path, std::string message) {
    m_problems.warning(m_file, std::move(path), std::move(message));
}

bool JsonReader::expectObject(const JsonValue& v, const std::string& path,
                              std::span<const std::string_view> allowed) {
    if (alreadyReported(v))
        return false;
    if (!v.isObject()) {
        error(path, "expected an object, got " + describeValue(v));
        return false;
    }
    for (const JsonMember& m : v.members)
        if (std::find(allowed.begin(), allowed.end(), m.key) == allowed.end())
            error(jsonPathKey(path, m.key),
                  "unknown key \"" + m.key + "\"" + didYouMean(m.key, allowed));
    return true;
}

const JsonValue* JsonReader::require(const JsonValue& object, const std::string& parentPath,
                                     std::string_view key) {
    const JsonValue* v = object.find(key);
    if (!v)
        error(jsonPathKey(parentPath, key), "required key is missing");
    return v;
}

std::optional<double> JsonReader::number(const JsonValue& v, const std::string& path,
                                         const NumberRange& range) {
    if (alreadyReported(v))
        return std::nullopt;
    if (v.kind != JsonValue::Kind::Number || !range.contains(v.number)) {
        error(path, "expected " + range.describe() + ", got " + describeValue(v));
        return std::nullopt;
    }
    return v.number;
}

std::optional<long long> JsonReader::integer(const JsonValue& v, const std::string& path,
                                             const NumberRange& range) {
    if (alreadyReported(v))
        return std::nullopt;
    if (v.kind != JsonValue::Kind::Number || !v.integral || !range.contains(v.number)) {
        std::string expected = range.describe();
        expected.replace(0, 8, "an integer"); // "a number…" → "an integer…"
        error(path, "expected " + expected + ", got " + describeValue(v));
        return std::nullopt;
    }
    return static_cast<long long>(v.number);
}

std::optional<bool> JsonReader::boolean(const JsonValue& v, const std::string& path) {
    if (alreadyReported(v))
        return std::nullopt;
    if (v.kind != JsonValue::Kind::Bool) {
        error(path, "expected true or false, got " + describeValue(v));
        return std::nullopt;
    }
    return v.boolean;
}

std::optional<std::string> JsonReader::string(const JsonValue& v, const std::string& path,
                                              bool allowEmpty) {
    if (alreadyReported(v))
        return std::nullopt;
    if (v.kind != JsonValue::Kind::String || (!allowEmpty && v.text.empty())) {
        error(path, std::string(allowEmpty ? "expected a string" : "expected a non-empty string") +
                        ", got " + describeValue(v));
        return std::nullopt;
    }
    return v.text;
}

std::optional<std::vector<double>> JsonReader::numbers(const JsonValue& v, const std::string& path,
                                                       size_t count, const NumberRange& range) {
    if (alreadyReported(v))
        return std::nullopt;
    if (!v.isArray() || v.items.size() != count) {
        error(path, "expected an array of " + std::to_string(count) + " numbers, got " +
                        describeValue(v));
        return std::nullopt;
    }
    std::vector<double> out;
    for (size_t i = 0; i < count; ++i)
        if (auto n = number(v.items[i], jsonPathIndex(path, i), range))
            out.push_back(*n);
    if (out.size() != count)
        return std::nullopt;
    return out;
}

std::optional<glm::vec3> JsonReader::vec3(const JsonValue& v, const std::string& path,
                                          const NumberRange& range) {
    auto n = numbers(v, path, 3, range);
    if (!n)
        return std::nullopt;
    return glm::vec3(static_cast<float>((*n)[0]), static_cast<float>((*n)[1]),
                     static_cast<float>((*n)[2]));
}

std::optional<glm::vec2> JsonReader::vec2(const JsonValue& v, const std::string& path,
                                          const NumberRange& range) {
    auto n = numbers(v, path, 2, range);
    if (!n)
        return std::nullopt;
    return glm::vec2(static_cast<float>((*n)[0]), static_cast<float>((*n)[1]));
}

std::optional<int> JsonReader::choice(const JsonValue& v, const std::string& path,
                                      std::span<const std::string_view> names) {
    if (alreadyReported(v))
        return std::nullopt;
    if (v.kind == JsonValue::Kind::String) {
        for (size_t i = 0; i < names.size(); ++i)
            if (names[i] == v.text)
                return static_cast<int>(i);
    }
    error(path, "expected one of " + listNames(names) + ", got " + describeValue(v) +
                    (v.kind == JsonValue::Kind::String ? didYouMean(v.text, names) : ""));
    return std::nullopt;
}

} // namespace velvet

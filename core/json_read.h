#pragma once
/// @file json_read.h
/// Typed reads out of a parsed document (internal to core's readers). Each read checks the type
/// and range, and on failure records one problem in the house style —
/// `lobes.base.roughness: expected a number in [0, 1], got "high"` — and returns nullopt, so a
/// reader carries on and reports every problem of the document, not only the first.

#include "core/diagnostics.h"
#include "core/json_value.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace velvet {

/// An allowed interval of numbers; each end open, closed or absent (infinite).
struct NumberRange {
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
    bool minExclusive = false;
    bool maxExclusive = false;

    bool contains(double v) const;
    /// "a number in [0, 1]", "a number > 0", "a number in (1, 179)", "a number".
    std::string describe() const;
};

/// [lo, hi]
NumberRange closedRange(double lo, double hi);
/// [lo, +inf)
NumberRange atLeast(double lo);
/// (lo, +inf)
NumberRange greaterThan(double lo);

/// Shortest decimal form of @p v for messages and docs ("0.03", "179", "1e+30").
std::string formatNumber(double v);
/// A value as a message shows it after "got": "high" quoted, numbers as written, "an object".
std::string describeValue(const JsonValue& v);
/// " (did you mean \"roughness\"?)" when a candidate is close to @p word, else "".
std::string didYouMean(std::string_view word, std::span<const std::string_view> candidates);
/// "\"ggx\", \"beckmann\" or \"blinn-phong\""
std::string listNames(std::span<const std::string_view> names);

/// Reads typed values and records problems against one file.
class JsonReader {
public:
    JsonReader(std::string fileName, Problems& problems);

    const std::string& fileName() const { return m_file; }
    void error(std::string path, std::string message);
    void warning(std::string path, std::string message);
    /// Whether this reader recorded any error.
    bool failed() const { return m_errors > 0; }
    /// How many errors this reader recorded (to tell whether one part read cleanly).
    size_t errorCount() const { return m_errors; }

    /// @p v must be an object whose keys are all in @p allowed; unknown keys are reported (each
    /// with a suggestion when one is close). False only when @p v is not an object.
    bool expectObject(const JsonValue& v, const std::string& path,
                      std::span<const std::string_view> allowed);
    /// Reports @p key of @p object as missing when absent. Returns the member or nullptr.
    const JsonValue* require(const JsonValue& object, const std::string& parentPath,
                             std::string_view key);

    std::optional<double> number(const JsonValue& v, const std::string& path,
                                 const NumberRange& range);
    std::optional<long long> integer(const JsonValue& v, const std::string& path,
                                     const NumberRange& range);
    std::optional<bool> boolean(const JsonValue& v, const std::string& path);
    std::optional<std::string> string(const JsonValue& v, const std::string& path,
                                      bool allowEmpty = true);
    /// An array of exactly @p count numbers, each in @p range.
    std::optional<std::vector<double>> numbers(const JsonValue& v, const std::string& path,
                                               size_t count, const NumberRange& range);
    std::optional<glm::vec3> vec3(const JsonValue& v, const std::string& path,
                                  const NumberRange& range);
    std::optional<glm::vec2> vec2(const JsonValue& v, const std::string& path,
                                  const NumberRange& range);
    /// One of @p names; returns its index.
    std::optional<int> choice(const JsonValue& v, const std::string& path,
                              std::span<const std::string_view> names);

private:
    /// Invalid values were reported by the parser; saying more about them would repeat it.
    bool alreadyReported(const JsonValue& v) const { return v.kind == JsonValue::Kind::Invalid; }

    std::string m_file;
    Problems& m_problems;
    size_t m_errors = 0;
};

} // namespace velvet

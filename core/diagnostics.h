#pragma once
/// @file diagnostics.h
/// Problems found while reading a document: each names the file, the JSON path and what is wrong.

#include <string>
#include <vector>

namespace velvet {

struct Problem {
    enum class Severity { Error, Warning };
    Severity severity = Severity::Error;
    std::string file;    ///< the document's path ("" for in-memory text)
    std::string path;    ///< JSON path, e.g. "lobes.base.roughness" ("" for the whole document)
    std::string message; ///< e.g. "expected a number in [0, 1], got \"high\""
    /// "file: path: message" — the one line printed on stderr.
    std::string toString() const;
};

struct Problems {
    std::vector<Problem> items;
    bool hasErrors() const;
    void error(std::string file, std::string path, std::string message);
    void warning(std::string file, std::string path, std::string message);
};

} // namespace velvet

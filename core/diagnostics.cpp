#include "core/diagnostics.h"

#include <algorithm>

namespace velvet {

std::string Problem::toString() const {
    // Empty parts are left out rather than printed as "": an in-memory document has no file, a
    // problem with the whole document (parse error, unreadable file) has no JSON path.
    std::string out;
    for (const std::string* part : {&file, &path}) {
        if (part->empty())
            continue;
        out += *part;
        out += ": ";
    }
    out += message.empty() ? std::string("unknown problem") : message;
    return out;
}

bool Problems::hasErrors() const {
    return std::any_of(items.begin(), items.end(),
                       [](const Problem& p) { return p.severity == Problem::Severity::Error; });
}

void Problems::error(std::string file, std::string path, std::string message) {
    items.push_back(
        {Problem::Severity::Error, std::move(file), std::move(path), std::move(message)});
}

void Problems::warning(std::string file, std::string path, std::string message) {
    items.push_back(
        {Problem::Severity::Warning, std::move(file), std::move(path), std::move(message)});
}

} // namespace velvet

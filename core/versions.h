#pragma once
/// @file versions.h
/// Versions of the libraries core is built against (for `velvet info` and bug reports).

#include <string>
#include <utility>
#include <vector>

namespace velvet {

/// (name, version) of each third-party library core uses, in a stable order.
std::vector<std::pair<std::string, std::string>> dependencyVersions();

} // namespace velvet

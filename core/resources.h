#pragma once
/// @file resources.h
/// Where shaders, schemas, presets and HDRIs live. Lookup order: the VELVET_RESOURCES environment
/// variable, a root set by the application (e.g. a resources/ folder beside the executable), then
/// the source tree's resources/ folder compiled in.

#include <filesystem>

namespace velvet::resources {

/// Sets the root the application found (ignored when VELVET_RESOURCES is set).
void setRoot(const std::filesystem::path& root);
/// The resources root in force.
std::filesystem::path root();
/// root() / relative.
std::filesystem::path path(const std::filesystem::path& relative);

} // namespace velvet::resources

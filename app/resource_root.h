#pragma once
/// @file resource_root.h
/// Finds the resources folder for the running executable.

namespace velvet::app {

/// Looks for resources/ beside the executable, then in the source tree's place relative to a
/// build folder (build/bin/velvet -> ../../resources); sets velvet::resources::setRoot when found.
/// VELVET_RESOURCES still wins (core/resources.h).
void locateResources(const char* argv0);

} // namespace velvet::app

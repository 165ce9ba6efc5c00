#pragma once
/// @file mtlx_graph_export.h
/// The node graph in a MaterialX export (issue 12): an input of the material output whose whole
/// upstream subgraph has MaterialX standard-library counterparts is written as an output of one
/// <nodegraph>, connected to the shader input; any other graph-driven input is baked as before
/// (core/baked_maps.h). The reverse of mtlx::graphCounterpart (core/mtlx_values.h), for the
/// nodes whose semantics match exactly; docs/interchange.md, "The node graph".

#include "core/export_files.h"
#include "core/material.h"

#include <map>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace velvet::mtlx {

/// The graph-driven output inputs ("baseColor", "roughness", …) of @p material that shader
/// @p shaderId ("standard_surface", "open_pbr_surface", "gltf_pbr") reads as one input holding
/// exactly the parameter, whose texture slot is empty, and whose upstream nodes all map. Pure:
/// reads no file.
std::set<std::string> mappableGraphInputs(const Material& material, const std::string& shaderId);

/// The <nodegraph> of mappableGraphInputs(@p material, @p shaderId), one output each.
struct GraphExport {
    std::string xml;                            ///< the element, indented; empty for no inputs
    std::string name;                           ///< the nodegraph's name
    std::map<std::string, std::string> outputs; ///< output input name -> nodegraph output
    std::vector<ExportFile> files;              ///< the graph's images, copied as they are
};

/// Builds it, the images named BASE_graph<node id>.<ext> beside the .mtlx (copied byte for
/// byte). False + one-line @p error when an image file cannot be read.
bool exportGraph(const Material& material, std::string_view baseName, const std::string& shaderId,
                 GraphExport& out, std::string* error);

} // namespace velvet::mtlx

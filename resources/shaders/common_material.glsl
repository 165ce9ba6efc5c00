// The material table, indexed by the material id stored in the G-buffer; its record type is
// generated from render/material_table.h (render/render_interface.cpp).
#include "render_bindings.glsl"

// The record type, GpuMaterial, comes from the generated include (render/material_table.h).
#include "render_interface.glsl"

layout(std430, binding = BINDING_MATERIAL_SSBO) readonly buffer MaterialTable {
    GpuMaterial materials[];
};

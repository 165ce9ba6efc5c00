#version 450 core
// The first half of the tiled path (render/light_passes.h): finds the TILE_SIZE^2 tiles that hold
// at least one mesh pixel and appends them to the active-tile list, whose length is the work-group
// count of light_tiled.comp's indirect dispatch. llvmpipe runs every branch of a shader under a
// lane mask (only loop back-edges branch), so a shading kernel's code costs every 8-lane row it is
// dispatched over, background or not: this cheap pass keeps the background tiles (most of the
// screen) out of the expensive one.
#include "common_gbuffer.glsl"
#include "light_bindings.glsl"

layout(local_size_x = TILE_SIZE, local_size_y = TILE_SIZE) in;
layout(std430, binding = BINDING_LIGHT_TILE_SSBO) buffer TileList {
    uint dispatchX; // DispatchIndirectCommand: num_groups_x (reset to 0 each frame), y, z
    uint dispatchY;
    uint dispatchZ;
    uint padding;
    uint tiles[]; // active tiles, x | y << 16
};
layout(location = LOCATION_TILE_VIEWPORT) uniform ivec2 uSize;

shared uint sAny;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (gl_LocalInvocationIndex == 0u)
        sAny = 0u;
    barrier();
    if (pixel.x < uSize.x && pixel.y < uSize.y && texelFetch(gDepthTex, pixel, 0).r < 1.0)
        sAny = 1u; // any writer wins; all write the same value
    barrier();
    if (gl_LocalInvocationIndex == 0u && sAny != 0u)
        tiles[atomicAdd(dispatchX, 1u)] = gl_WorkGroupID.x | (gl_WorkGroupID.y << 16u);
}

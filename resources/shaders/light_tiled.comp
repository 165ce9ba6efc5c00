#version 450 core
// Tiled light culling and shading in one compute pass (Andersson 2009, "Parallel Graphics in
// Frostbite"; Olsson & Assarsson 2011, "Tiled Shading"): each TILE_SIZE^2 work group finds its
// tile's depth bounds and a 32-bin depth bitmask of the pixels it holds (Harada, McKee & Yang 2012,
// "Forward+"; Harada 2012, "A 2.5D Culling for Forward+"), culls the lights against the tile's
// view-space box and that mask in batches of LIGHT_BATCH (any number of lights, bounded shared
// memory), then each invocation shades its pixel with the batch's list and adds the sum to the
// HDR image. The mask drops lights that fall in the depth gaps of a tile (silhouettes), where a
// min/max range alone keeps everything between the front and the back surface.
// Dispatched indirectly over the tiles light_tile_classify.comp found to hold mesh pixels only.
#include "light_common.glsl"

layout(local_size_x = TILE_SIZE, local_size_y = TILE_SIZE) in;
layout(binding = BINDING_LIGHT_HDR_IMAGE, rgba16f) uniform image2D uHdrImage;
// The tiles with at least one mesh pixel (light_tile_classify.comp): one work group each.
layout(std430, binding = BINDING_LIGHT_TILE_SSBO) readonly buffer TileList {
    uvec4 dispatchArgs;
    uint tiles[];
};

shared uint sMinDepth;
shared uint sMaxDepth;
shared uint sDepthMask;
shared uint sCount;
shared uint sList[LIGHT_BATCH];

vec3 viewFromNdc(vec2 ndcXY, float depth) {
    vec4 p = frame.invProjMatrix * vec4(ndcXY, depth * 2.0 - 1.0, 1.0);
    return p.xyz / p.w;
}

// The bits of the depth bins [zLo, zHi] covers, bins of width 1/scale from zNear (view distance).
uint depthBits(float zLo, float zHi, float zNear, float scale) {
    int b0 = clamp(int((zLo - zNear) * scale), 0, 31);
    int b1 = clamp(int((zHi - zNear) * scale), 0, 31);
    uint upTo = b1 >= 31 ? 0xffffffffu : (1u << uint(b1 + 1)) - 1u;
    return upTo & ~((1u << uint(b0)) - 1u);
}

void main() {
    uint packedTile = tiles[gl_WorkGroupID.x];
    uvec2 tile = uvec2(packedTile & 0xffffu, packedTile >> 16u);
    ivec2 pixel = ivec2(tile * TILE_SIZE + gl_LocalInvocationID.xy);
    ivec2 size = ivec2(frame.viewport.xy);
    bool inside = pixel.x < size.x && pixel.y < size.y;
    uint local = gl_LocalInvocationIndex;
    if (local == 0u) {
        sMinDepth = floatBitsToUint(1.0);
        sMaxDepth = 0u;
        sDepthMask = 0u;
    }
    barrier();
    ShadingPoint p;
    vec4 shadows;
    bool shaded = inside && loadShadingPoint(pixel, p, shadows);
    float depth = shaded ? texelFetch(gDepthTex, pixel, 0).r : 1.0;
    if (shaded) {
        // Non-negative floats order like their bit patterns.
        uint bits = floatBitsToUint(depth);
        atomicMin(sMinDepth, bits);
        atomicMax(sMaxDepth, bits);
    }
    barrier();
    if (sMaxDepth == 0u)
        return; // the whole tile is background (uniform across the group)

    // The tile's view-space bounding box: its four corners at the nearest and farthest depth.
    vec2 tileMin = vec2(tile * TILE_SIZE) * frame.viewport.zw * 2.0 - 1.0;
    vec2 tileMax = vec2((tile + 1u) * TILE_SIZE) * frame.viewport.zw * 2.0 - 1.0;
    float dMin = uintBitsToFloat(sMinDepth), dMax = uintBitsToFloat(sMaxDepth);
    vec3 boxMin = vec3(1e30), boxMax = vec3(-1e30);
    for (int i = 0; i < 8; ++i) {
        vec2 xy = vec2((i & 1) != 0 ? tileMax.x : tileMin.x, (i & 2) != 0 ? tileMax.y : tileMin.y);
        vec3 c = viewFromNdc(xy, (i & 4) != 0 ? dMax : dMin);
        boxMin = min(boxMin, c);
        boxMax = max(boxMax, c);
    }
    // Depth bins between the tile's nearest and farthest view distance (-z).
    float zNear = -boxMax.z, zFar = -boxMin.z;
    float binScale = 32.0 / max(zFar - zNear, 1e-6);
    if (shaded) {
        vec2 ndcXY = (vec2(pixel) + 0.5) * frame.viewport.zw * 2.0 - 1.0;
        float z = -viewFromNdc(ndcXY, depth).z;
        atomicOr(sDepthMask, depthBits(z, z, zNear, binScale));
    }
    barrier();
    uint tileMask = sDepthMask;

    int view = frame.modes.y;
    vec3 sum = vec3(0.0);
    for (int base = 0; base < uLightCount; base += LIGHT_BATCH) {
        if (local == 0u)
            sCount = 0u;
        barrier();
        int batch = min(LIGHT_BATCH, uLightCount - base);
        for (int i = int(local); i < batch; i += TILE_SIZE * TILE_SIZE) {
            GpuLight L = lights[base + i];
            float r = L.positionRange.w;
            vec3 c = (frame.viewMatrix * vec4(L.positionRange.xyz, 1.0)).xyz;
            vec3 d = c - clamp(c, boxMin, boxMax); // sphere vs box (Arvo 1990)
            if (dot(d, d) < r * r &&
                (depthBits(-c.z - r, -c.z + r, zNear, binScale) & tileMask) != 0u)
                sList[atomicAdd(sCount, 1u)] = uint(base + i);
        }
        barrier();
        if (shaded)
            for (uint k = 0u; k < sCount; ++k)
                sum += shadeLocalLight(lights[sList[k]], p, shadows, view);
        barrier();
    }
    if (shaded)
        imageStore(uHdrImage, pixel, imageLoad(uHdrImage, pixel) + vec4(sum, 0.0));
}

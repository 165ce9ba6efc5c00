#version 450 core
// The blurred occlusion (ao_blur.frag) into the fourth channel of the shadow masks, which no
// shadow slot uses when at most three lights cast shadows (render/ao_pass.h, packInto): the
// lighting passes upsample the masks anyway, so the occlusion comes with them at no cost of its
// own (stage_shading.glsl, stageOcclusion). The same texel grid: texel t stands for pixel D t.
//   the mask (location 0)         each texel's own occlusion, which the mask's depth- and
//                                 material-aware upsample reads as it reads the shadows;
//   the ground's mask (location 2) the ground's occlusion, also at the texels where the mesh
//                                 hides the ground (the mean of the ground's texels about them),
//                                 so the catcher's bilinear fetch does not pull the mesh's
//                                 occlusion into the ground's at a silhouette.
// Drawn with every channel but alpha masked off.
#include "gbuffer_read.glsl"
#include "stage_interface.glsl"

layout(binding = BINDING_OCCLUSION_TEX) uniform sampler2D uOcclusion;
layout(location = 0) out vec4 outMask;
layout(location = 2) out vec4 outGroundMask;

bool isGround(ivec2 texel) {
    ivec2 pixel = min(texel * stage.counts.y, ivec2(frame.viewport.xy) - 1);
    int id = readMaterialId(pixel);
    return texelFetch(gDepthTex, pixel, 0).r < 1.0 &&
           (id == GROUND_CATCHER_MATERIAL_ID || id == GROUND_PLAIN_MATERIAL_ID);
}

void main() {
    ivec2 t = ivec2(gl_FragCoord.xy);
    ivec2 last = textureSize(uOcclusion, 0) - 1;
    // The 3x3 about t (k = 4 is t itself): its own occlusion and whether it is the ground's.
    float own = 1.0, ownGround = 0.0, sum = 0.0, count = 0.0;
    for (int k = 0; k < 9; ++k) {
        ivec2 q = clamp(t + ivec2(k % 3 - 1, k / 3 - 1), ivec2(0), last);
        float ground = isGround(q) ? 1.0 : 0.0;
        float occlusion = texelFetch(uOcclusion, q, 0).r;
        sum += ground * occlusion;
        count += ground;
        if (k == 4) {
            own = occlusion;
            ownGround = ground;
        }
    }
    float groundOcclusion = ownGround > 0.5 ? own : count > 0.0 ? sum / count : 1.0;
    outMask = vec4(own);
    outGroundMask = vec4(groundOcclusion);
}

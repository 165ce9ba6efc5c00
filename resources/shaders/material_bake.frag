#version 450 core
// A material's maps baked in UV space for engine texture sets (render/material_bake.h): one
// fragment per texel of the target, uv = its centre, and the values the G-buffer pass computes
// for a surface point with that uv — parameters times their texture slots (atlas regions
// included, through sampleSlot), then the material graph over them — written before lighting,
// as maps. Keep in step with gbuffer.frag (the texture-set tests compare both with the same
// material's known texels); the lobe values come from the same material_lobe_inputs.glsl.
#include "common_material.glsl"
#include "common_material_textures.glsl"
// Generated from the material's node graph (core/graph/graph_compiler.h).
#include "material_graph.glsl"
#include "material_lobe_inputs.glsl"

layout(location = 0) uniform vec2 uSize; // the target's size in texels (uTexRegion is 1..13)

layout(location = 0) out vec4 outBaseColor; // rgb scene-linear base colour, a the slot's alpha
layout(location = 1) out vec4 outNormal;    // xyz unit tangent-space normal (OpenGL, +Y up)
layout(location = 2) out vec4 outOrm;       // occlusion (strength applied), roughness, metallic
layout(location = 3) out vec4 outEmission;  // rgb emission (colour x strength), scene-linear
layout(location = 4) out vec4 outCoat;      // clearcoat weight, clearcoat roughness
layout(location = 5) out vec4 outSheen;     // rgb sheen weight x colour (linear), a roughness
layout(location = 6) out vec4 outSpecular;  // rgb specular colour (linear), a specular weight
layout(location = 7) out vec4 outAnisotropy; // xy direction (rotation applied), z strength

void main() {
    // Texel centres; row 0 of the target (read back first) is v = 0.5 / height, the image's top
    // row in glTF's UV convention, which Velvet's texture uploads follow (row 0 at t = 0).
    vec2 uv = gl_FragCoord.xy / uSize;
    GpuMaterial m = materials[0];
    vec3 baseColor = m.baseColorMetallic.rgb;
    float alpha = 1.0;
    float metallic = m.baseColorMetallic.a;
    float roughness = m.roughIorOcclusionNormal.x;
    if (hasTexture(m, TEX_BASE_COLOR)) {
        vec4 t = sampleSlot(m, TEX_BASE_COLOR, uv);
        alpha = t.a;
        baseColor *= t.rgb;
    }
    if (hasTexture(m, TEX_METALLIC_ROUGHNESS)) {
        vec4 t = sampleSlot(m, TEX_METALLIC_ROUGHNESS, uv);
        roughness *= t.g;
        metallic *= t.b;
    }
    if (hasTexture(m, TEX_SPEC_ROUGH_METAL)) {
        vec4 t = sampleSlot(m, TEX_SPEC_ROUGH_METAL, uv);
        roughness *= t.g;
        metallic *= t.b;
    }
    MaterialInputs inputs = velvetGraphDefaults();
    inputs.baseColor = baseColor;
    inputs.metallic = metallic;
    inputs.roughness = roughness;
    inputs.normalScale = m.roughIorOcclusionNormal.w;
    inputs.occlusionStrength = m.roughIorOcclusionNormal.z;
    inputs.occlusion = hasTexture(m, TEX_OCCLUSION) ? sampleSlot(m, TEX_OCCLUSION, uv).r : 1.0;
    inputs.emissionColor =
        m.emissive.rgb * (hasTexture(m, TEX_EMISSIVE) ? sampleSlot(m, TEX_EMISSIVE, uv).rgb : vec3(1.0));
    inputs.emissionStrength = m.emissive.a;
    if (hasTexture(m, TEX_NORMAL))
        inputs.normal = sampleSlot(m, TEX_NORMAL, uv).xyz * 2.0 - 1.0;
    readLobeInputs(m, uv, inputs);
    velvetGraph(uv, inputs);
    // glTF's scaled normal, normalize((t * 2 - 1) * (s, s, 1)), as the G-buffer pass applies it.
    vec3 tn = inputs.normal;
    tn.xy *= inputs.normalScale;
    tn = dot(tn, tn) > 1e-12 ? normalize(tn) : vec3(0.0, 0.0, 1.0);
    float occlusion = 1.0 + inputs.occlusionStrength * (inputs.occlusion - 1.0);
    outBaseColor = vec4(max(inputs.baseColor, vec3(0.0)), clamp(alpha, 0.0, 1.0));
    outNormal = vec4(tn, 1.0);
    outOrm = vec4(clamp(occlusion, 0.0, 1.0), clamp(inputs.roughness, 0.0, 1.0),
                  clamp(inputs.metallic, 0.0, 1.0), 1.0);
    outEmission = vec4(max(inputs.emissionColor * inputs.emissionStrength, vec3(0.0)), 1.0);
    outCoat = vec4(clamp(inputs.clearcoatWeight, 0.0, 1.0), clamp(inputs.clearcoatRoughness, 0.0, 1.0),
                   0.0, 1.0);
    outSheen = vec4(clamp(inputs.sheenWeight * inputs.sheenColor, 0.0, 1.0),
                    clamp(inputs.sheenRoughness, 0.0, 1.0));
    outSpecular = vec4(max(inputs.specularColor, vec3(0.0)), clamp(inputs.specularWeight, 0.0, 1.0));
    // KHR_materials_anisotropy's direction turned by the rotation (counter-clockwise, tangent
    // towards bitangent), as gbuffer.frag turns it; a texture set carries no separate rotation.
    float r = radians(inputs.anisotropyRotation);
    vec2 d = mat2(cos(r), sin(r), -sin(r), cos(r)) * inputs.anisotropyDirection;
    d = dot(d, d) > 1e-12 ? normalize(d) : vec2(1.0, 0.0);
    outAnisotropy = vec4(d, clamp(inputs.anisotropyStrength, 0.0, 1.0), 1.0);
}

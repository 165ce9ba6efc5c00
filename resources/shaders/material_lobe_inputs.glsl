// The lobe values a surface point with texture coordinates uv starts from, before the material
// graph: each parameter times its texture channel, as glTF multiplies factors and textures
// (KHR_materials_sheen: colour RGB, roughness A; _clearcoat: weight R, roughness G; _specular:
// weight A, colour RGB; _anisotropy: direction RG, strength B). One copy for the G-buffer pass
// (gbuffer.frag) and the texture-set bake (material_bake.frag), so both read the same values.
// Needs common_material.glsl, common_material_textures.glsl and material_graph.glsl first.
void readLobeInputs(GpuMaterial m, vec2 uv, inout MaterialInputs inputs) {
    inputs.sheenWeight = m.sheenWeightAnisotropy.x;
    inputs.sheenColor = m.sheenColorRoughness.rgb;
    if (hasTexture(m, TEX_SHEEN_COLOR))
        inputs.sheenColor *= sampleSlot(m, TEX_SHEEN_COLOR, uv).rgb;
    inputs.sheenRoughness = m.sheenColorRoughness.a;
    if (hasTexture(m, TEX_SHEEN_ROUGHNESS)) // KHR_materials_sheen: roughness in A
        inputs.sheenRoughness *= sampleSlot(m, TEX_SHEEN_ROUGHNESS, uv).a;
    inputs.clearcoatWeight = m.clearcoat.x;
    if (hasTexture(m, TEX_CLEARCOAT)) // KHR_materials_clearcoat: R
        inputs.clearcoatWeight *= sampleSlot(m, TEX_CLEARCOAT, uv).r;
    inputs.clearcoatRoughness = m.clearcoat.y;
    if (hasTexture(m, TEX_CLEARCOAT_ROUGHNESS)) // G
        inputs.clearcoatRoughness *= sampleSlot(m, TEX_CLEARCOAT_ROUGHNESS, uv).g;
    inputs.clearcoatNormalScale = m.clearcoat.z;
    if (hasTexture(m, TEX_CLEARCOAT_NORMAL))
        inputs.clearcoatNormal = sampleSlot(m, TEX_CLEARCOAT_NORMAL, uv).xyz * 2.0 - 1.0;
    inputs.specularWeight = m.specularColorWeight.a;
    if (hasTexture(m, TEX_SPECULAR)) // KHR_materials_specular: A
        inputs.specularWeight *= sampleSlot(m, TEX_SPECULAR, uv).a;
    if (hasTexture(m, TEX_SPEC_ROUGH_METAL)) // the seeds' atlas: R specular
        inputs.specularWeight *= sampleSlot(m, TEX_SPEC_ROUGH_METAL, uv).r;
    inputs.specularColor = m.specularColorWeight.rgb;
    if (hasTexture(m, TEX_SPECULAR_COLOR))
        inputs.specularColor *= sampleSlot(m, TEX_SPECULAR_COLOR, uv).rgb;
    inputs.anisotropyStrength = m.sheenWeightAnisotropy.y;
    inputs.anisotropyRotation = degrees(m.sheenWeightAnisotropy.z);
    if (hasTexture(m, TEX_ANISOTROPY)) { // KHR_materials_anisotropy: RG direction, B strength
        vec3 a = sampleSlot(m, TEX_ANISOTROPY, uv).rgb;
        inputs.anisotropyDirection = a.rg * 2.0 - 1.0;
        inputs.anisotropyStrength *= a.b;
    }
}

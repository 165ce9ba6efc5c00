// The layered BRDF of shadeDirectional() (common_brdf.glsl) split into its lobes, for area lights
// (a diffuse and a specular light direction, Karis 2013's representative point) and for the
// lobe debug views. For one direction and no widening, diffuse + specular + sheen + clearcoat
// equals shadeDirectional(); the C++ twin of the sum is velvet::brdf::evalDirectional().
#include "common_brdf.glsl"
#include "debug_views.glsl"

struct Lobes {
    vec3 diffuse;   // (1 - metallic) (1 - F) diffuse, sheen- and coat-attenuated
    vec3 specular;  // base specular (dielectric + metal), sheen- and coat-attenuated
    vec3 sheen;     // KHR_materials_sheen lobe, coat-attenuated
    vec3 clearcoat; // KHR_materials_clearcoat lobe
};

// Karis 2013, "Real Shading in Unreal Engine 4" (energy normalization of a widened lobe:
// (alpha / alpha')^2, alpha' = saturate(alpha + sourceRadius / (2 distance)))
float areaSpecularNormalization(float alpha, float widen) {
    float ratio = alpha / max(saturate(alpha + widen), 1e-6);
    return ratio * ratio;
}

// lDiffuse: unit direction to the light for diffuse and sheen; lSpecular: unit direction to the
// representative point for the specular lobes; widen: sourceRadius / (2 distance), 0 for punctual
// lights. Each lobe includes its n.l.
Lobes shadeLobes(Surface s, vec3 n, vec3 v, vec3 lDiffuse, vec3 lSpecular, float widen) {
    Lobes o;
    o.diffuse = o.specular = o.sheen = o.clearcoat = vec3(0.0);
    float NdotV = max(dot(n, v), 1e-4);
    float rough = max(s.roughness, MIN_ROUGHNESS);
    float alpha = rough * rough;
    float fc = s.clearcoat > 0.0
                   ? s.clearcoat * fresnelSchlick(0.04, 1.0, max(dot(s.clearcoatNormal, v), 1e-4))
                   : 0.0;
    float coatAttenuation = 1.0 - fc;
    bool hasSheen = max3(s.sheenColor) > 0.0;
    float sheenAlbedoV = hasSheen ? sheenDirectionalAlbedo(NdotV, s.sheenRoughness, s.sheenModel) : 0.0;

    float NdotLd = dot(n, lDiffuse);
    if (NdotLd > 0.0) {
        vec3 h = normalize(lDiffuse + v);
        float VdotH = saturate(dot(v, h));
        vec3 fDielectric =
            s.specularWeight * fresnelDielectric(s.terms.z, dielectricF0(s), s.ior, VdotH);
        vec3 diffuseLobe = diffuse(s.terms.w, s.baseColor, rough, NdotLd, NdotV, VdotH);
        float scaling = 1.0;
        if (hasSheen) {
            scaling = min(1.0 - max3(s.sheenColor) * sheenAlbedoV,
                          1.0 - max3(s.sheenColor) * sheenDirectionalAlbedo(NdotLd, s.sheenRoughness, s.sheenModel));
            float NdotH = saturate(dot(n, h));
            float sheen = distributionCharlie(NdotH, sinSquared(n, h), s.sheenRoughness) *
                          visibilitySheen(s.sheenModel, NdotLd, NdotV, s.sheenRoughness);
            o.sheen = s.sheenColor * sheen * coatAttenuation * NdotLd;
        }
        o.diffuse = (1.0 - s.metallic) * (1.0 - max3(fDielectric)) * diffuseLobe * scaling *
                    coatAttenuation * NdotLd;
    }

    float NdotL = dot(n, lSpecular);
    if (NdotL > 0.0) {
        vec3 h = normalize(lSpecular + v);
        float NdotH = saturate(dot(n, h));
        float sin2H = sinSquared(n, h);
        float VdotH = saturate(dot(v, h));
        float specular = specularDV(s, n, v, lSpecular, h, NdotL, NdotV, NdotH, sin2H, VdotH, alpha) *
                         areaSpecularNormalization(alpha, widen);
        vec3 fDielectric =
            s.specularWeight * fresnelDielectric(s.terms.z, dielectricF0(s), s.ior, VdotH);
        vec3 fMetal = fresnelConductor(s.terms.z, s.baseColor, VdotH);
        float scaling = 1.0;
        if (hasSheen)
            scaling = min(1.0 - max3(s.sheenColor) * sheenAlbedoV,
                          1.0 - max3(s.sheenColor) * sheenDirectionalAlbedo(NdotL, s.sheenRoughness, s.sheenModel));
        // Turquin 2019's multiple-scattering energy (common_brdf.glsl), per F0.
        o.specular = mix(fDielectric * multipleScatteringFactor(dielectricF0(s), NdotV, rough),
                         fMetal * multipleScatteringFactor(s.baseColor, NdotV, rough), s.metallic) *
                     specular * scaling * coatAttenuation * NdotL;
        if (s.clearcoat > 0.0) {
            // Through the coat's own normal (KHR_materials_clearcoat); n when it has none.
            float cr = max(s.clearcoatRoughness, MIN_ROUGHNESS);
            o.clearcoat = vec3(s.clearcoat * clearcoatLobe(s, s.clearcoatNormal, v, lSpecular,
                                                           areaSpecularNormalization(cr * cr, widen)));
        }
    }
    return o;
}

// The lobe a debug view shows (debug_views.glsl), or their sum for the final image.
vec3 selectLobes(Lobes o, int view) {
    if (view == DEBUG_DIFFUSE_ONLY)
        return o.diffuse;
    if (view == DEBUG_SPECULAR_ONLY)
        return o.specular + o.sheen + o.clearcoat;
    if (view == DEBUG_BASE_SPECULAR)
        return o.specular;
    if (view == DEBUG_SHEEN_ONLY)
        return o.sheen;
    if (view == DEBUG_CLEARCOAT_ONLY)
        return o.clearcoat;
    return o.diffuse + o.specular + o.sheen + o.clearcoat;
}

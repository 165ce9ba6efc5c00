#version 450 core
// Full-screen lighting: reads the G-buffer, reconstructs the position from depth, adds the
// directional lights, ambient lights and the environment (SH9 diffuse + GGX-prefiltered cube and
// DFG LUT specular); debug views write raw values.
//
// Built in variants (render/renderer.cpp, one program each, so that a pixel pays only for the
// code of its own variant; llvmpipe runs both sides of every branch):
//   LIGHTING_BACKGROUND     the background only; drawn where the G-buffer depth is the far plane
//                           (or, with BACKGROUND_DOWNSAMPLE, everywhere in a smaller target;
//                           with BACKGROUND_EQUIRECT, its dome's cache)
//   LIGHTING_LOBE_VIEWS     surfaces, the lobe views and lights per pixel
//   LIGHTING_GBUFFER_VIEWS  surfaces, the G-buffer views (albedo .. material id)
//   LIGHTING_CATCHER        the shadow-catching ground only, per BACKGROUND_MODE (docs/shadows.md)
//   STAGE_GROUND_CATCHER    (with the final image) discards the catcher's pixels
//   STAGE_GROUND_PLAIN      (with the final image and BACKGROUND_MODE) the plain ground's fade
//   (none of them)          surfaces, the final image
// Each surface variant of the final image is also built specialised to the frame's features
// (FIXED_<TERM>, WITH_<LOBE>, FIXED_IBL_BAKED...: render/lighting_features.h).
// The surface variants are drawn only where there is geometry (depth test against the G-buffer
// depth, the full-screen triangle at the far plane: fullscreen.vert's FULLSCREEN_FAR_PLANE).
// Emission is already in the HDR target (gbuffer.frag writes it per pixel): the surface variants
// blend as result = outColor.rgb + target.rgb * outColor.a (glBlendFuncSeparate(ONE, SRC_ALPHA,
// ZERO, ONE) in renderer.cpp), so alpha is how much of the emission stays: 1 - the clearcoat's
// Fresnel in the final image, 0 in debug views (their value replaces it), 1 in the emissive view.
#include "gbuffer_read.glsl"
#include "common_environment.glsl"
#include "light_lobes.glsl"
#include "stage_shading.glsl"
#include "common_occlusion.glsl"
#include "screen_space_reflection.glsl"

layout(location = 0) out vec4 outColor;

// LIGHTING_INLINE_POST (the final image's background and surfaces, no emission): the display
// step — the post chain's one fused pass, or the built-in tone curve — compiled in as the
// generated include's `vec4 postInline(vec4 linear, ivec2 px)`, so the lit colour goes to the
// display target without the HDR target and a full-screen pass of its own (issue 16).
// Included outside the #if: a driver ignores #line directives in a skipped group, so an include
// inside one would shift every later line of this file in error messages.
#include "inline_post.glsl"
#if defined(LIGHTING_INLINE_POST)
vec4 finalColorAt(vec3 linear, float alpha, ivec2 pixel) {
    return postInline(vec4(linear, 1.0), pixel);
}
#else
vec4 finalColorAt(vec3 linear, float alpha, ivec2 pixel) { return vec4(linear, alpha); }
#endif
vec4 finalColor(vec3 linear, float alpha) {
    return finalColorAt(linear, alpha, ivec2(gl_FragCoord.xy));
}

vec3 background(vec2 ndcXY) {
    vec3 dirView = frame.cameraPosition.w > 0.5
                       ? vec3(0.0, 0.0, -1.0)
                       : normalize(viewPositionFromDepth(ndcXY, 1.0));
    vec3 dir = normalize((frame.invViewMatrix * vec4(dirView, 0.0)).xyz);
    return backgroundRadiance(dir, gl_FragCoord.xy * frame.viewport.w); // common_environment.glsl
}

#if defined(LIGHTING_BACKGROUND)
// BACKGROUND_DOWNSAMPLE n: drawn into a target n times smaller each way
// (render/background_downsample.h), each texel standing for the full-resolution point at the
// centre of its n x n pixels (the frame block's viewport stays the full frame's).
#if defined(BACKGROUND_DOWNSAMPLE)
const float BACKGROUND_SCALE = float(BACKGROUND_DOWNSAMPLE);
#else
const float BACKGROUND_SCALE = 1.0;
#endif
#if defined(BACKGROUND_EQUIRECT)
// BACKGROUND_EQUIRECT n: the background's cache for its dome (render/background_dome.h), n x n
// texels per texel of the environment's equirect: the display value in the direction at the texel's
// centre (the inverse of equirectUv, then of toEnvironment), which the display step must not
// vary by the pixel's position (the caller's rule).
void main() {
    vec2 uv = gl_FragCoord.xy / (float(BACKGROUND_EQUIRECT) * vec2(textureSize(uEnvironment, 0)));
    float theta = PI * uv.y, phi = 2.0 * PI * (uv.x - 0.5);
    vec3 e = vec3(sin(phi) * sin(theta), cos(theta), -cos(phi) * sin(theta));
    float c = frame.envParams.x, s = frame.envParams.y;
    vec3 dir = vec3(c * e.x + s * e.z, e.y, -s * e.x + c * e.z);
    outColor = finalColorAt(backgroundRadiance(dir, uv), 1.0, ivec2(gl_FragCoord.xy));
}
#else
void main() {
    vec2 fragCoord = gl_FragCoord.xy * BACKGROUND_SCALE;
    vec2 ndcXY = fragCoord * frame.viewport.zw * 2.0 - 1.0;
    outColor = finalColorAt(background(ndcXY), 1.0, ivec2(fragCoord));
}
#endif
#elif defined(LIGHTING_CATCHER)
// The shadow catcher's pixels only (stage_shading.glsl): the background times how much of the
// light the ground receives. Every other pixel is discarded first, so it costs them nothing.
void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    if (readMaterialId(pixel) != GROUND_CATCHER_MATERIAL_ID)
        discard;
    vec2 ndcXY = gl_FragCoord.xy * frame.viewport.zw * 2.0 - 1.0;
    vec3 posView = viewPositionFromDepth(ndcXY, texelFetch(gDepthTex, pixel, 0).r);
    vec3 posWorld = (frame.invViewMatrix * vec4(posView, 1.0)).xyz;
    vec4 shadows = groundShadowMask(pixel);
    float ssao = stageOcclusion(shadows, pixel, -posView.z);
    outColor = vec4(background(ndcXY) * catcherTransmission(posWorld, ssao, shadows), 1.0);
}
#else
void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    int view = frame.modes.y;
#if defined(STAGE_GROUND_CATCHER)
    // The catcher has its own variant (above); discarded pixels skip the rest on llvmpipe too.
    if (readMaterialId(pixel) == GROUND_CATCHER_MATERIAL_ID)
        discard;
#endif
    // Drawn only where there is geometry (see the header), so the depth is never the far plane.
    ShadingPoint p = readShadingPoint(pixel, texelFetch(gDepthTex, pixel, 0).r);
    Surface s = p.s;
    vec3 n = p.n;
    vec3 v = p.v;
    vec3 posView = p.posView;
    float occlusion = p.occlusion;
    // Every shadow slot's visibility here, upsampled once (shadow_mask.glsl); the plain ground's
    // fade into the catcher reads the local lights' slots too.
#if defined(STAGE_GROUND_PLAIN)
    vec4 shadows = frameShadowMask(pixel, -posView.z, p.materialId);
#else
    vec4 shadows = surfaceShadowMask(pixel, -posView.z, p.materialId);
#endif

#if defined(LIGHTING_LOBE_VIEWS)
    {
        // Directional lights through one lobe; light_passes adds the other lights.
        vec3 lobes = vec3(0.0);
        for (int i = 0; i < directionalLightCount() && view != DEBUG_LIGHTS_PER_PIXEL; ++i) {
            vec3 l = frame.lightDirection[i].xyz;
            lobes += selectLobes(shadeLobes(s, n, v, l, l, 0.0), view) * frame.lightRadiance[i].rgb *
                     directionalShadow(i, shadows) * geometricHorizon(p, l, 0.0);
        }
        outColor = vec4(lobes, 0.0); // alpha 0: replaces the emission (see the header)
    }
#elif defined(LIGHTING_GBUFFER_VIEWS)
    {
        vec3 value = view == DEBUG_ALBEDO      ? s.baseColor
                     : view == DEBUG_NORMAL    ? n
                     : view == DEBUG_DEPTH     ? vec3(-posView.z)
                     : view == DEBUG_ROUGHNESS ? vec3(s.roughness)
                     : view == DEBUG_METALLIC  ? vec3(s.metallic)
                     : view == DEBUG_POSITION  ? p.posWorld
                     : view == DEBUG_SPECULAR  ? s.specularColor * s.specularWeight
                     : view == DEBUG_CLEARCOAT ? vec3(s.clearcoat, s.clearcoatRoughness, 0.0)
                     : view == DEBUG_SHEEN     ? s.sheenColor
                     : view == DEBUG_OCCLUSION ? vec3(occlusion * stageOcclusion(shadows, pixel, -posView.z))
                     : view == DEBUG_EMISSIVE  ? vec3(0.0)
                     : view == DEBUG_ANISOTROPY ? s.anisotropyDirection * s.anisotropyStrength
                     : view == DEBUG_SPECULAR_OCCLUSION
                         ? vec3(p.specularOcclusion * stageOcclusion(shadows, pixel, -posView.z))
                                               : vec3(float(p.materialId));
        // Alpha 0 replaces the emission the geometry pass wrote; the emissive view keeps it
        // (alpha 1, nothing added): the per-pixel emission itself.
        outColor = vec4(value, view == DEBUG_EMISSIVE ? 1.0 : 0.0);
    }
#else

    // The stage (stage_shading.glsl): screen-space occlusion of the environment's light.
    float ssao = stageOcclusion(shadows, pixel, -posView.z);
    vec2 ndcXY = gl_FragCoord.xy * frame.viewport.zw * 2.0 - 1.0;

    // The sheen's albedo along the view: every light's scaling and the image-based sheen read it.
    float NdotV = max(dot(n, v), 1e-4);
#if WITH_SHEEN
    float sheenAlbedoV = sheenDirectionalAlbedo(NdotV, s.sheenRoughness, s.sheenModel);
#else
    float sheenAlbedoV = 0.0;
#endif

    // Direct light, shadowed by the lights' shadow maps (the shadow mask, shadow_mask.glsl).
    vec3 color = vec3(0.0);
    // A bent shading normal takes no light from below the surface (geometricHorizon).
    for (int i = 0; i < directionalLightCount(); ++i)
        color += shadeDirectional(s, n, v, frame.lightDirection[i].xyz, sheenAlbedoV) *
                 frame.lightRadiance[i].rgb *
                 directionalShadow(i, shadows) * geometricHorizon(p, frame.lightDirection[i].xyz, 0.0);

    // Ambient (common_environment.glsl): SH9 irradiance for the diffuse lobes, times the chosen
    // diffuse term's directional albedo (common_brdf.glsl: 1 for Lambert, tabulated for Burley);
    // the split sum for the specular ones, the GGX-prefiltered cube times the DFG LUT with
    // Fdez-Aguera 2019's multiple-scattering energy (or the approximate path while the bake is
    // incomplete).
    vec3 surroundings = irradianceOverPi(n);
    vec3 irradiance = surroundings;
    vec3 r = reflect(-v, n);
    float rough = max(s.roughness, MIN_ROUGHNESS);
    irradiance *= diffuseDirectionalAlbedo(s.terms.w, NdotV, rough);
#if WITH_GEOMETRIC_HORIZON
    // A bent normal's cosine lobe clipped by the geometric horizon: under uniform light the part
    // above it gathers (1 + n.ng) / 2 of the whole lobe's light, as the path tracer, which takes
    // none from below a hit's face, sees it (BENCHMARKS.md, "Interreflection in the occlusion").
    if (p.bentShading)
        irradiance *= 0.5 * (1.0 + dot(n, p.ng));
#endif
    vec2 ab = environmentDfg(NdotV, rough);
    vec3 specDielectric = s.specularWeight * specularAlbedo(dielectricF0(s), ab);
    vec3 specMetal = specularAlbedo(s.baseColor, ab);
    // The base's reflected environment light: an isotropic base's split sum, its lookup narrowed at
    // grazing angles (reflectedRadiance); an anisotropic base's sweep along its stretch, which
    // weighs its own Fresnel, masking and energy (anisotropicReflection).
    vec3 specular;
    // A frame with time to spare (the viewport at rest, a supersampled still) samples a glossy
    // lobe, whose shape at grazing angles and stretch are then its own (sampledReflection).
    bool sampled = reflectionSamplesThisFrame() > 0 && rough <= SAMPLED_REFLECTION_MAX_ROUGHNESS;
    if (sampled || usesAnisotropy(s)) {
        SweptReflection sw;
        if (sampled) {
#if WITH_GEOMETRIC_HORIZON
            vec3 face = p.bentShading ? p.ng : n;
#else
            vec3 face = n;
#endif
            bool stretched = usesAnisotropy(s);
            vec3 t = stretched ? s.anisotropyDirection : incidencePlaneTangent(n, v, NdotV);
            vec2 alpha =
                stretched ? anisotropicAlphas(rough, s.anisotropyStrength) : vec2(rough * rough);
            sw = sampledReflection(n, face, t, v, NdotV, alpha, s.terms.y, gl_FragCoord.xy);
        } else {
            sw = anisotropicReflection(s, n, v, NdotV, rough);
        }
        specular = mix(s.specularWeight * sweptSpecular(sw, dielectricF0(s), ab),
                       sweptSpecular(sw, s.baseColor, ab), s.metallic);
    } else {
        specular = mix(specDielectric, specMetal, s.metallic) * reflectedRadiance(r, NdotV, rough);
    }
#if WITH_GEOMETRIC_HORIZON
    // A bent normal's reflection may point below the surface, where no light comes from: faded
    // out as it sinks (Russell 2016, "Horizon Occlusion for Normal Mapped Reflections"; Filament's
    // specular horizon occlusion). Measured against the reference: BENCHMARKS.md, "Light from
    // below the surface".
    if (p.bentShading && !sampled) { // a sampled lobe drops its samples below the face itself
        float horizon = saturate(1.0 + dot(r, p.ng));
        specular *= horizon * horizon;
    }
#endif
    // The diffuse and specular parts each under their own occlusion (gbuffer.frag: the
    // material's occlusion, and the mesh's visibility from itself where it has one).
    float diffuseOcclusion = p.occlusion, specularOcclusion = p.specularOcclusion;
    // What the occlusion hides of the lobe is the surface itself, which reflects the environment
    // too: no black, but the light it sends back (meshReflection), so a white metal's cavities stay
    // white in a white furnace as the path tracer's do.
    vec3 specularAlbedoMix = mix(specDielectric, specMetal, s.metallic);
    vec3 diffuseAlbedo = (1.0 - s.metallic) * (1.0 - max3(specDielectric)) * s.baseColor;
    vec3 hiddenLight = meshReflection(surroundings, diffuseAlbedo + specularAlbedoMix);
    vec3 reflected = specular * specularOcclusion +
                     specularAlbedoMix * (1.0 - specularOcclusion) * hiddenLight;
    // The diffuse light: the environment's under the occlusions (the screen-space one applied
    // with the rest of the ambient light below), or, traced, outside them.
    vec3 diffuseLight = irradiance * diffuseOcclusion;
    vec3 tracedDiffuse = vec3(0.0);
#if WITH_SCREEN_SPACE_REFLECTIONS
    // Where this pixel's rays meet the mesh, the mesh's own light in place of the environment's
    // (screen_space_reflection.glsl), through the lobe's albedo. Its misses keep the occluded
    // environment: the mesh may still hide it off screen or behind itself.
#if WITH_SAMPLED_REFLECTIONS // a frame whose lobes are all rougher compiles the rays out
    {
        bool stretched = usesAnisotropy(s);
        vec3 t = stretched ? s.anisotropyDirection : incidencePlaneTangent(n, v, NdotV);
        vec2 alpha = stretched ? anisotropicAlphas(rough, s.anisotropyStrength) : vec2(rough * rough);
        // Every glossy pixel, also where the mesh's visibility finds the lobe open: its cone
        // model misses parts of the mesh the rays meet (gated to the occluded pixels, the
        // gold ball under the rig read 9.96 mean ΔE2000 against 9.28, for 45 instead of 74 ms
        // added to a 290 ms 1280x720 refinement frame of the copper ball on its stage). A
        // rougher lobe keeps its sampled reflection: no rays, a loop run no times, which
        // llvmpipe skips for a whole block (it runs both sides of an `if`).
        int rays = rough <= SAMPLED_REFLECTION_MAX_ROUGHNESS ? screenSpaceReflectionRays() : 0;
        reflected = tracedReflection(p, t, alpha, NdotV, pixel, rays, specularAlbedoMix, reflected);
    }
#endif
    {
        // The diffuse light traced too (screenSpaceGather): cosine-distributed rays about the
        // face; those that meet the mesh bring its light (the key light's on the ring, which no
        // occlusion can give back), the others the environment's irradiance. The rays find the
        // mesh's parts that the screen-space occlusion finds, so it does not darken this light
        // again (tracedDiffuse is kept out of it below).
        int rays = screenSpaceReflectionRays();
        vec3 gathered = vec3(0.0);
        float hits = 0.0;
        for (int i = 0; i < rays; ++i) {
            vec4 hit = screenSpaceGather(p, pixel, i);
            gathered += hit.rgb;
            hits += hit.a;
        }
        tracedDiffuse = diffuseAlbedo * (diffuseLight * (float(rays) - hits) + gathered) / float(rays);
        diffuseLight = vec3(0.0);
    }
#endif
    vec3 ambient = diffuseAlbedo * diffuseLight + reflected;
#if WITH_SHEEN // (common_brdf.glsl's specialisation)
    if (max3(s.sheenColor) > 0.0) {
        // The sheen model's own albedo scales the layers below it; the lobe itself is lit by the
        // irradiance about its mean direction (sheenLightDirection) times that albedo, or at rest
        // sampled: not the prefiltered radiance along the reflection at the sheen roughness
        // (Filament's evaluateSheenIBL), which lit velvet with a lamp highlight its lobe does not
        // have.
        float e = sheenAlbedoV;
        vec3 sheenLight; // the lobe's light for a white sheen
#if WITH_SAMPLED_REFLECTIONS
        // At rest the lobe itself is sampled (sampledSheenLight), its samples clipped by the face.
        if (reflectionSamplesThisFrame() > 0) {
            sheenLight = sampledSheenLight(n, p.ng, v, NdotV, s.sheenRoughness, s.sheenModel,
                                           gl_FragCoord.xy);
        } else
#endif
        {
            vec3 sheenDirection = sheenLightDirection(n, v, NdotV, s.sheenRoughness);
            sheenLight = e * irradianceOverPi(sheenDirection);
#if WITH_GEOMETRIC_HORIZON
            // Under a bent normal the face's horizon cuts the lobe too: of a cosine lobe about d,
            // the share above a plane through its origin with normal m is (1 + d.m) / 2 under
            // uniform light. The lobe's model was fitted about n (sheenLightDirection), which the
            // shading normal's own horizon already bounds, so what the face takes away is the share
            // above ng over the share above n (1 where n = ng): a knit's loops and a crushed pile's
            // tilted fibres, which face away from the face, lose the light from below it that the
            // path tracer never gives them (BENCHMARKS.md, "The sheen under the face's horizon").
            if (p.bentShading)
                sheenLight *= saturate((1.0 + dot(sheenDirection, p.ng)) /
                                       max(1.0 + dot(sheenDirection, n), 1e-4));
#endif
        }
        ambient = ambient * (1.0 - max3(s.sheenColor) * e) +
                  s.sheenColor * sheenLight * diffuseOcclusion;
        tracedDiffuse *= 1.0 - max3(s.sheenColor) * e;
    }
#endif
    float keepEmission = 1.0; // KHR_materials_clearcoat: emission seen through the coat's Fresnel
#if WITH_CLEARCOAT
    if (s.clearcoat > 0.0) {
        // Through the coat's own normal (KHR_materials_clearcoat; the base's unless it has one).
        vec3 nc = s.clearcoatNormal;
        float NdotVc = max(dot(nc, v), 1e-4);
        float cr = max(s.clearcoatRoughness, MIN_ROUGHNESS);
        vec2 abc = environmentDfg(NdotVc, cr);
        float fc = s.clearcoat * fresnelSchlick(0.04, 1.0, NdotVc);
        tracedDiffuse *= 1.0 - fc;
        // As the base's reflection (above): what the occlusion hides of the coat's lobe is the
        // surface itself, which sends back its own light (meshReflection), not black: a glazed
        // ceramic's coat under the shader ball's ring mirrors the lit ball, as the path tracer's
        // does (BENCHMARKS.md, "The coat reflects the mesh").
        vec3 coatReflected = reflectedRadiance(reflect(-v, nc), NdotVc, cr) * specularOcclusion +
                             (1.0 - specularOcclusion) * hiddenLight;
#if WITH_SCREEN_SPACE_REFLECTIONS && WITH_SAMPLED_REFLECTIONS
        {
            // And traced where the base's reflection is (its rays above): GGX visible normals of
            // the coat's lobe about its own normal, the mesh's light where they meet it.
            ShadingPoint coat = p;
            coat.n = nc;
            int rays = cr <= SAMPLED_REFLECTION_MAX_ROUGHNESS ? screenSpaceReflectionRays() : 0;
            coatReflected = tracedReflection(coat, incidencePlaneTangent(nc, v, NdotVc),
                                             vec2(cr * cr), NdotVc, pixel, rays, vec3(1.0),
                                             coatReflected);
        }
#endif
        ambient = ambient * (1.0 - fc) + s.clearcoat * (0.04 * abc.x + abc.y) * coatReflected;
        keepEmission = 1.0 - fc;
    }
#endif
    // The screen-space occlusion with the light its cavity's walls bounce back (Jimenez et al.
    // 2016's multiple-bounce fit, common_occlusion.glsl): the path tracer's interreflection, which
    // a bare visibility leaves out (BENCHMARKS.md, "Interreflection in the occlusion").
#if WITH_OCCLUSION
    color += ambient * multiBounceOcclusion(ssao, s.baseColor) + tracedDiffuse;
#else
    color += ambient + tracedDiffuse;
#endif
#if defined(STAGE_GROUND_PLAIN)
    if (p.materialId == GROUND_PLAIN_MATERIAL_ID) // the plain ground fades into the catcher
        color = mix(color, background(ndcXY) * catcherTransmission(p.posWorld, ssao, shadows),
                    groundFade(p.posWorld));
#endif
    outColor = finalColor(color, keepEmission); // + emission x alpha, by the blend (the header)
#endif
}
#endif // LIGHTING_BACKGROUND

#pragma once
/// @file lighting_features.h
/// What the full-screen lighting pass must be able to shade this frame, so that its program can
/// be specialised to it (issue 16, docs/architecture.md "Lighting variants").
///
/// llvmpipe (and any SIMD shader core when lanes disagree) runs both sides of every branch, so a
/// lighting shader that can shade every BRDF term choice, every lobe, shadows and occlusion pays
/// for all of them at every pixel even when the frame's one material is a plain GGX velvet. The
/// features are read off what the frame really draws — the material records in the table (their
/// term choices, lobe weights and lobe-channel maps), the lights' shadow slots, the occlusion
/// switch, the IBL bake's state — and become preprocessor defines of lighting.frag: a term fixed
/// by every material is compiled in as a constant, a lobe no material has is compiled out.
///
/// A value edit must never compile (issue 5): when an edit needs a variant not built yet, the
/// frame draws with the generic program (every feature, run-time switches, always built) and the
/// specialised one is built at the next frame that follows no value edit (LightingPass).
/// No GL here: the derivation is pure and tested on its own (test_render_lighting_features).

#include "render/material_table.h"

#include <span>
#include <string>
#include <vector>

namespace velvet::render {

struct LightingFeatures {
    /// The term every drawn material uses (core/material.h's enums), or kAnyTerm: chosen per
    /// material at run time.
    static constexpr int kAnyTerm = -1;
    int distribution = kAnyTerm;
    int visibility = kAnyTerm;
    int fresnel = kAnyTerm;
    int diffuse = kAnyTerm;
    int sheenModel = kAnyTerm;
    /// How many directional lights the frame block carries (FrameBlock::modes.x), or kAnyTerm:
    /// read at run time. A loop of a constant count is unrolled; one of a count read from the
    /// frame block costs llvmpipe its mask bookkeeping at every pixel (about 10 % of the
    /// lighting pass with one light: BENCHMARKS.md, "The directional lights' count compiled
    /// in"). Adding or removing a light compiles; a light's value edit never does.
    int directionalLights = kAnyTerm;
    /// The material id of every pixel the surface programs shade (the scene's material, 0, when
    /// neither the A/B split's material nor the plain ground is drawn; the shadow catcher's
    /// pixels are discarded before they are read), or kAnyTerm: decoded per pixel. With it the
    /// material table is read at a constant index, which llvmpipe loads once for a block of
    /// pixels instead of once per pixel (about 0.7 ms of a 1280x720 frame's lighting).
    int materialId = kAnyTerm;
    /// Lobes some drawn material has (a weight above zero or a per-pixel channel for it).
    bool sheen = true;
    bool clearcoat = true;
    bool anisotropy = true;
    /// Some drawn material varies a lobe value per pixel (its lobe-channel map is not empty).
    bool lobeChannels = true;
    /// Some directional light has a shadow map.
    bool directionalShadows = true;
    /// Some light has a shadow map: the frame has a shadow mask (render/shadow_mask.h).
    bool shadowMask = true;
    /// Some light with a shadow map is a local one (point, spot, area): the shadow catcher
    /// weighs its mask channel by the light's illuminance (stage_shading.glsl).
    bool localShadows = true;
    /// Screen-space ambient occlusion is on.
    bool occlusion = true;
    /// Some drawn record's base colour, metallic or roughness vary per pixel (it lacks
    /// kRecordValuesPerMaterial): the lighting decodes them from the G-buffer. Without, it reads
    /// the table's alone and the G-buffer's sRGB decode compiles out.
    bool gbufferValues = true;
    /// Some drawn material bends its shading normal per pixel
    /// (GpuMaterial::sheenWeightAnisotropy.w): the lighting reconstructs the geometric normal to
    /// keep light from below the surface out.
    bool geometricHorizon = true;
    /// The frame samples its reflections (FrameSettings::reflectionSamples: the viewport at rest,
    /// a supersampled still); every other frame compiles the sampling out, which llvmpipe would
    /// otherwise pay for beside the split sum (+5 ms a 1280x720 frame).
    bool sampledReflections = true;
    /// The second surfaces pass of a frame that traces the mesh's light in screen space
    /// (FrameSettings::screenSpaceReflections; screen_space_reflection.glsl): it reads the first
    /// pass's image where its reflection and diffuse rays meet the mesh. Off in the generic
    /// program and every first pass.
    bool screenSpaceReflections = false;
    /// The environment's irradiance cube (render/irradiance_map.h) is ready: the SH9 compiles out.
    bool irradianceMap = true;
    /// Whether the occlusion rides in the shadow masks' fourth channel (1: read with the shadows'
    /// upsample; 0: its own upsample; Stage::packsOcclusion), or kAnyTerm: StageBlock::counts.z
    /// at run time. llvmpipe pays for the own upsample's code even where a uniform skips it.
    int occlusionInMask = kAnyTerm;
    /// The baked IBL (prefiltered cube and DFG LUT) is ready: the approximate path compiles out.
    /// Unknown (-1), 0 or 1; the same for the multiple-scattering energy switch.
    int iblBaked = -1;
    int multipleScattering = -1;

    /// The generic program's features: everything, every choice at run time.
    static LightingFeatures generic() { return {}; }
    bool isGeneric() const { return *this == generic(); }
    /// lighting.frag's defines for these features (none for the generic program); also the key
    /// of a built variant.
    std::vector<std::string> defines() const;
    bool operator==(const LightingFeatures&) const = default;
};

/// The features needed to draw @p records (the material table's records in use this frame),
/// with the frame's shadow, occlusion and IBL state.
LightingFeatures lightingFeaturesOf(std::span<const GpuMaterial> records, bool directionalShadows,
                                    bool occlusion, bool iblBaked, bool multipleScattering);

} // namespace velvet::render

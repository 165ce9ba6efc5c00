#pragma once
/// @file geometry_pass.h
/// Render-private: the geometry pass. Draws the preview mesh with the G-buffer program (the
/// material graph compiled in) into the G-buffer, and each pixel's emission into the HDR target
/// bound after the G-buffer's attachments (render/frame_targets.h), as Killzone 2 wrote emissive
/// into its light-accumulation buffer during the geometry pass. The A/B split draws the right
/// part again, scissored, from a cleared G-buffer, with material id 1.

#include "core/material.h"
#include "render/material_table.h"
#include "render/mesh_cache.h"

namespace velvet::render {

class MaterialGraphProgram;
class TextureSet;

/// Whether @p m can emit light: emissive colour x strength above 0, or its material graph feeds
/// an emission input of the Material output (decides whether a frame writes emission).
bool materialEmits(const Material& m);

struct GeometryPassInputs {
    unsigned framebuffer = 0; ///< FrameTargets::geometryFramebuffer
    int width = 0, height = 0;
    bool emission = false; ///< the HDR draw buffer is on: clear it to black, opaque
    /// The lobe-channel targets are on (FrameTargets::geometryFramebuffer): a drawn record has a
    /// lobe map. Off, they are neither cleared nor written: nothing reads them.
    bool lobeTargets = true;
    /// FrameSettings::splitMaterial is set: the seam at splitPosition x width, B right of it
    /// (left with splitSwapped).
    bool split = false;
    float splitPosition = 0.5f;
    bool splitSwapped = false;
    /// B's own G-buffer program when B's graph is not A's (null: B draws with A's program, its
    /// values differing only in the material table).
    MaterialGraphProgram* splitGraph = nullptr;
    /// B's texture slots (split only): B draws its own files, not A's.
    const TextureSet* texturesB = nullptr;
    /// The records of A and B (B when split) as the material table holds them: each draw uses
    /// its program specialised to its record's texture slots and lobe map
    /// (MaterialGraphProgram::programFor), built now unless @p mayBuild is false (a value edit
    /// this frame), when the generic program draws.
    GpuMaterial recordA{}, recordB{};
    bool mayBuild = true;
    /// Set by the pass when a specialised program was wanted but not built (!mayBuild).
    bool* deferred = nullptr;
    /// Off: always the generic program (Renderer::setSpecialisedPrograms).
    bool specialise = true;
};

/// Runs the pass over @p mesh (@p graph: A's program). Leaves depth testing on with writes and
/// back-face culling as the mesh asked, for the lighting pass to reset.
void drawGeometryPass(const GeometryPassInputs& in, const MeshCache::Entry& mesh,
                      MaterialGraphProgram& graph, const TextureSet& textures);

/// The black, opaque HDR colour of a pixel without emission (the lighting pass clears to it when
/// the geometry pass wrote none).
inline constexpr float kNoEmission[4] = {0, 0, 0, 1};

} // namespace velvet::render

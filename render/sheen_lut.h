#pragma once
/// @file sheen_lut.h
/// The sheen albedo tables (and the specular lobe's albedo) on the GPU: one texture that both the
/// lighting (through IblBaker) and the BRDF probe bind, so the shaders and the C++ twin read the
/// same numbers.

namespace velvet::render {

/// Creates a kSheenLutSize^2 RGBA32F texture whose channel m holds
/// brdf::sheenAlbedoLut(SheenModel(m)) and whose alpha holds brdf::specularAlbedoLut() (the base
/// specular lobe's E for multiple-scattering compensation, core/brdf_energy.h), row-major (row =
/// roughness), sampled bilinearly with clamp to edge as core/brdf.h's lookup does. Needs a current
/// GL 4.5 context; the caller owns (and deletes) the returned texture name.
unsigned createSheenAlbedoLut();

} // namespace velvet::render

#pragma once
/// @file sheen_lut.h
/// The sheen albedo tables (and the specular and diffuse lobes' albedo) on the GPU: one texture
/// that both the lighting (through IblBaker) and the BRDF probe bind, so the shaders and the C++
/// twin read the same numbers.

namespace velvet::render {

/// Creates a kSheenLutSize^2 RGBA32F texture: red holds brdf::sheenAlbedoLut(CharlieContyKulla),
/// green the table of CharlieAshikhmin and CharlieNeubelt (one function, one table), blue
/// brdf::burleyAlbedoLut() (Burley's diffuse albedo for image-based light, core/diffuse_albedo.h)
/// and alpha brdf::specularAlbedoLut() (the base specular lobe's E for multiple-scattering
/// compensation, core/brdf_energy.h); row-major (row = roughness), sampled bilinearly with clamp to
/// edge as core/brdf.h's lookup does. Needs a current GL 4.5 context; the caller owns (and
/// deletes) the returned texture name.
unsigned createSheenAlbedoLut();

} // namespace velvet::render

#pragma once
/// @file light_sampling.h
/// The path tracer's two sampling strategies (internal to reference/), combined by multiple
/// importance sampling (Veach & Guibas 1995, the power heuristic): BRDF sampling, a mixture of a
/// cosine lobe and GGX half vectors for the base and the coat (Walter et al. 2007), and light
/// sampling (next-event estimation) of the punctual and area lights.

#include "reference/scene_hit.h"

namespace velvet::reference::detail {

/// The density over solid angle with which sampleBrdf picks @p l.
float brdfPdf(const brdf::Surface& s, glm::vec3 n, glm::vec3 v, glm::vec3 l);
/// A direction from the lobe mixture (may be below the surface: its pdf is then 0).
glm::vec3 sampleBrdf(const brdf::Surface& s, glm::vec3 n, glm::vec3 v, Rng& rng);
/// Radiance times the BRDF reaching the point from light @p L sampled once (next event), with
/// the MIS weight against BRDF sampling for the area lights.
glm::vec3 sampleLight(const Context& ctx, const LocalLight& L, const Hit& hit, glm::vec3 v,
                      glm::vec3 origin, Rng& rng);
/// Emission of the area lights along a BRDF-sampled ray that reaches @p tMax first, with the
/// MIS weight against light sampling.
glm::vec3 areaEmission(const Context& ctx, glm::vec3 o, glm::vec3 d, float tMax, float brdfPdfL);

} // namespace velvet::reference::detail

#pragma once
/// @file lights.h
/// CPU twins of the light functions in resources/shaders/light_common.glsl (same names, same
/// clamps): distance falloff, spot cone, and the representative points of area lights. Pure GLM.
/// Units (docs/units.md): directional lux, point/spot candela, area nits (luminance), ambient a
/// multiplier of scene-linear white.

#include <glm/vec3.hpp>

namespace velvet::lights {

/// Shortest distance used in the inverse-square law (1 cm), so a light on a surface stays finite.
inline constexpr float kMinLightDistance = 0.01f;

/// Karis 2013, "Real Shading in Unreal Engine 4": the windowing function
/// saturate(1 - (d / range)^4)^2, 1 at the light and exactly 0 from @p range on (so light volumes
/// and tiles may cull at the radius without a visible edge). 0 when range <= 0.
float windowFalloff(float distance, float range);

/// Inverse-square law times the window: illuminance (lux) per candela at @p distance metres,
/// 1 / max(d^2, kMinLightDistance^2) * windowFalloff(d, range).
float distanceAttenuation(float distance, float range);

/// Spot cone: smoothstep from the outer cone (0) to the inner cone (1) over cos(angle), where
/// @p cosAngle is the cosine between the spot direction and the direction from the light to the
/// point. Inner >= outer is clamped so the inner cone never lies outside the outer one.
float spotConeAttenuation(float cosAngle, float cosOuter, float cosInner);

/// @name Area lights by representative point (Karis 2013, "Real Shading in Unreal Engine 4")
/// The specular lobes take the point of the light closest to the reflection ray; the diffuse
/// lobe and the sheen take the light's centre with the light's full illuminance. Energy: the
/// specular D is widened by normalization (alpha / alpha')^2, alpha' = saturate(alpha + r / (2d)).
/// @{
/// Point on a sphere light (centre @p toCenter relative to the shaded point, radius @p radius)
/// closest to the ray along unit @p reflection from the shaded point; relative to the point.
glm::vec3 sphereRepresentativePoint(glm::vec3 toCenter, glm::vec3 reflection, float radius);
/// Point of a one-sided rectangle light (centre @p toCenter, unit axes @p axisX / @p axisY, half
/// sizes @p halfX / @p halfY) nearest to where the reflection ray meets its plane, clamped to the
/// rectangle; when the ray runs away from the plane, the clamped projection of the shaded point.
glm::vec3 rectangleRepresentativePoint(glm::vec3 toCenter, glm::vec3 axisX, glm::vec3 axisY,
                                       float halfX, float halfY, glm::vec3 reflection);
/// Karis 2013's energy normalization (alpha / alpha')^2 with alpha' = saturate(alpha + widen),
/// widen = sourceRadius / (2 * distance).
float areaSpecularNormalization(float alpha, float widen);
/// Illuminance (lux) per nit at distance @p distance from the centre of a sphere light of radius
/// @p radius, facing it: pi (r / d)^2 (exact outside the sphere), windowed by @p range.
float sphereIlluminancePerNit(float distance, float radius, float range);
/// The rectangle's unit axes from the light's unit direction @p normal (the way it emits): x
/// horizontal (perpendicular to +Y, or to +X for a light facing straight up or down), y = n x x.
void rectangleAxes(glm::vec3 normal, glm::vec3& axisX, glm::vec3& axisY);
/// Illuminance (lux) per nit of a one-sided rectangle light of half sizes @p halfX / @p halfY
/// whose centre is @p distance away, @p cosLight the cosine between its normal and the direction
/// from the light to the point: the small-source form factor A cos(theta_light) / d^2 (no
/// horizon clipping; exact only far from the rectangle), windowed by @p range. 0 behind it.
float rectangleIlluminancePerNit(float distance, float cosLight, float halfX, float halfY,
                                 float range);
/// @}

} // namespace velvet::lights

#pragma once
/// @file half_float.h
/// IEEE 754 binary16 conversions for the RGBA16F data Velvet caches, uploads and reads back,
/// through Imath's half (the OpenEXR ecosystem's reference: round to nearest, ties to even;
/// overflow to infinity; NaN stays NaN; every half converts to a float exactly). Imath is a small
/// library of its own, so converting does not load OpenImageIO (core/image_codec.h).

#include <cstddef>
#include <cstdint>

namespace velvet {

std::uint16_t floatToHalf(float value);
float halfToFloat(std::uint16_t h);
/// @p n values at once (the texture and read-back paths: one call, not one per value).
void floatsToHalves(const float* in, std::size_t n, std::uint16_t* out);
void halvesToFloats(const std::uint16_t* in, std::size_t n, float* out);

} // namespace velvet

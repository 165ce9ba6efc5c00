#pragma once
/// @file half_float.h
/// IEEE 754 binary16 conversions for the RGBA16F data Velvet caches and uploads, without a
/// library (OpenImageIO's convert_pixel_values did this before core/image_codec.h made the image
/// library load on first use).

#include <cstdint>
#include <cstring>

namespace velvet {

/// Round to nearest, ties to even, as Imath's half and the F16C instructions do; overflow to
/// infinity, NaN stays NaN. Fabian Giesen's float_to_half_fast3_rtne (public domain, "Half to
/// float done quic", 2012): a float add aligns the subnormals' mantissa, an integer bias rounds
/// the normal ones.
inline std::uint16_t floatToHalf(float value) {
    std::uint32_t f;
    std::memcpy(&f, &value, 4);
    const std::uint32_t sign = f & 0x80000000u;
    f ^= sign;
    std::uint16_t h;
    if (f >= (127u + 16u) << 23) { // >= 65536 (or Inf, NaN): Inf or quiet NaN
        h = f > 0x7f800000u ? 0x7e00 : 0x7c00;
    } else if (f < 113u << 23) { // below 2^-14: a subnormal half or zero
        const std::uint32_t magicBits = ((127u - 15u) + (23u - 10u) + 1u) << 23;
        float magic, x;
        std::memcpy(&magic, &magicBits, 4);
        std::memcpy(&x, &f, 4);
        x += magic; // rounds to nearest even at the half's last subnormal bit
        std::uint32_t xb;
        std::memcpy(&xb, &x, 4);
        h = std::uint16_t(xb - magicBits);
    } else {
        const std::uint32_t odd = (f >> 13) & 1u;
        f += ((15u - 127u) << 23) + 0xfffu; // rebias the exponent, round half down ...
        f += odd;                           // ... or up when the kept mantissa is odd
        h = std::uint16_t(f >> 13);
    }
    return std::uint16_t(h | (sign >> 16));
}

/// Exact (every half is a float).
inline float halfToFloat(std::uint16_t h) {
    const std::uint32_t sign = std::uint32_t(h & 0x8000u) << 16;
    const std::uint32_t exponent = (h >> 10) & 0x1fu;
    const std::uint32_t mantissa = h & 0x3ffu;
    std::uint32_t f;
    if (exponent == 0) {
        if (mantissa == 0) {
            f = sign;
        } else { // subnormal: mantissa x 2^-24
            const float v = float(mantissa) * (1.0f / 16777216.0f);
            std::memcpy(&f, &v, 4);
            f |= sign;
        }
    } else if (exponent == 31) {
        f = sign | 0x7f800000u | (mantissa << 13);
    } else {
        f = sign | ((exponent + 112u) << 23) | (mantissa << 13);
    }
    float out;
    std::memcpy(&out, &f, 4);
    return out;
}

} // namespace velvet

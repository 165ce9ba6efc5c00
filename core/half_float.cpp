#include "core/half_float.h"

#include <Imath/half.h>

namespace velvet {

std::uint16_t floatToHalf(float value) {
    return imath_float_to_half(value);
}

float halfToFloat(std::uint16_t h) {
    return imath_half_to_float(h);
}

void floatsToHalves(const float* in, std::size_t n, std::uint16_t* out) {
    for (std::size_t i = 0; i < n; ++i)
        out[i] = imath_float_to_half(in[i]);
}

void halvesToFloats(const std::uint16_t* in, std::size_t n, float* out) {
    for (std::size_t i = 0; i < n; ++i)
        out[i] = imath_half_to_float(in[i]);
}

} // namespace velvet

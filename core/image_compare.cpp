#include "core/image_compare.h"

#include "core/color_difference.h"
#include "core/color_management.h"
#include "core/tone_curves.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <glm/common.hpp>
#include <string_view>

namespace velvet {
namespace {

/// 3x5 glyphs for the legend's numbers: each row is 3 bits, the high bit on the left.
struct Glyph {
    char c;
    std::array<unsigned char, 5> rows;
};
constexpr Glyph kGlyphs[] = {
    {'0', {7, 5, 5, 5, 7}}, {'1', {2, 6, 2, 2, 7}}, {'2', {7, 1, 7, 4, 7}}, {'3', {7, 1, 7, 1, 7}},
    {'4', {5, 5, 7, 1, 1}}, {'5', {7, 4, 7, 1, 7}}, {'6', {7, 4, 7, 5, 7}}, {'7', {7, 1, 1, 1, 1}},
    {'8', {7, 5, 7, 5, 7}}, {'9', {7, 5, 7, 1, 7}}, {'.', {0, 0, 0, 0, 2}}, {'>', {4, 2, 1, 2, 4}},
    {'=', {0, 7, 0, 7, 0}}, {'E', {7, 4, 6, 4, 7}}, {'d', {1, 1, 7, 5, 7}},
};
constexpr int kGlyphScale = 2;                 ///< pixels per glyph pixel
constexpr int kGlyphAdvance = 4 * kGlyphScale; ///< 3 columns + 1 of spacing
constexpr int kMargin = 6, kBarHeight = 12, kTickHeight = 4;
constexpr int kLegendHeight = kMargin + kBarHeight + kTickHeight + 2 + 5 * kGlyphScale + kMargin;
constexpr int kLegendMinWidth = 220;

void drawText(Image& img, int x, int y, std::string_view text, glm::vec3 colour) {
    for (const char c : text) {
        const Glyph* g = nullptr;
        for (const Glyph& candidate : kGlyphs)
            if (candidate.c == c)
                g = &candidate;
        if (g)
            for (int row = 0; row < 5; ++row)
                for (int col = 0; col < 3; ++col) {
                    if (!(g->rows[size_t(row)] & (4 >> col)))
                        continue;
                    for (int sy = 0; sy < kGlyphScale; ++sy)
                        for (int sx = 0; sx < kGlyphScale; ++sx) {
                            const int px = x + col * kGlyphScale + sx,
                                      py = y + row * kGlyphScale + sy;
                            if (px < 0 || py < 0 || px >= img.width || py >= img.height)
                                continue;
                            float* p = img.at(px, py);
                            p[0] = colour.r, p[1] = colour.g, p[2] = colour.b;
                        }
                }
        x += kGlyphAdvance;
    }
}

std::string label(double value) {
    char text[32];
    std::snprintf(text, sizeof text, value == std::floor(value) ? "%.0f" : "%.1f", value);
    return text;
}

} // namespace

Image defaultDisplayTransform(const Image& linear) {
    Image out(linear.width, linear.height, linear.channels);
    const int colour = std::min(linear.channels, 3);
    for (int y = 0; y < linear.height; ++y)
        for (int x = 0; x < linear.width; ++x) {
            const float* in = linear.at(x, y);
            float* o = out.at(x, y);
            glm::vec3 c(in[0], colour > 1 ? in[1] : in[0], colour > 2 ? in[2] : in[0]);
            c = glm::max(c, glm::vec3(0.0f)); // the tone curve is defined for c >= 0
            c = glm::clamp(tone::khronosPbrNeutral(c), glm::vec3(0.0f), glm::vec3(1.0f));
            for (int i = 0; i < colour; ++i)
                o[i] = linearToSrgb(c[i]);
            for (int i = colour; i < linear.channels; ++i)
                o[i] = in[i];
        }
    return out;
}

bool compareImages(const Image& a, const Image& b, Image& deltaE, DeltaEStats& stats,
                   std::string* error) {
    if (a.empty() || b.empty()) {
        if (error)
            *error = "an image is empty";
        return false;
    }
    if (a.width != b.width || a.height != b.height) {
        if (error)
            *error = "the images differ in size: " + std::to_string(a.width) + "x" +
                     std::to_string(a.height) + " and " + std::to_string(b.width) + "x" +
                     std::to_string(b.height);
        return false;
    }
    deltaE = Image(a.width, a.height, 1);
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            const glm::vec4 pa = a.rgba(x, y), pb = b.rgba(x, y);
            *deltaE.at(x, y) = float(ciede2000(srgbToLab(glm::vec3(pa)), srgbToLab(glm::vec3(pb))));
        }
    stats = deltaEStats(deltaE);
    return true;
}

DeltaEStats deltaEStats(const Image& deltaE) {
    DeltaEStats s;
    std::vector<float> values(deltaE.pixels.begin(), deltaE.pixels.end());
    if (values.empty())
        return s;
    s.pixels = values.size();
    double sum = 0.0;
    for (const float v : values) {
        sum += v;
        s.max = std::max(s.max, double(v));
    }
    s.mean = sum / double(values.size());
    const size_t rank = size_t(std::ceil(0.95 * double(values.size())));
    const size_t index = std::max<size_t>(rank, 1) - 1;
    std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(index), values.end());
    s.p95 = values[index];
    return s;
}

DeltaEStats deltaEStats(const Image& deltaE, const Image& coverage) {
    if (deltaE.width != coverage.width || deltaE.height != coverage.height ||
        deltaE.channels != 1 || coverage.channels != 1)
        return {};
    Image inside(0, 1, 1);
    for (size_t i = 0; i < deltaE.pixels.size(); ++i)
        if (coverage.pixels[i] >= 1.0f)
            inside.pixels.push_back(deltaE.pixels[i]);
    inside.width = int(inside.pixels.size());
    return deltaEStats(inside);
}

glm::vec3 heatMapColor(double value, double scaleMax) {
    struct Stop {
        float at;
        glm::vec3 colour;
    };
    static constexpr Stop kStops[] = {
        {0.00f, {0.00f, 0.00f, 0.00f}}, {0.25f, {0.15f, 0.25f, 0.95f}},
        {0.50f, {0.10f, 0.80f, 0.30f}}, {0.75f, {1.00f, 0.85f, 0.05f}},
        {1.00f, {0.95f, 0.10f, 0.10f}},
    };
    const float t = scaleMax > 0.0 ? float(std::clamp(value / scaleMax, 0.0, 1.0)) : 1.0f;
    for (size_t i = 1; i < std::size(kStops); ++i)
        if (t <= kStops[i].at) {
            const float f = (t - kStops[i - 1].at) / (kStops[i].at - kStops[i - 1].at);
            return glm::mix(kStops[i - 1].colour, kStops[i].colour, f);
        }
    return kStops[std::size(kStops) - 1].colour;
}

int heatMapLegendHeight() {
    return kLegendHeight;
}

Image heatMapWithLegend(const Image& deltaE, double scaleMax) {
    const int width = std::max(deltaE.width, kLegendMinWidth);
    Image out(width, deltaE.height + kLegendHeight, 3);
    for (int y = 0; y < deltaE.height; ++y)
        for (int x = 0; x < deltaE.width; ++x) {
            const glm::vec3 c = heatMapColor(*deltaE.at(x, y), scaleMax);
            float* p = out.at(x, y);
            p[0] = c.r, p[1] = c.g, p[2] = c.b;
        }
    // The legend: a ramp, ticks under it and their values; the last reads ">=max".
    const int barX0 = kMargin + 2 * kGlyphAdvance + 4, barX1 = width - kMargin - 3 * kGlyphAdvance;
    const int barY = deltaE.height + kMargin;
    const glm::vec3 white(1.0f);
    for (int x = barX0; x < barX1; ++x) {
        const glm::vec3 c =
            heatMapColor(scaleMax * double(x - barX0) / double(barX1 - 1 - barX0), scaleMax);
        for (int y = barY; y < barY + kBarHeight; ++y) {
            float* p = out.at(x, y);
            p[0] = c.r, p[1] = c.g, p[2] = c.b;
        }
    }
    for (int i = 0; i <= 4; ++i) {
        const int x = barX0 + (barX1 - 1 - barX0) * i / 4;
        for (int y = barY + kBarHeight; y < barY + kBarHeight + kTickHeight; ++y) {
            float* p = out.at(x, y);
            p[0] = p[1] = p[2] = 1.0f;
        }
        std::string text = label(scaleMax * i / 4.0);
        if (i == 4)
            text = ">=" + text;
        const int textWidth = int(text.size()) * kGlyphAdvance - kGlyphScale;
        drawText(out, std::clamp(x - textWidth / 2, 0, width - textWidth),
                 barY + kBarHeight + kTickHeight + 2, text, white);
    }
    drawText(out, kMargin, barY + kBarHeight / 2 - 5, "dE", white);
    return out;
}

} // namespace velvet

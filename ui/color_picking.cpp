#include "ui/color_picking.h"

#include <QString>
#include <algorithm>
#include <cmath>
#include <glm/common.hpp>

namespace velvet::ui {
namespace {

glm::vec3 srgbEncode(glm::vec3 v) {
    return {linearToSrgb(v.x), linearToSrgb(v.y), linearToSrgb(v.z)};
}

glm::vec3 srgbDecode(glm::vec3 v) {
    return {srgbToLinear(v.x), srgbToLinear(v.y), srgbToLinear(v.z)};
}

glm::vec3 clamp01(glm::vec3 v) {
    return glm::clamp(v, glm::vec3(0.0f), glm::vec3(1.0f));
}

constexpr int kInverseIterations = 24;
constexpr float kInverseTolerance = 0.25f / 255.0f; // well inside one 8-bit code
constexpr float kMaxLinear = 64.0f;                 // tone-mapped views approach white slowly

} // namespace

glm::vec3 PickerColorSpace::toDisplay(glm::vec3 linear) const {
    if (isSrgb())
        return clamp01(srgbEncode(linear));
    float rgb[3] = {linear.x, linear.y, linear.z};
    DisplaySettings settings = display;
    settings.exposure = 0.0f; // a picked albedo should not change with the viewport exposure
    std::string error;
    if (!colorManagement->applyDisplay(rgb, settings, &error))
        return clamp01(srgbEncode(linear));
    return clamp01(glm::vec3(rgb[0], rgb[1], rgb[2]));
}

glm::vec3 PickerColorSpace::toLinear(glm::vec3 target) const {
    target = clamp01(target);
    const glm::vec3 srgbGuess = srgbDecode(target);
    if (isSrgb())
        return srgbGuess;
    // Display transforms are monotonic per channel for in-gamut colours and close to a power
    // law: solve each channel in log space, log(decode(f(x))) = log(decode(target)), with secant
    // steps (the first step assumes slope 1, i.e. plain sRGB). Channels that cannot reach the
    // target (display white under a tone-mapping view) stop at the range limit.
    constexpr float kFloor = 1e-6f;
    glm::vec3 x = glm::max(srgbGuess, glm::vec3(kFloor));
    glm::vec3 prevLog(0.0f), prevHave(0.0f);
    glm::vec3 best = x;
    float bestError = 1e9f;
    for (int i = 0; i < kInverseIterations; ++i) {
        const glm::vec3 shown = toDisplay(x);
        const glm::vec3 diff = glm::abs(shown - target);
        const float error = std::max({diff.x, diff.y, diff.z});
        if (error < bestError) {
            bestError = error;
            best = x;
        }
        if (error < kInverseTolerance)
            break;
        const glm::vec3 have = srgbDecode(shown);
        for (int c = 0; c < 3; ++c) {
            if (target[c] <= 0.0f) {
                x[c] = 0.0f;
                continue;
            }
            const float logX = std::log(std::max(x[c], kFloor));
            const float logHave = std::log(std::max(have[c], kFloor));
            const float logWant = std::log(std::max(srgbGuess[c], kFloor));
            float slope = 1.0f;
            if (i > 0 && std::abs(logX - prevLog[c]) > 1e-6f)
                slope = std::clamp((logHave - prevHave[c]) / (logX - prevLog[c]), 0.05f, 4.0f);
            prevLog[c] = logX;
            prevHave[c] = logHave;
            const float step = std::clamp((logWant - logHave) / slope, -4.0f, 4.0f);
            x[c] = std::clamp(std::exp(logX + step), kFloor, kMaxLinear);
        }
    }
    return bestError < 2.0f / 255.0f ? best : srgbGuess;
}

QColor PickerColorSpace::toQColor(glm::vec3 linear) const {
    const glm::vec3 d = toDisplay(linear);
    return QColor::fromRgbF(d.x, d.y, d.z);
}

glm::vec3 PickerColorSpace::fromQColor(const QColor& color) const {
    return toLinear(glm::vec3(static_cast<float>(color.redF()), static_cast<float>(color.greenF()),
                              static_cast<float>(color.blueF())));
}

QString PickerColorSpace::name() const {
    if (isSrgb())
        return QStringLiteral("sRGB");
    const QString d = display.display.empty()
                          ? QString::fromStdString(colorManagement->defaultDisplay())
                          : QString::fromStdString(display.display);
    const QString v = display.view.empty()
                          ? QString::fromStdString(colorManagement->defaultView(d.toStdString()))
                          : QString::fromStdString(display.view);
    QString text = d + QStringLiteral(" / ") + v;
    if (!display.look.empty())
        text += QStringLiteral(" / ") + QString::fromStdString(display.look);
    return text;
}

} // namespace velvet::ui

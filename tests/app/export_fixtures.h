#pragma once
/// @file export_fixtures.h
/// A material for the export tests that uses most texture slots: base colour and sheen colour
/// as two regions of one atlas (the base colour with a cut-out column), occlusion with
/// metallic-roughness (packed on export), normal, emissive, clearcoat and specular colour maps,
/// each of a known constant value so that exported texels can be checked.

#include "core/document_io.h"
#include "core/image.h"

#include <QDir>
#include <QString>
#include <QtGlobal>
#include <algorithm>
#include <initializer_list>
#include <string>

namespace velvet::test {

inline velvet::Image flat(int w, int h, int channels, std::initializer_list<float> value) {
    velvet::Image img(w, h, channels);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            std::copy(value.begin(), value.end(), img.at(x, y));
    return img;
}

inline void writePng(const QString& file, const velvet::Image& img) {
    std::string error;
    if (!velvet::writeImage(file.toStdString(), img, velvet::PixelFormat::UInt8, &error))
        qFatal("%s", error.c_str());
}

/// Writes the textures under DIR/textures/ and the preset DIR/textured.json; returns its path.
inline QString writeTexturedPreset(const QString& dir) {
    const QString t = dir + "/textures/";
    QDir().mkpath(t);
    // Atlas: left half base colour (with a cut-out column), right half sheen colour.
    velvet::Image atlas(64, 32, 4);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 64; ++x) {
            const float base[4] = {0.2f, 0.4f, 0.6f, x == 3 ? 0.0f : 1.0f};
            const float sheen[4] = {1.0f, 0.8f, 0.2f, 1.0f};
            std::copy(x < 32 ? base : sheen, (x < 32 ? base : sheen) + 4, atlas.at(x, y));
        }
    writePng(t + "atlas.png", atlas);
    writePng(t + "occlusion.png", flat(16, 16, 1, {0.25f}));
    writePng(t + "mr.png", flat(16, 16, 3, {0.0f, 0.6f, 0.9f}));
    writePng(t + "normal.png", flat(16, 16, 3, {0.5f, 0.5f, 1.0f}));
    writePng(t + "emissive.png", flat(8, 8, 3, {1.0f, 0.5f, 0.0f}));
    writePng(t + "clearcoat.png", flat(8, 8, 1, {0.7f}));
    writePng(t + "speccolor.png", flat(8, 8, 3, {0.9f, 0.9f, 1.0f}));

    using velvet::ParamId;
    using velvet::TextureSlot;
    velvet::Material m;
    m.name = "Textured test";
    m.setColor(ParamId::EmissiveColor, glm::vec3(1.0f));
    m.setScalar(ParamId::EmissiveStrength, 4.0f);
    m.setScalar(ParamId::ClearcoatWeight, 1.0f);
    m.setScalar(ParamId::SheenWeight, 0.5f);
    m.setColor(ParamId::SheenColor, {1.0f, 0.5f, 0.5f});
    m.setScalar(ParamId::Ior, 1.45f);
    auto ref = [&](const char* file) {
        velvet::TextureRef r;
        r.file = (t + file).toStdString();
        return r;
    };
    velvet::TextureRef base = ref("atlas.png");
    base.useRegion = true;
    base.region = {0, 0, 32, 32};
    velvet::TextureRef sheen = base;
    sheen.region = {32, 0, 32, 32};
    m.setTexture(TextureSlot::BaseColor, base);
    m.setTexture(TextureSlot::SheenColor, sheen);
    m.setTexture(TextureSlot::Occlusion, ref("occlusion.png"));
    m.setTexture(TextureSlot::MetallicRoughness, ref("mr.png"));
    m.setTexture(TextureSlot::Normal, ref("normal.png"));
    m.setTexture(TextureSlot::Emissive, ref("emissive.png"));
    m.setTexture(TextureSlot::Clearcoat, ref("clearcoat.png"));
    m.setTexture(TextureSlot::SpecularColor, ref("speccolor.png"));
    const QString preset = dir + "/textured.json";
    std::string error;
    if (!velvet::saveMaterialFile(m, preset.toStdString(), &error))
        qFatal("%s", error.c_str());
    return preset;
}

} // namespace velvet::test

// core/channel_packing: every layout packs its maps into the documented channels and unpacks
// them back; absent maps get their defaults; mismatched sizes are refused with both named.
#include "core/channel_packing.h"

#include <QTemporaryDir>
#include <QtTest>

using namespace velvet;

namespace {

/// A one-channel map whose texels all differ (and differ between maps through @p seed), on the
/// 8-bit grid so a PNG round trip is exact.
Image map(int w, int h, int seed) {
    Image img(w, h, 1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            img.at(x, y)[0] = float((x * 17 + y * 5 + seed * 41) % 256) / 255.0f;
    return img;
}

void compareMaps(const Image& a, const Image& b, float tolerance, const char* what) {
    QVERIFY2(!a.empty() && !b.empty(), what);
    QCOMPARE(a.width, b.width);
    QCOMPARE(a.height, b.height);
    QCOMPARE(b.channels, 1);
    for (size_t i = 0; i < a.pixels.size(); ++i)
        QVERIFY2(std::abs(a.pixels[i] - b.pixels[i]) <= tolerance, what);
}

} // namespace

class TestCoreChannelPacking : public QObject {
    Q_OBJECT

private slots:
    void ids() {
        for (int i = 0; i < int(PackLayout::Count); ++i) {
            const auto layout = PackLayout(i);
            QCOMPARE(packLayoutFromId(packLayoutId(layout)), std::optional(layout));
            QVERIFY(!packLayoutLabel(layout).empty());
        }
        QVERIFY(!packLayoutFromId("nope"));
    }

    // Each layout puts each map in its documented channel and unpacks it back exactly.
    void roundTrip_data() {
        QTest::addColumn<int>("layout");
        QTest::newRow("glTF metallic-roughness") << int(PackLayout::GltfMetallicRoughness);
        QTest::newRow("Unreal ORM") << int(PackLayout::UnrealOrm);
        QTest::newRow("HDRP mask map") << int(PackLayout::HdrpMaskMap);
        QTest::newRow("spec/rough/metal") << int(PackLayout::SpecRoughMetal);
    }
    void roundTrip() {
        QFETCH(int, layout);
        ChannelMaps maps;
        maps.occlusion = map(9, 5, 1);
        maps.roughness = map(9, 5, 2);
        maps.metallic = map(9, 5, 3);
        maps.specular = map(9, 5, 4);
        maps.detailMask = map(9, 5, 5);
        Image packed;
        std::string error;
        QVERIFY2(packChannels(PackLayout(layout), maps, packed, &error), error.c_str());
        QCOMPARE(packed.width, 9);
        QCOMPARE(packed.height, 5);

        // Where each map went, per layout (sampled at one texel).
        const float o = maps.occlusion.at(4, 3)[0], r = maps.roughness.at(4, 3)[0],
                    m = maps.metallic.at(4, 3)[0], s = maps.specular.at(4, 3)[0],
                    d = maps.detailMask.at(4, 3)[0];
        const float* p = packed.at(4, 3);
        switch (PackLayout(layout)) {
        case PackLayout::GltfMetallicRoughness: // glTF 2.0 3.9.2: G roughness, B metallic
        case PackLayout::UnrealOrm:
            QCOMPARE(packed.channels, 3);
            QCOMPARE(p[0], o);
            QCOMPARE(p[1], r);
            QCOMPARE(p[2], m);
            break;
        case PackLayout::HdrpMaskMap: // MODS, A = smoothness = 1 - roughness
            QCOMPARE(packed.channels, 4);
            QCOMPARE(p[0], m);
            QCOMPARE(p[1], o);
            QCOMPARE(p[2], d);
            QCOMPARE(p[3], 1.0f - r);
            break;
        case PackLayout::SpecRoughMetal:
            QCOMPARE(packed.channels, 3);
            QCOMPARE(p[0], s);
            QCOMPARE(p[1], r);
            QCOMPARE(p[2], m);
            break;
        default:
            QFAIL("layout");
        }

        ChannelMaps back;
        QVERIFY2(unpackChannels(PackLayout(layout), packed, back, &error), error.c_str());
        const float eps = 1e-6f; // 1 - (1 - r) is exact to a rounding
        compareMaps(maps.roughness, back.roughness, eps, "roughness");
        compareMaps(maps.metallic, back.metallic, eps, "metallic");
        if (PackLayout(layout) == PackLayout::SpecRoughMetal) {
            compareMaps(maps.specular, back.specular, eps, "specular");
            QVERIFY(back.occlusion.empty());
        } else {
            compareMaps(maps.occlusion, back.occlusion, eps, "occlusion");
            QVERIFY(back.specular.empty());
        }
        if (PackLayout(layout) == PackLayout::HdrpMaskMap)
            compareMaps(maps.detailMask, back.detailMask, eps, "detail mask");
        else
            QVERIFY(back.detailMask.empty());
    }

    // Through an 8-bit PNG and back: the packing survives a file (values on the 8-bit grid).
    void roundTripThroughAFile() {
        QTemporaryDir dir;
        ChannelMaps maps;
        maps.occlusion = map(16, 8, 1);
        maps.roughness = map(16, 8, 2);
        maps.metallic = map(16, 8, 3);
        Image packed;
        std::string error;
        QVERIFY2(packChannels(PackLayout::UnrealOrm, maps, packed, &error), error.c_str());
        const std::string file = (dir.path() + "/orm.png").toStdString();
        QVERIFY2(writeImage(file, packed, PixelFormat::UInt8, &error), error.c_str());
        Image read;
        QVERIFY2(readImage(file, read, &error), error.c_str());
        ChannelMaps back;
        QVERIFY2(unpackChannels(PackLayout::UnrealOrm, read, back, &error), error.c_str());
        compareMaps(maps.occlusion, back.occlusion, 1e-6f, "occlusion");
        compareMaps(maps.roughness, back.roughness, 1e-6f, "roughness");
        compareMaps(maps.metallic, back.metallic, 1e-6f, "metallic");
    }

    // Absent maps are filled with the documented defaults (occlusion 1, roughness 0.5,
    // metallic 0, detail mask 1), or the caller's; a colour input contributes its R.
    void absentMapsGetDefaults() {
        ChannelMaps maps;
        maps.roughness = Image(3, 2, 3);
        std::fill(maps.roughness.pixels.begin(), maps.roughness.pixels.end(), 0.2f);
        maps.roughness.at(1, 1)[0] = 0.9f; // R of a colour image is what counts
        Image packed;
        std::string error;
        QVERIFY2(packChannels(PackLayout::HdrpMaskMap, maps, packed, &error), error.c_str());
        QCOMPARE(packed.at(0, 0)[0], 0.0f);        // metallic
        QCOMPARE(packed.at(0, 0)[1], 1.0f);        // occlusion
        QCOMPARE(packed.at(0, 0)[2], 1.0f);        // detail mask
        QCOMPARE(packed.at(0, 0)[3], 1.0f - 0.2f); // smoothness
        QCOMPARE(packed.at(1, 1)[3], 1.0f - 0.9f);

        ChannelDefaults defaults;
        defaults.metallic = 1.0f;
        defaults.specular = 0.25f;
        QVERIFY(packChannels(PackLayout::SpecRoughMetal, maps, packed, &error, defaults));
        QCOMPARE(packed.at(2, 1)[0], 0.25f);
        QCOMPARE(packed.at(2, 1)[2], 1.0f);
    }

    void refusals() {
        ChannelMaps maps;
        Image packed;
        std::string error;
        QVERIFY(!packChannels(PackLayout::UnrealOrm, maps, packed, &error));
        QVERIFY2(error.find("nothing to pack") != std::string::npos, error.c_str());

        maps.roughness = map(512, 512, 0);
        maps.metallic = map(256, 256, 0);
        QVERIFY(!packChannels(PackLayout::GltfMetallicRoughness, maps, packed, &error));
        qInfo("%s", error.c_str());
        QVERIFY2(error.find("roughness is 512x512") != std::string::npos &&
                     error.find("metallic is 256x256") != std::string::npos,
                 error.c_str());
        // A map the layout does not hold is not checked (specular in ORM).
        maps.metallic = map(512, 512, 0);
        maps.specular = map(4, 4, 0);
        QVERIFY2(packChannels(PackLayout::UnrealOrm, maps, packed, &error), error.c_str());

        ChannelMaps back;
        QVERIFY(!unpackChannels(PackLayout::HdrpMaskMap, packed, back, &error));
        QVERIFY2(error.find("needs 4 channels") != std::string::npos, error.c_str());
    }
};

QTEST_GUILESS_MAIN(TestCoreChannelPacking)
#include "test_core_channel_packing.moc"

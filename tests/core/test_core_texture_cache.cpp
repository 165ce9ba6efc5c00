// core/texture_cache: each (file, colour space) decoded once into scene-linear float, handed out
// shared, reloaded when the file changes on disk; missing and broken files give a problem and a
// null image, never an exception.
#include "core/color_management.h"
#include "core/image.h"
#include "core/texture_cache.h"

#include <QTemporaryDir>
#include <QtTest>
#include <chrono>
#include <filesystem>
#include <fstream>

using namespace velvet;
namespace fs = std::filesystem;

namespace {

Image flat(int w, int h, int c, float v) {
    Image img(w, h, c);
    std::fill(img.pixels.begin(), img.pixels.end(), v);
    return img;
}

bool mentions(const Texture& t, const std::string& text, Problem::Severity severity) {
    for (const Problem& p : t.problems)
        if (p.severity == severity && p.toString().find(text) != std::string::npos)
            return true;
    return false;
}

} // namespace

class TestCoreTextureCache : public QObject {
    Q_OBJECT
    QTemporaryDir m_dir;
    ColorManagement m_cm;
    fs::path path(const char* name) { return fs::path(m_dir.path().toStdString()) / name; }
    void write(const fs::path& file, const Image& image, PixelFormat format = PixelFormat::UInt8) {
        std::string error;
        QVERIFY2(writeImage(file, image, format, &error), error.c_str());
    }

private slots:
    void initTestCase() {
        std::string error;
        QVERIFY2(m_cm.loadDefault(&error), error.c_str());
    }

    // 8-bit 128 tagged "sRGB texture" loads as 0.2158 scene-linear (IEC 61966-2-1 EOTF of
    // 128/255); grey maps to RRR for a colour slot. The same file as data stays 128/255 and grey.
    void srgbTextureLoadsLinear() {
        const fs::path file = path("grey128.png");
        write(file, flat(4, 4, 1, 128.0f / 255.0f));
        TextureCache cache(m_cm);
        const Texture color = cache.get(file, TextureUsage::Color, "sRGB texture");
        QVERIFY(color.image);
        QVERIFY(color.problems.empty());
        QCOMPARE(color.colorSpace, std::string("sRGB texture"));
        QCOMPARE(color.image->channels, 3);
        for (int k = 0; k < 3; ++k)
            QVERIFY2(std::abs(color.image->at(2, 2)[k] - 0.2158f) < 5e-4f,
                     qPrintable(QString::number(color.image->at(2, 2)[k])));
        // Empty colour space: the colour default for a PNG is sRGB texture (same entry).
        const Texture byDefault = cache.get(file, TextureUsage::Color);
        QCOMPARE(byDefault.image.get(), color.image.get());

        const Texture data = cache.get(file, TextureUsage::Data);
        QVERIFY(data.image);
        QCOMPARE(data.colorSpace, std::string("Raw"));
        QCOMPARE(data.image->channels, 1);
        QVERIFY(std::abs(data.image->at(0, 0)[0] - 128.0f / 255.0f) < 1e-6f);
        QCOMPARE(cache.decodeCount(), std::uint64_t(2));

        // Through a slot: base colour is a colour slot, occlusion a data slot.
        TextureRef ref;
        ref.file = file.string();
        QCOMPARE(cache.get(ref, TextureSlot::BaseColor).image.get(), color.image.get());
        QCOMPARE(cache.get(ref, TextureSlot::Occlusion).image.get(), data.image.get());
        QVERIFY(!cache.get(TextureRef{}, TextureSlot::BaseColor).image);
        QCOMPARE(cache.decodeCount(), std::uint64_t(2));

        // An EXR in a colour slot is scene-linear by the config's file rules: left as stored.
        const fs::path exr = path("linear.exr");
        write(exr, flat(2, 2, 3, 0.5f), PixelFormat::Float);
        const Texture linear = cache.get(exr, TextureUsage::Color);
        QVERIFY(linear.image);
        QCOMPARE(linear.colorSpace, std::string("Linear Rec.709"));
        QCOMPARE(linear.image->at(1, 1)[0], 0.5f);
    }

    // Decoded once however often it is asked for; poll() without a change decodes nothing; a
    // rewrite with a new value (and a later mtime) is reloaded with a new generation.
    void loadsOnceAndReloadsWhenTheFileChanges() {
        const fs::path file = path("changing.png");
        write(file, flat(8, 8, 3, 0.0f));
        TextureCache cache(m_cm);
        const Texture first = cache.get(file, TextureUsage::Data);
        QVERIFY(first.image);
        QVERIFY(first.generation != 0);
        for (int i = 0; i < 5; ++i) {
            const Texture again = cache.get(file, TextureUsage::Data);
            QCOMPARE(again.image.get(), first.image.get());
            QCOMPARE(again.generation, first.generation);
        }
        QCOMPARE(cache.poll(), 0);
        QCOMPARE(cache.decodeCount(), std::uint64_t(1));
        QCOMPARE(cache.size(), size_t(1));

        // Rewritten in place (same inode, same size: a flat PNG of another value), only the
        // modification time tells; bump it as an editor's save would.
        const auto before = fs::last_write_time(file);
        {
            const fs::path other = path("other.png");
            write(other, flat(8, 8, 3, 1.0f));
            std::ifstream in(other, std::ios::binary);
            const std::string bytes((std::istreambuf_iterator<char>(in)), {});
            std::ofstream(file, std::ios::binary | std::ios::trunc)
                .write(bytes.data(), std::streamsize(bytes.size()));
        }
        fs::last_write_time(file, before + std::chrono::seconds(2));
        QCOMPARE(cache.poll(), 1);
        QCOMPARE(cache.decodeCount(), std::uint64_t(2));
        const Texture second = cache.get(file, TextureUsage::Data);
        QVERIFY(second.image);
        QVERIFY(second.generation != first.generation);
        QCOMPARE(second.image->at(3, 3)[1], 1.0f);
        QCOMPARE(first.image->at(3, 3)[1], 0.0f); // holders of the old image keep it intact
        QCOMPARE(cache.poll(), 0);

        // An atomic save (new file renamed over it) is seen too, whatever the times say.
        write(file, flat(8, 8, 3, 0.5f));
        fs::last_write_time(file, before + std::chrono::seconds(2));
        QCOMPARE(cache.poll(), 1);
        QVERIFY(std::abs(cache.get(file, TextureUsage::Data).image->at(0, 0)[0] - 0.5f) < 0.003f);
        QCOMPARE(cache.decodeCount(), std::uint64_t(3));
    }

    // Missing, broken and mistagged files give a problem naming the file and a null image; a
    // missing file that appears later is picked up by poll().
    void problemsInsteadOfExceptions() {
        TextureCache cache(m_cm);
        const fs::path missing = path("later.png");
        const Texture none = cache.get(missing, TextureUsage::Color);
        QVERIFY(!none.image);
        QVERIFY(mentions(none, "later.png: no such file", Problem::Severity::Error));
        QCOMPARE(cache.poll(), 0);
        write(missing, flat(2, 2, 3, 1.0f));
        QCOMPARE(cache.poll(), 1);
        const Texture appeared = cache.get(missing, TextureUsage::Color);
        QVERIFY(appeared.image);
        QVERIFY(appeared.problems.empty());
        QVERIFY(appeared.generation != none.generation);

        const fs::path broken = path("broken.png");
        std::ofstream(broken) << "not a png";
        const Texture bad = cache.get(broken, TextureUsage::Color);
        QVERIFY(!bad.image);
        QVERIFY(mentions(bad, "broken.png", Problem::Severity::Error));
        qInfo("%s", bad.problems.at(0).toString().c_str());

        const Texture tagged = cache.get(missing, TextureUsage::Color, "No Such Space");
        QVERIFY(!tagged.image);
        QVERIFY(mentions(tagged, "No Such Space", Problem::Severity::Error));
        qInfo("%s", tagged.problems.at(0).toString().c_str());

        // Removing the file is a change as well: the image goes, with a problem.
        fs::remove(missing);
        QVERIFY(cache.poll() >= 1);
        QVERIFY(!cache.get(missing, TextureUsage::Color).image);
    }

    // Textures beyond the GPU limit are downscaled on load, with a warning naming the file.
    void largeTexturesAreFittedToTheGpuLimit() {
        const fs::path file = path("big.png");
        write(file, flat(512, 512, 3, 1.0f));
        TextureCacheOptions options;
        options.maxTextureSide = 256;
        TextureCache cache(m_cm, options);
        const Texture t = cache.get(file, TextureUsage::Color);
        QVERIFY(t.image);
        QCOMPARE(t.image->width, 256);
        QCOMPARE(t.image->height, 256);
        QVERIFY(mentions(t, "big.png: 512x512", Problem::Severity::Warning));
        qInfo("%s", t.problems.at(0).toString().c_str());

        cache.trim();
        QCOMPARE(cache.size(), size_t(1)); // t still holds the image
    }
};

QTEST_GUILESS_MAIN(TestCoreTextureCache)
#include "test_core_texture_cache.moc"

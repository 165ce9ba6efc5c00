// core/image: round trips through every format the renderer and CLI write, and refusal of bad
// files (truncated, unknown, missing, oversized) with a message naming the file.
#include "core/image.h"

#include <QTemporaryDir>
#include <QtTest>
#include <cstdint>
#include <fstream>

using namespace velvet;

namespace {

Image gradient(int w, int h, int c) {
    Image img(w, h, c);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int k = 0; k < c; ++k)
                img.at(x, y)[k] = float((x * 7 + y * 13 + k * 50) % 256) / 255.0f;
    return img;
}

std::string readBytes(const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}
void writeBytes(const std::string& file, const std::string& bytes) {
    std::ofstream(file, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

std::uint32_t crc32(const unsigned char* p, size_t n) {
    std::uint32_t c = 0xffffffffu;
    for (size_t i = 0; i < n; ++i) {
        c ^= p[i];
        for (int k = 0; k < 8; ++k)
            c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
    }
    return ~c;
}
void putBigEndian(std::string& s, size_t at, std::uint32_t v) {
    for (int i = 0; i < 4; ++i)
        s[at + i] = char((v >> (24 - 8 * i)) & 0xff);
}

} // namespace

class TestCoreImage : public QObject {
    Q_OBJECT
    QTemporaryDir m_dir;
    std::string path(const char* name) { return (m_dir.path() + "/" + name).toStdString(); }

private slots:
    void roundTrip_data() {
        QTest::addColumn<QString>("name");
        QTest::addColumn<int>("format");
        QTest::addColumn<double>("tolerance");
        QTest::newRow("png 8-bit") << "a.png" << int(PixelFormat::UInt8) << 0.5 / 255;
        QTest::newRow("exr half") << "a.exr" << int(PixelFormat::Half) << 1e-3;
        QTest::newRow("exr float") << "b.exr" << int(PixelFormat::Float) << 0.0;
        QTest::newRow("tiff 16-bit") << "a.tif" << int(PixelFormat::UInt16) << 0.5 / 65535;
        QTest::newRow("hdr rgbe") << "a.hdr" << int(PixelFormat::Float) << 1.0 / 128;
    }
    void roundTrip() {
        QFETCH(QString, name);
        QFETCH(int, format);
        QFETCH(double, tolerance);
        const bool rgb = name.endsWith(".hdr");
        const Image src = gradient(37, 21, rgb ? 3 : 4);
        std::string error;
        const std::string file = path(qPrintable(name));
        QVERIFY2(writeImage(file, src, PixelFormat(format), &error), error.c_str());
        Image back;
        QVERIFY2(readImage(file, back, &error), error.c_str());
        QCOMPARE(back.width, src.width);
        QCOMPARE(back.height, src.height);
        QCOMPARE(back.channels, src.channels);
        double worst = 0.0;
        for (size_t i = 0; i < src.pixels.size(); ++i) {
            const double e = std::abs(double(back.pixels[i]) - src.pixels[i]);
            // RGBE shares one exponent per pixel: error relative to the pixel's largest channel.
            const float* px = &src.pixels[i - i % src.channels];
            const double scale =
                rgb ? std::max({double(px[0]), double(px[1]), double(px[2]), 0.05}) : 1.0;
            worst = std::max(worst, e / scale);
        }
        QVERIFY2(worst <= tolerance + 1e-7, qPrintable(QString("worst error %1").arg(worst)));
        // No temp files left beside the target.
        QCOMPARE(QDir(m_dir.path())
                     .entryList(QStringList() << ".*tmp*", QDir::Files | QDir::Hidden)
                     .size(),
                 0);
    }

    void greyMapsToRgb() {
        Image grey(2, 1, 1);
        grey.pixels = {0.25f, 0.75f};
        QCOMPARE(grey.rgba(1, 0), glm::vec4(0.75f, 0.75f, 0.75f, 1.0f));
        std::string error;
        QVERIFY2(writeImage(path("grey.png"), grey, PixelFormat::UInt8, &error), error.c_str());
        Image back;
        QVERIFY2(readImage(path("grey.png"), back, &error), error.c_str());
        QCOMPARE(back.channels, 1);
    }

    void truncatedFilesAreErrorsNamingTheFile_data() {
        QTest::addColumn<QString>("name");
        QTest::newRow("png") << "t.png";
        QTest::newRow("exr") << "t.exr";
    }
    void truncatedFilesAreErrorsNamingTheFile() {
        QFETCH(QString, name);
        const std::string file = path(qPrintable(name));
        std::string error;
        QVERIFY(writeImage(file, gradient(64, 64, 4), PixelFormat::Half, &error));
        const std::string bytes = readBytes(file);
        writeBytes(file, bytes.substr(0, bytes.size() / 2));
        Image img;
        QVERIFY(!readImage(file, img, &error));
        qInfo("%s", error.c_str());
        QVERIFY2(error.find(file) != std::string::npos, error.c_str());
    }

    void missingAndUnknownFiles() {
        Image img;
        std::string error;
        QVERIFY(!readImage(path("nope.png"), img, &error));
        QVERIFY2(error.find("nope.png") != std::string::npos &&
                     error.find("no such file") != std::string::npos,
                 error.c_str());
        writeBytes(path("garbage.png"), "this is not an image at all, just text");
        QVERIFY(!readImage(path("garbage.png"), img, &error));
        QVERIFY2(error.find("garbage.png") != std::string::npos, error.c_str());
        qInfo("%s", error.c_str());
    }

    // A PNG whose IHDR claims 100000 x 100000 (CRC fixed so the header is valid) is refused from
    // the header, before any pixel is decoded (nothing near 160 GB is allocated).
    void hugeHeaderIsRefusedBeforeDecoding() {
        const std::string file = path("huge.png");
        std::string error;
        QVERIFY(writeImage(file, gradient(4, 4, 3), PixelFormat::UInt8, &error));
        std::string bytes = readBytes(file);
        // 8-byte signature, then IHDR: length(4) "IHDR"(4) width(4) height(4) ... CRC over
        // type+data.
        QCOMPARE(bytes.substr(12, 4), std::string("IHDR"));
        putBigEndian(bytes, 16, 100000);
        putBigEndian(bytes, 20, 100000);
        putBigEndian(bytes, 29,
                     crc32(reinterpret_cast<const unsigned char*>(bytes.data()) + 12, 17));
        writeBytes(file, bytes);
        Image img;
        QVERIFY(!readImage(file, img, &error));
        qInfo("%s", error.c_str());
        QVERIFY2(error.find("huge.png") != std::string::npos &&
                     error.find("100000x100000") != std::string::npos,
                 error.c_str());

        const std::string hdr = path("huge.hdr");
        writeBytes(hdr, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 100000 +X 100000\n");
        QVERIFY(!readImage(hdr, img, &error));
        QVERIFY2(error.find("huge.hdr") != std::string::npos, error.c_str());
        qInfo("%s", error.c_str());

        // Limits are the caller's: a small limit refuses a small image.
        ImageReadLimits tight;
        tight.maxSide = 2;
        QVERIFY(writeImage(path("small.png"), gradient(4, 4, 3), PixelFormat::UInt8, &error));
        QVERIFY(!readImage(path("small.png"), img, &error, tight));
    }
};

QTEST_GUILESS_MAIN(TestCoreImage)
#include "test_core_image.moc"

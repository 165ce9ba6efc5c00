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

/// A smooth ramp (JPEG-friendly) with values between 8-bit codes, so 16-bit and float formats
/// must keep more than 8 bits to pass.
Image smooth(int w, int h, int c) {
    Image img(w, h, c);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int k = 0; k < c; ++k)
                img.at(x, y)[k] = (float(x * 3 + y * 3 + k * 20) + 0.37f) / 255.0f;
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
    // Every format, every channel count and sample type it can hold: write -> read -> equal
    // within the format's precision. Rows where the format cannot hold the layout check the
    // documented nearest one (HDR grey -> RRR, JPEG drops alpha, BMP grey + alpha -> RRRA).
    void roundTrip_data() {
        QTest::addColumn<QString>("name");
        QTest::addColumn<int>("format");
        QTest::addColumn<int>("channels");
        QTest::addColumn<int>("readChannels");
        QTest::addColumn<double>("tolerance");
        struct Fmt {
            const char* ext;
            std::vector<PixelFormat> types;
            std::vector<int> channels;
        };
        const std::vector<Fmt> formats = {
            {"png", {PixelFormat::UInt8, PixelFormat::UInt16}, {1, 2, 3, 4}},
            {"jpg", {PixelFormat::UInt8}, {1, 2, 3, 4}},
            {"tif",
             {PixelFormat::UInt8, PixelFormat::UInt16, PixelFormat::Half, PixelFormat::Float},
             {1, 2, 3, 4}},
            {"exr", {PixelFormat::Half, PixelFormat::Float}, {1, 2, 3, 4}},
            {"hdr", {PixelFormat::Float}, {1, 3, 4}},
            {"tga", {PixelFormat::UInt8}, {1, 2, 3, 4}},
            {"bmp", {PixelFormat::UInt8}, {1, 2, 3, 4}},
        };
        const char* typeNames[] = {"u8", "u16", "half", "float"};
        for (const Fmt& f : formats)
            for (PixelFormat t : f.types)
                for (int c : f.channels) {
                    const QString ext = f.ext;
                    int readChannels = c;
                    if (ext == "hdr")
                        readChannels = 3;
                    else if (ext == "jpg" && (c == 2 || c == 4))
                        readChannels = c - 1;
                    else if (ext == "bmp" && c == 2)
                        readChannels = 4;
                    double tolerance = 0.0;
                    if (ext == "jpg")
                        tolerance = 6.0 / 255; // lossy (quality 95): checked per pixel
                    else if (ext == "hdr")
                        tolerance = 1.0 / 128; // RGBE: 8-bit mantissa, relative to the max
                    else if (t == PixelFormat::UInt8)
                        tolerance = 0.5 / 255;
                    else if (t == PixelFormat::UInt16)
                        tolerance = 0.5 / 65535;
                    else if (t == PixelFormat::Half)
                        tolerance = 1.0 / 2048; // 11-bit significand, values in [0, 1]
                    const QString row =
                        QString("%1 %2 %3ch").arg(ext, typeNames[static_cast<int>(t)]).arg(c);
                    QTest::newRow(qPrintable(row))
                        << QString("rt_%1_%2.%3")
                               .arg(typeNames[static_cast<int>(t)])
                               .arg(c)
                               .arg(ext)
                        << static_cast<int>(t) << c << readChannels << tolerance;
                }
    }
    void roundTrip() {
        QFETCH(QString, name);
        QFETCH(int, format);
        QFETCH(int, channels);
        QFETCH(int, readChannels);
        QFETCH(double, tolerance);
        const bool rgbe = name.endsWith(".hdr");
        const bool lossy = name.endsWith(".jpg");
        const Image src = smooth(37, 21, channels);
        std::string error;
        const std::string file = path(qPrintable(name));
        QVERIFY2(writeImage(file, src, PixelFormat(format), &error), error.c_str());
        ImageInfo info;
        QVERIFY2(readImageInfo(file, info, &error), error.c_str());
        QCOMPARE(info.width, src.width);
        QCOMPARE(info.height, src.height);
        Image back;
        QVERIFY2(readImage(file, back, &error), error.c_str());
        QCOMPARE(back.width, src.width);
        QCOMPARE(back.height, src.height);
        QCOMPARE(back.channels, readChannels);
        double worst = 0.0;
        for (int y = 0; y < src.height; ++y)
            for (int x = 0; x < src.width; ++x) {
                // Compared as RGBA, the way every consumer reads them (grey -> RRR).
                glm::vec4 a = src.rgba(x, y), b = back.rgba(x, y);
                if (readChannels == 3 || readChannels == 1)
                    a.a = 1.0f; // the format dropped alpha
                for (int k = 0; k < 4; ++k) {
                    const double e = std::abs(double(b[k]) - double(a[k]));
                    // RGBE shares one exponent per pixel: error relative to the largest channel.
                    const double scale =
                        rgbe && k < 3 ? std::max({double(a.r), double(a.g), double(a.b), 0.05})
                                      : 1.0;
                    worst = std::max(worst, e / scale);
                }
            }
        QVERIFY2(
            worst <= tolerance + 1e-7,
            qPrintable(QString("worst error %1 (%2 in 8-bit codes)").arg(worst).arg(worst * 255)));
        if (!lossy && !rgbe && format != int(PixelFormat::UInt8) && !name.endsWith(".tga") &&
            !name.endsWith(".bmp"))
            QVERIFY2(worst < 0.25 / 255, "more than 8-bit precision expected"); // not 8-bit
        // No temp files left beside the target.
        QCOMPARE(QDir(m_dir.path())
                     .entryList(QStringList() << ".*tmp*", QDir::Files | QDir::Hidden)
                     .size(),
                 0);
    }

    // EXIF/TIFF Orientation (TIFF 6.0 tag 274): every one of the 8 values is undone on read, so
    // display pixel (dx, dy) is the stored pixel the EXIF definition puts there.
    void orientationIsHonoured_data() {
        QTest::addColumn<int>("orientation");
        for (int o = 1; o <= 8; ++o)
            QTest::newRow(qPrintable(QString::number(o))) << o;
    }
    void orientationIsHonoured() {
        QFETCH(int, orientation);
        const int w = 5, h = 3;
        Image stored(w, h, 1);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                stored.at(x, y)[0] = float(y * w + x) / 255.0f;
        const std::string file = path(qPrintable(QString("orient%1.tif").arg(orientation)));
        std::string error;
        ImageWriteOptions options;
        options.orientation = orientation;
        QVERIFY2(writeImage(file, stored, PixelFormat::UInt8, &error, options), error.c_str());
        ImageInfo info;
        QVERIFY2(readImageInfo(file, info, &error), error.c_str());
        QCOMPARE(info.orientation, orientation);
        const bool swap = orientation >= 5;
        QCOMPARE(info.displayWidth(), swap ? h : w);
        Image shown;
        QVERIFY2(readImage(file, shown, &error), error.c_str());
        QCOMPARE(shown.width, swap ? h : w);
        QCOMPARE(shown.height, swap ? w : h);
        for (int dy = 0; dy < shown.height; ++dy)
            for (int dx = 0; dx < shown.width; ++dx) {
                int sx = dx, sy = dy;
                switch (orientation) {
                case 2:
                    sx = w - 1 - dx;
                    break; // mirrored left-right
                case 3:
                    sx = w - 1 - dx;
                    sy = h - 1 - dy;
                    break; // rotated 180
                case 4:
                    sy = h - 1 - dy;
                    break; // mirrored top-bottom
                case 5:
                    sx = dy;
                    sy = dx;
                    break; // transposed
                case 6:
                    sx = dy;
                    sy = h - 1 - dx;
                    break; // rotate 90 CW to show
                case 7:
                    sx = w - 1 - dy;
                    sy = h - 1 - dx;
                    break; // transversed
                case 8:
                    sx = w - 1 - dy;
                    sy = dx;
                    break; // rotate 90 CCW to show
                default:
                    break;
                }
                QCOMPARE(shown.at(dx, dy)[0], stored.at(sx, sy)[0]);
            }
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
        QTest::newRow("tiff") << "t.tif";
        QTest::newRow("jpeg") << "t.jpg";
        QTest::newRow("hdr") << "t.hdr";
        QTest::newRow("tga") << "t.tga";
        QTest::newRow("bmp") << "t.bmp";
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
        QVERIFY2(error.find(file) != std::string::npos &&
                     error.find("truncated") != std::string::npos,
                 error.c_str());
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
        QVERIFY2(error.find("garbage.png") != std::string::npos &&
                     error.find("unknown format") != std::string::npos,
                 error.c_str());
        qInfo("%s", error.c_str());
        writeBytes(path("garbage.xyz"), "neither a known extension nor known content");
        QVERIFY(!readImage(path("garbage.xyz"), img, &error));
        QVERIFY2(error.find("garbage.xyz") != std::string::npos &&
                     error.find("unknown format") != std::string::npos,
                 error.c_str());
        qInfo("%s", error.c_str());
        writeBytes(path("empty.png"), "");
        QVERIFY(!readImage(path("empty.png"), img, &error));
        QVERIFY2(error.find("empty.png") != std::string::npos &&
                     error.find("empty") != std::string::npos,
                 error.c_str());
        ImageInfo info;
        QVERIFY(!readImageInfo(path("nope.png"), info, &error));
        QVERIFY2(error.find("no such file") != std::string::npos, error.c_str());
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
                     error.find("100000x100000") != std::string::npos &&
                     error.find("16384") != std::string::npos,
                 error.c_str());
        // The header alone is read: with the limits lifted the probe succeeds and reports the
        // claimed size, which proves nothing was decoded (160 GB as float RGBA).
        ImageReadLimits none;
        none.maxSide = 1 << 30;
        none.maxDecodedBytes = ~std::uint64_t(0);
        ImageInfo info;
        QVERIFY2(readImageInfo(file, info, &error, none), error.c_str());
        QCOMPARE(info.width, 100000);
        QCOMPARE(info.height, 100000);
        QCOMPARE(info.format, std::string("png"));
        // The decoded-size limit is checked too, with both numbers in the message.
        ImageReadLimits byteLimit;
        byteLimit.maxSide = 1 << 30;
        QVERIFY(!readImage(file, img, &error, byteLimit));
        QVERIFY2(error.find("MiB") != std::string::npos &&
                     error.find("1024 MiB") != std::string::npos,
                 error.c_str());
        qInfo("%s", error.c_str());

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

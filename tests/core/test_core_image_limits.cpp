// Image decode limits from VELVET_MAX_IMAGE_SIDE / VELVET_MAX_IMAGE_BYTES (core/image.h, issue 6):
// the parser's accepted and refused values, and that the variables, set before the first image
// read of the process, are the limits readImage() applies.
#include "core/image.h"

#include <QTemporaryDir>
#include <QtTest>
#include <cstdlib>

using namespace velvet;

class TestCoreImageLimits : public QObject {
    Q_OBJECT
private slots:
    void initTestCase() {
        // Before anything constructs an ImageReadLimits (the variables are read once).
        qputenv("VELVET_MAX_IMAGE_SIDE", "32");
        qputenv("VELVET_MAX_IMAGE_BYTES", "64K");
    }

    void parsesValidValues() {
        ImageReadLimits l{1, 1};
        std::string error;
        QVERIFY(parseImageLimits(nullptr, nullptr, l, &error));
        QCOMPARE(l.maxSide, kDefaultMaxImageSide);
        QCOMPARE(l.maxDecodedBytes, kDefaultMaxImageBytes);
        QVERIFY(parseImageLimits("4096", "2G", l, &error));
        QCOMPARE(l.maxSide, 4096);
        QCOMPARE(l.maxDecodedBytes, std::uint64_t(2) << 30);
        QVERIFY(parseImageLimits("", "1048576", l, &error)); // empty: unset
        QCOMPARE(l.maxSide, kDefaultMaxImageSide);
        QCOMPARE(l.maxDecodedBytes, std::uint64_t(1) << 20);
        QVERIFY(parseImageLimits("1", "512mib", l, &error));
        QCOMPARE(l.maxDecodedBytes, std::uint64_t(512) << 20);
    }

    void refusesBadValues_data() {
        QTest::addColumn<QByteArray>("side");
        QTest::addColumn<QByteArray>("bytes");
        QTest::addColumn<QString>("named");
        QTest::newRow("side not a number") << QByteArray("big") << QByteArray() << "SIDE";
        QTest::newRow("side zero") << QByteArray("0") << QByteArray() << "SIDE";
        QTest::newRow("side negative") << QByteArray("-5") << QByteArray() << "SIDE";
        QTest::newRow("side with suffix") << QByteArray("4K") << QByteArray() << "SIDE";
        QTest::newRow("side too large") << QByteArray("2000000") << QByteArray() << "SIDE";
        QTest::newRow("bytes unknown suffix") << QByteArray() << QByteArray("3T") << "BYTES";
        QTest::newRow("bytes too small") << QByteArray() << QByteArray("100") << "BYTES";
        QTest::newRow("bytes overflow") << QByteArray() << QByteArray("99999999999G") << "BYTES";
        QTest::newRow("bytes fraction") << QByteArray() << QByteArray("1.5G") << "BYTES";
    }
    void refusesBadValues() {
        QFETCH(QByteArray, side);
        QFETCH(QByteArray, bytes);
        QFETCH(QString, named);
        ImageReadLimits l{1, 1};
        std::string error;
        QVERIFY(!parseImageLimits(side.isNull() ? nullptr : side.constData(),
                                  bytes.isNull() ? nullptr : bytes.constData(), l, &error));
        const QString message = QString::fromStdString(error);
        QVERIFY2(message.contains("VELVET_MAX_IMAGE_" + named), error.c_str());
        QVERIFY2(message.contains(QString::fromLatin1(side.isNull() ? bytes : side)),
                 error.c_str());
        // The bad variable keeps the built-in limit.
        QCOMPARE(l.maxSide, kDefaultMaxImageSide);
        QCOMPARE(l.maxDecodedBytes, kDefaultMaxImageBytes);
    }

    void environmentIsTheDefault() {
        QCOMPARE(imageLimitsProblem(), std::string());
        const ImageReadLimits limits;
        QCOMPARE(limits.maxSide, 32);
        QCOMPARE(limits.maxDecodedBytes, std::uint64_t(64) << 10);

        QTemporaryDir dir;
        const std::string small = dir.filePath("small.png").toStdString();
        const std::string wide = dir.filePath("wide.png").toStdString();
        const std::string big = dir.filePath("big.png").toStdString();
        std::string error;
        QVERIFY2(writeImage(small, Image(32, 32, 4), PixelFormat::UInt8, &error), error.c_str());
        QVERIFY2(writeImage(wide, Image(33, 1, 4), PixelFormat::UInt8, &error), error.c_str());
        Image img;
        QVERIFY2(readImage(small, img, &error), error.c_str()); // 32x32x16 B = 16 KiB
        QVERIFY(!readImage(wide, img, &error));
        QVERIFY2(QString::fromStdString(error).contains("limit of 32 pixels"), error.c_str());
        // 32 a side but 64 KiB decoded is 1024 pixels: a 32x32 passes, explicit limits win.
        QVERIFY2(writeImage(big, Image(200, 30, 4), PixelFormat::UInt8, &error), error.c_str());
        QVERIFY(!readImage(big, img, &error, ImageReadLimits{256, std::uint64_t(64) << 10}));
        QVERIFY2(QString::fromStdString(error).contains("limit of 64 KiB"), error.c_str());
        QVERIFY2(readImage(big, img, &error, ImageReadLimits{256, std::uint64_t(1) << 20}),
                 error.c_str());
    }
};

QTEST_GUILESS_MAIN(TestCoreImageLimits)
#include "test_core_image_limits.moc"

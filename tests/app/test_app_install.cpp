// Issue 17, item 16: `cmake --install` into a DESTDIR gives a tree that runs from anywhere: the
// installed velvet finds its resources under share/velvet (not the source tree: VELVET_RESOURCES
// is unset and `velvet info` names the folder), renders headless and takes an editor screenshot
// (under xvfb) from another working folder; the .desktop entry and SVG icon are where the
// freedesktop specifications put them; CPack's DEB has the computed library dependencies.
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QImage>
#include <QProcess>
#include <QTemporaryDir>
#include <QTest>
#include <QXmlStreamReader>

namespace {

struct Run {
    int exitCode = -1;
    bool finished = false;
    QString out, err;
};

/// Runs @p program in @p workingDir with the test's environment minus VELVET_RESOURCES (which
/// ctest sets to the source tree) and with throwaway home folders for settings and autosaves.
Run run(const QString& program, const QStringList& args, const QString& workingDir,
        const QMap<QString, QString>& extra = {}, int timeoutMs = 240000) {
    QProcess p;
    p.setWorkingDirectory(workingDir);
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    env.remove(QStringLiteral("VELVET_RESOURCES"));
    for (auto it = extra.begin(); it != extra.end(); ++it)
        env.insert(it.key(), it.value());
    p.setProcessEnvironment(env);
    p.start(program, args);
    Run r;
    r.finished = p.waitForFinished(timeoutMs);
    if (!r.finished) {
        p.kill();
        p.waitForFinished();
    }
    r.exitCode = p.exitCode();
    r.out = QString::fromUtf8(p.readAllStandardOutput());
    r.err = QString::fromUtf8(p.readAllStandardError());
    return r;
}

/// True when @p image has more than a handful of distinct colours (a picture, not a blank).
bool looksRendered(const QImage& image) {
    QSet<QRgb> colours;
    for (int y = 0; y < image.height(); y += 7)
        for (int x = 0; x < image.width(); x += 7)
            colours.insert(image.pixel(x, y));
    return colours.size() > 16;
}

} // namespace

class TestAppInstall : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void layoutFollowsFreedesktop();
    void installedRenderFromAnotherFolder();
    void installedScreenshotFromAnotherFolder();
    void debianPackageHasComputedDependencies();

private:
    QString installed(const QString& relative) const { return m_prefix + '/' + relative; }
    QMap<QString, QString> homes() const;

    QTemporaryDir m_dir;
    QString m_prefix;    ///< DESTDIR + /usr
    QString m_elsewhere; ///< a working folder with nothing of Velvet's in it
};

void TestAppInstall::initTestCase() {
    QVERIFY(m_dir.isValid());
    const QString destdir = m_dir.filePath(QStringLiteral("stage"));
    const Run install = run(QStringLiteral(VELVET_CMAKE),
                            {QStringLiteral("--install"), QStringLiteral(VELVET_BUILD_DIR),
                             QStringLiteral("--prefix"), QStringLiteral("/usr")},
                            m_dir.path(), {{QStringLiteral("DESTDIR"), destdir}});
    QVERIFY2(install.finished && install.exitCode == 0, qPrintable(install.out + install.err));
    m_prefix = destdir + QStringLiteral("/usr");
    m_elsewhere = m_dir.filePath(QStringLiteral("elsewhere"));
    QVERIFY(QDir().mkpath(m_elsewhere));
}

QMap<QString, QString> TestAppInstall::homes() const {
    return {{QStringLiteral("HOME"), m_dir.filePath(QStringLiteral("home"))},
            {QStringLiteral("XDG_CONFIG_HOME"), m_dir.filePath(QStringLiteral("home/config"))},
            {QStringLiteral("XDG_DATA_HOME"), m_dir.filePath(QStringLiteral("home/data"))},
            {QStringLiteral("XDG_CACHE_HOME"), m_dir.filePath(QStringLiteral("home/cache"))}};
}

void TestAppInstall::layoutFollowsFreedesktop() {
    const QFileInfo binary(installed(QStringLiteral("bin/velvet")));
    QVERIFY(binary.isFile() && binary.isExecutable());
    QVERIFY(QFileInfo(installed(QStringLiteral("share/velvet/resources/shaders"))).isDir());
    for (const char* hdri : {"city", "forest", "interior", "studio", "sunset"})
        QVERIFY2(QFileInfo::exists(
                     installed(QStringLiteral("share/velvet/resources/hdri/%1.exr").arg(hdri))),
                 hdri);
    QVERIFY(
        QFileInfo::exists(installed(QStringLiteral("share/velvet/resources/hdri/LICENSE.txt"))));
    // OpenImageIO's module, loaded on first use from bin/../lib/velvet (core/image_codec.h); the
    // installed render below decodes the stage's EXR through it. (The sanitizer build links
    // the codec into the executable instead: no module.)
    QCOMPARE(QFileInfo::exists(installed(QStringLiteral("lib/velvet/velvet-image-codec.so"))),
             bool(VELVET_IMAGE_CODEC_MODULE));

    // Desktop Entry Specification: a [Desktop Entry] group with Type, Name, Exec and Icon.
    QFile desktop(installed(QStringLiteral("share/applications/velvet.desktop")));
    QVERIFY(desktop.open(QIODevice::ReadOnly | QIODevice::Text));
    const QStringList lines = QString::fromUtf8(desktop.readAll()).split('\n');
    QCOMPARE(lines.value(0), QStringLiteral("[Desktop Entry]"));
    QVERIFY(lines.contains(QStringLiteral("Type=Application")));
    QVERIFY(lines.contains(QStringLiteral("Name=Velvet")));
    QVERIFY(lines.contains(QStringLiteral("Icon=velvet")));
    QVERIFY(lines.contains(QStringLiteral("Exec=velvet %f")));

    // Icon Theme Specification: hicolor/scalable/apps/NAME.svg, named as Icon= says; valid SVG.
    QFile icon(installed(QStringLiteral("share/icons/hicolor/scalable/apps/velvet.svg")));
    QVERIFY(icon.open(QIODevice::ReadOnly));
    QXmlStreamReader xml(&icon);
    QVERIFY(xml.readNextStartElement());
    QCOMPARE(xml.name().toString(), QStringLiteral("svg"));
    while (!xml.atEnd())
        xml.readNext();
    QVERIFY2(!xml.hasError(), qPrintable(xml.errorString()));
}

void TestAppInstall::installedRenderFromAnotherFolder() {
    const QString velvet = installed(QStringLiteral("bin/velvet"));
    QMap<QString, QString> env = homes();
    const Run info = run(velvet, {QStringLiteral("info")}, m_elsewhere, env);
    QVERIFY2(info.finished, qPrintable(info.err));
    const QString resources =
        QFileInfo(installed(QStringLiteral("share/velvet/resources"))).canonicalFilePath();
    QVERIFY2(info.out.contains(QStringLiteral("Resources: ") + resources), qPrintable(info.out));

    const Run render =
        run(velvet, {QStringLiteral("render"), QStringLiteral("-o"), QStringLiteral("x.png")},
            m_elsewhere, env);
    QVERIFY2(render.finished && render.exitCode == 0, qPrintable(render.out + render.err));
    const QImage image(QDir(m_elsewhere).filePath(QStringLiteral("x.png")));
    QVERIFY(!image.isNull());
    QCOMPARE(image.size(), QSize(512, 512));
    QVERIFY(looksRendered(image));
}

void TestAppInstall::installedScreenshotFromAnotherFolder() {
    if (qEnvironmentVariableIsEmpty("DISPLAY"))
        QSKIP("needs a display (ctest runs this test under xvfb-run)");
    const Run shot =
        run(installed(QStringLiteral("bin/velvet")),
            {QStringLiteral("--screenshot"), QStringLiteral("window.png")}, m_elsewhere, homes());
    QVERIFY2(shot.finished && shot.exitCode == 0, qPrintable(shot.out + shot.err));
    const QImage image(QDir(m_elsewhere).filePath(QStringLiteral("window.png")));
    QVERIFY(!image.isNull());
    QVERIFY2(image.width() >= 640 && image.height() >= 400,
             qPrintable(QStringLiteral("%1x%2").arg(image.width()).arg(image.height())));
    QVERIFY(looksRendered(image));
}

void TestAppInstall::debianPackageHasComputedDependencies() {
    const QString out = m_dir.filePath(QStringLiteral("package"));
    const Run cpack =
        run(QStringLiteral(VELVET_CPACK),
            {QStringLiteral("-G"), QStringLiteral("DEB"), QStringLiteral("--config"),
             QStringLiteral(VELVET_BUILD_DIR "/CPackConfig.cmake"), QStringLiteral("-B"), out},
            m_dir.path());
    QVERIFY2(cpack.finished && cpack.exitCode == 0, qPrintable(cpack.out + cpack.err));
    const QStringList debs = QDir(out).entryList({QStringLiteral("velvet_*.deb")}, QDir::Files);
    QCOMPARE(debs.size(), 1);
    const QString deb = QDir(out).filePath(debs[0]);
    const Run depends = run(QStringLiteral("dpkg-deb"),
                            {QStringLiteral("-f"), deb, QStringLiteral("Depends")}, m_dir.path());
    QVERIFY2(depends.exitCode == 0, qPrintable(depends.err));
    // dpkg-shlibdeps' answer names the packages of the linked libraries.
    for (const char* library :
         {"libqt6gui6", "libqt6widgets6", "libopenimageio", "libepoxy0", "libegl1"})
        QVERIFY2(depends.out.contains(QLatin1String(library)), qPrintable(depends.out));
    const Run contents = run(QStringLiteral("dpkg-deb"), {QStringLiteral("-c"), deb}, m_dir.path());
    for (const char* path : {"./usr/bin/velvet", "./usr/share/applications/velvet.desktop",
                             "./usr/share/icons/hicolor/scalable/apps/velvet.svg",
                             "./usr/share/velvet/resources/hdri/sunset.exr"})
        QVERIFY2(contents.out.contains(QLatin1String(path)), path);
    QCOMPARE(contents.out.contains(QLatin1String("./usr/lib/velvet/velvet-image-codec.so")),
             bool(VELVET_IMAGE_CODEC_MODULE));
}

QTEST_GUILESS_MAIN(TestAppInstall)
#include "test_app_install.moc"

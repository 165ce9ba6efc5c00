// The renderer's own warnings reach the host's problem list (Renderer::takeWarnings), once each,
// and never stderr: here with $OCIO naming a config that does not exist, so the display falls
// back to the built-in sRGB curve.
#include "core/image.h"
#include "render/offscreen.h"
#include "render/renderer.h"
#include "render_test_util.h"

#include <QTemporaryDir>
#include <QtTest>
#include <cstdio>
#include <unistd.h>

using namespace velvet;

namespace {

/// Runs @p f with file descriptor 2 redirected to a file; returns what was written to it.
template <typename F>
std::string capturingStderr(const QString& file, F&& f) {
    std::fflush(stderr);
    const int saved = dup(2);
    FILE* out = std::fopen(file.toUtf8().constData(), "w");
    dup2(fileno(out), 2);
    f();
    std::fflush(stderr);
    dup2(saved, 2);
    close(saved);
    std::fclose(out);
    return test::readText(file.toStdString());
}

} // namespace

class TestRenderWarnings : public QObject {
    Q_OBJECT
    QTemporaryDir m_dir;
    std::string m_missing;

private slots:
    void initTestCase() {
        QVERIFY(m_dir.isValid());
        m_missing = (m_dir.path() + "/no-such-config.ocio").toStdString();
        qputenv("OCIO", QByteArray::fromStdString(m_missing));
        std::string error;
        QVERIFY2(test::headlessContext(&error), error.c_str());
    }

    // initialize() reports the missing config once, as a warning naming the file; later frames
    // and scene updates add nothing; nothing goes to stderr. A new config request
    // (setColorManagement) tries, and warns, once more.
    void missingConfigIsWarnedOnceThroughTheProblemList() {
        render::Renderer renderer;
        std::string error;
        bool ok = false;
        const std::string printed = capturingStderr(m_dir.path() + "/stderr.txt",
                                                    [&] { ok = renderer.initialize(&error); });
        QVERIFY2(ok, error.c_str());
        QVERIFY2(printed.find("OpenColorIO") == std::string::npos, printed.c_str());
        const Problems first = renderer.takeWarnings();
        QCOMPARE(first.items.size(), size_t(1));
        const Problem& p = first.items[0];
        qInfo("%s", p.toString().c_str());
        QVERIFY(p.severity == Problem::Severity::Warning);
        QCOMPARE(p.file, m_missing);
        QVERIFY2(p.message.find("sRGB") != std::string::npos, p.message.c_str());

        render::OffscreenTarget target;
        QVERIFY2(target.resize(32, 32, &error), error.c_str());
        render::FrameSettings fs;
        fs.width = fs.height = 32;
        for (int i = 0; i < 2; ++i)
            QVERIFY2(renderer.render(fs, target.framebuffer(), &error), error.c_str());
        renderer.setScene(Scene{});
        QVERIFY(renderer.takeWarnings().items.empty());

        renderer.setColorManagement(nullptr);
        QVERIFY2(renderer.render(fs, target.framebuffer(), &error), error.c_str());
        QCOMPARE(renderer.takeWarnings().items.size(), size_t(1));
        QVERIFY2(renderer.render(fs, target.framebuffer(), &error), error.c_str());
        QVERIFY(renderer.takeWarnings().items.empty());
    }

    // renderSceneOffscreen (the CLI's render) hands them to its problems, which the CLI prints.
    void offscreenRenderReportsThem() {
        render::FrameSettings fs;
        fs.width = fs.height = 32;
        Problems problems;
        std::string error;
        Image display;
        QVERIFY2(render::renderSceneOffscreen(Scene{}, fs, nullptr, &display, &error, &problems),
                 error.c_str());
        QCOMPARE(problems.items.size(), size_t(1));
        QCOMPARE(problems.items[0].file, m_missing);
        QVERIFY(!problems.hasErrors());
    }
};

QTEST_GUILESS_MAIN(TestRenderWarnings)
#include "test_render_warnings.moc"

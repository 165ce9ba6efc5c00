// Asynchronous texture loading (issue 16): with Renderer::setAsyncTextures a 2048² map loads
// on a worker thread while frames keep coming; each frame uploads at most the budget (a count
// of bytes, not a time), coarsest level first, so a coarse proxy draws before the full map; the
// completed image equals the synchronous one and a headless render's; one file in two slots is
// decoded once; its level 0 streams from the mip cache's entry (loaded from the file again when
// the entry goes mid-stream); and a large texture's storage is made on a thread of its own, in a
// context sharing the drawing one's objects (render/texture_storage_thread.h).
#include "core/image.h"
#include "render/headless_context.h"
#include "render/offscreen.h"
#include "render/renderer.h"
#include "render/texture_storage_thread.h"
#include "render_test_util.h"

#include <QTemporaryDir>
#include <QtTest>
#include <cmath>
#include <filesystem>
#include <memory>

using namespace velvet;
namespace fs = std::filesystem;

namespace {

constexpr int kSize = 64;
constexpr std::uint64_t kBudget = 256 * 1024;

glm::vec3 centre(const Image& img) {
    glm::vec3 sum(0.0f);
    for (int y = kSize / 2 - 3; y < kSize / 2 + 3; ++y)
        for (int x = kSize / 2 - 3; x < kSize / 2 + 3; ++x)
            sum += glm::vec3(img.rgba(x, y));
    return sum / 36.0f;
}

float maxDifference(const Image& a, const Image& b) {
    float worst = 0.0f;
    for (size_t i = 0; i < a.pixels.size() && i < b.pixels.size(); ++i)
        worst = std::max(worst, std::abs(a.pixels[i] - b.pixels[i]));
    return worst;
}

} // namespace

class TestRenderTextureLoading : public QObject {
    Q_OBJECT
    QTemporaryDir m_dir;
    fs::path m_map;
    Image m_synchronous;                               ///< the map's frame, rendered synchronously
    std::unique_ptr<render::OffscreenTarget> m_target; ///< kSize², every case draws into it

    static render::FrameSettings frameSettings() {
        render::FrameSettings fs;
        fs.width = fs.height = kSize;
        return fs;
    }

    Scene scene() const {
        Scene s;
        s.lights.clear();
        s.environment.hdri.clear();
        s.environment.color = glm::vec3(1.0f);
        s.material.setColor(ParamId::BaseColor, glm::vec3(0.2f, 0.2f, 1.0f));
        s.material.setScalar(ParamId::SheenWeight, 0.0f);
        TextureRef ref;
        ref.file = m_map.string();
        s.material.setTexture(TextureSlot::BaseColor, ref);
        s.material.setTexture(TextureSlot::SheenColor, ref); // the same file again
        return s;
    }

private slots:
    void initTestCase() {
        std::string error;
        QVERIFY2(test::headlessContext(&error), error.c_str());
        m_target = std::make_unique<render::OffscreenTarget>();
        QVERIFY(m_target->resize(kSize, kSize, &error));
        qputenv("XDG_CACHE_HOME", (m_dir.path() + "/cache").toUtf8());
        // A red map with a fine checker in green: level 0 differs from its coarse levels.
        Image map(2048, 2048, 3);
        for (int y = 0; y < map.height; ++y)
            for (int x = 0; x < map.width; ++x) {
                float* p = map.at(x, y);
                p[0] = 1.0f, p[1] = float((x + y) % 2) * 0.5f, p[2] = 0.0f;
            }
        m_map = fs::path(m_dir.path().toStdString()) / "red.png";
        QVERIFY2(writeImage(m_map, map, PixelFormat::UInt8, &error), error.c_str());
    }

    void cleanupTestCase() { m_target.reset(); }

    void framesKeepComingWhileAMapLoads() {
        std::string error;
        render::OffscreenTarget& target = *m_target;
        const render::FrameSettings fs = frameSettings();

        // The synchronous image first (the default: update() returns with the map uploaded).
        Image synchronous;
        {
            render::Renderer sync;
            QVERIFY2(sync.initialize(&error), error.c_str());
            sync.setScene(scene());
            sync.finishEnvironment(); // the same environment bake as below, complete
            QVERIFY(sync.render(fs, target.framebuffer(), &error));
            synchronous = sync.readLinear();
            QCOMPARE(sync.textureProgress().loading, 0);
        }

        render::Renderer renderer;
        QVERIFY2(renderer.initialize(&error), error.c_str());
        renderer.setAsyncTextures(true);
        renderer.setTextureUploadBudget(kBudget);
        Scene without = scene();
        without.material.setTexture(TextureSlot::BaseColor, {});
        without.material.setTexture(TextureSlot::SheenColor, {});
        renderer.setScene(without);
        renderer.finishEnvironment();
        QVERIFY(renderer.render(fs, target.framebuffer(), &error));
        const glm::vec3 parameter = centre(renderer.readLinear());

        renderer.setScene(scene());
        // Nothing is on the GPU before a frame: the next one draws what has arrived.
        QCOMPARE(renderer.textureProgress().loading, 1);
        QCOMPARE(renderer.textureProgress().total, 1); // two slots, one texture
        int frames = 0, parameterFrames = 0;
        while (renderer.textureProgress().loading > 0 && frames < 20000) {
            QVERIFY(renderer.render(fs, target.framebuffer(), &error));
            if (renderer.textureUploadStats().bytes == 0 &&
                glm::distance(centre(renderer.readLinear()), parameter) < 1e-3f)
                ++parameterFrames; // the load has not arrived: the parameter value is drawn
            ++frames;
        }
        const render::TextureUploadStats& up = renderer.textureUploadStats();
        // 2048² RGBA8 with every level: at least this many frames at the budget.
        std::uint64_t bytes = 0;
        for (int s = 2048; s >= 1; s /= 2)
            bytes += std::uint64_t(s) * s * 4;
        qInfo("%d frames while loading (%d with the parameter value, %d with a coarse proxy); "
              "at most %llu bytes a frame; worst upload %.1f ms",
              frames, parameterFrames, up.proxyFrames,
              static_cast<unsigned long long>(up.worstFrameBytes), up.worstFrameMs);
        QCOMPARE(up.bytes, bytes);
        // Level 0 (16 MiB) came from the cache entry band by band, never whole in memory.
        QCOMPARE(up.streamedBytes, std::uint64_t(2048) * 2048 * 4);
        QVERIFY(up.worstFrameBytes <= kBudget);
        QVERIFY(std::uint64_t(up.frames) >= bytes / kBudget);
        QVERIFY(up.proxyFrames > 0);
        QCOMPARE(renderer.textureDecodes() + renderer.textureCacheHits(), std::uint64_t(1));

        // Complete: the same image as the synchronous renderer's.
        QVERIFY(renderer.render(fs, target.framebuffer(), &error));
        const Image done = renderer.readLinear();
        const float diff = maxDifference(done, synchronous);
        QVERIFY2(diff < 1e-4f, qPrintable(QString::number(diff)));
        QVERIFY(glm::distance(centre(done), parameter) > 0.05f);

        // Headless rendering waits for every texture: never a proxy.
        Image headless;
        QVERIFY2(render::renderSceneOffscreen(scene(), fs, &headless, nullptr, &error),
                 error.c_str());
        QVERIFY(maxDifference(headless, synchronous) < 1e-4f);
        m_synchronous = synchronous;
    }

    // The 2048² map's storage (22 MiB with mips) is made on the storage thread: frames keep
    // coming meanwhile, the finished image is the synchronous one, and a renderer dropped while
    // its storage is still being made frees it (no leak, no crash).
    void storageIsMadeOffTheDrawingThread() {
        QVERIFY(!m_synchronous.pixels.empty()); // framesKeepComingWhileAMapLoads ran first
        std::string error;
        const render::FrameSettings fs = frameSettings();
        {
            render::Renderer renderer;
            QVERIFY2(renderer.initialize(&error), error.c_str());
            renderer.setAsyncTextures(true);
            auto worker = render::HeadlessContext::workerSharingCurrent(&error);
            QVERIFY2(worker, error.c_str());
            renderer.setTextureStorageContext(std::move(worker));
            renderer.setScene(scene());
            renderer.finishEnvironment();
            int frames = 0;
            while (renderer.textureProgress().loading > 0 && frames < 20000) {
                QVERIFY(renderer.render(fs, m_target->framebuffer(), &error));
                ++frames;
            }
            QCOMPARE(renderer.textureUploadStats().storageOffThread, 1);
            QVERIFY(renderer.render(fs, m_target->framebuffer(), &error));
            const float diff = maxDifference(renderer.readLinear(), m_synchronous);
            QVERIFY2(diff < 1e-4f, qPrintable(QString::number(diff)));
        }
        {
            render::Renderer renderer;
            QVERIFY2(renderer.initialize(&error), error.c_str());
            renderer.setAsyncTextures(true);
            renderer.setTextureStorageContext(
                render::HeadlessContext::workerSharingCurrent(&error));
            renderer.setScene(scene());
            for (int i = 0; i < 3; ++i)
                QVERIFY(renderer.render(fs, m_target->framebuffer(), &error));
        } // dropped with the storage perhaps in flight: abandoned, freed by whoever holds it
    }

    // A worker context that cannot be made current: the storage is made on the drawing thread
    // after all, and the map still loads.
    void aWorkerThatCannotStartFallsBack() {
        struct Broken final : render::WorkerGlContext {
            bool makeCurrent(std::string* error) override {
                *error = "no context here";
                return false;
            }
        };
        render::TextureStorageThread thread(std::make_unique<Broken>());
        auto pending = thread.allocate({16, 16, 1, 0x8058 /* GL_RGBA8 */});
        unsigned texture = 0;
        std::string why;
        QCOMPARE(render::TextureStorageThread::wait(*pending, texture, &why),
                 render::TextureStorageThread::State::Failed);
        QCOMPARE(why, std::string("no context here"));
        QCOMPARE(texture, 0u);

        std::string error;
        render::Renderer renderer;
        QVERIFY2(renderer.initialize(&error), error.c_str());
        renderer.setAsyncTextures(true);
        renderer.setTextureStorageContext(std::make_unique<Broken>());
        renderer.setScene(scene());
        renderer.finishEnvironment();
        int frames = 0;
        while (renderer.textureProgress().loading > 0 && frames < 20000) {
            QVERIFY(renderer.render(frameSettings(), m_target->framebuffer(), &error));
            ++frames;
        }
        QCOMPARE(renderer.textureUploadStats().storageOffThread, 0);
        QVERIFY(renderer.render(frameSettings(), m_target->framebuffer(), &error));
        QVERIFY(maxDifference(renderer.readLinear(), m_synchronous) < 1e-4f);
    }

    // The cache entry level 0 streams from goes mid-stream (a cache cleaned by hand): a warning
    // names the entry, the file is loaded again with level 0 in memory, the coarse levels draw
    // meanwhile, and the finished image is the synchronous one.
    void anEntryGoneMidStreamLoadsTheFileAgain() {
        QVERIFY(!m_synchronous.pixels.empty());
        std::string error;
        render::OffscreenTarget& target = *m_target;
        const render::FrameSettings fs = frameSettings();
        render::Renderer renderer;
        QVERIFY2(renderer.initialize(&error), error.c_str());
        renderer.setAsyncTextures(true);
        renderer.setTextureUploadBudget(kBudget);
        renderer.setScene(scene());
        renderer.finishEnvironment();
        int frames = 0;
        while (renderer.textureUploadStats().streamedBytes == 0 && frames++ < 20000)
            QVERIFY(renderer.render(fs, target.framebuffer(), &error));
        QVERIFY(renderer.textureProgress().loading > 0);
        const fs::path cache = fs::path(m_dir.path().toStdString()) / "cache";
        QVERIFY(fs::remove_all(cache) > 0);
        Problems warnings;
        while (renderer.textureProgress().loading > 0 && frames++ < 40000) {
            QVERIFY(renderer.render(fs, target.framebuffer(), &error));
            for (Problem& p : renderer.takeWarnings().items)
                warnings.items.push_back(std::move(p));
        }
        QVERIFY(!warnings.items.empty());
        const std::string text = warnings.items[0].toString();
        qInfo("%s", text.c_str());
        QVERIFY2(text.find("could not be read") != std::string::npos, text.c_str());
        QVERIFY2(text.find("red.png") != std::string::npos, text.c_str());
        QCOMPARE(renderer.textureDecodes(), std::uint64_t(1)); // the hit, then the file again
        QCOMPARE(renderer.textureCacheHits(), std::uint64_t(1));
        QVERIFY(renderer.render(fs, target.framebuffer(), &error));
        const float diff = maxDifference(renderer.readLinear(), m_synchronous);
        QVERIFY2(diff < 1e-4f, qPrintable(QString::number(diff)));
    }

    // A missing file in asynchronous mode: the problem comes through takeWarnings(), naming
    // the file and the slot, and the parameter value stays.
    void missingFileIsReportedLater() {
        std::string error;
        render::OffscreenTarget& target = *m_target;
        const render::FrameSettings fs = frameSettings();
        render::Renderer renderer;
        QVERIFY2(renderer.initialize(&error), error.c_str());
        renderer.setAsyncTextures(true);
        Scene s = scene();
        TextureRef missing;
        missing.file = (fs::path(m_dir.path().toStdString()) / "gone.png").string();
        s.material.setTexture(TextureSlot::BaseColor, missing);
        s.material.setTexture(TextureSlot::SheenColor, {});
        renderer.setScene(s);
        Problems warnings;
        for (int i = 0; i < 2000 && warnings.items.empty(); ++i) {
            QVERIFY(renderer.render(fs, target.framebuffer(), &error));
            warnings = renderer.takeWarnings();
            if (warnings.items.empty())
                QTest::qWait(2);
        }
        QVERIFY(!warnings.items.empty());
        const std::string text = warnings.items[0].toString();
        QVERIFY2(text.find("gone.png") != std::string::npos, text.c_str());
        QVERIFY2(text.find("textures.baseColor") != std::string::npos, text.c_str());
        QCOMPARE(renderer.textureProgress().loading, 0);
    }
};

QTEST_GUILESS_MAIN(TestRenderTextureLoading)
#include "test_render_texture_loading.moc"

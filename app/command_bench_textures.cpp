// velvet bench --textures [--json] [--short]: the texture path of issue 16 measured in one
// process on a generated 4096² RGBA8 map (2048² with --short): first and second load (on-disk
// mip cache cold, then warm), the float path beside it, peak memory against the map's GPU size,
// and the frames an asynchronous load keeps drawing. DESIGN.md, "Measuring".
#include "app/cli.h"
#include "core/color_management.h"
#include "core/image.h"
#include "core/image_ops.h"
#include "core/mip_texture.h"
#include "core/texture_cache.h"
#include "render/headless_context.h"
#include "render/offscreen.h"
#include "render/renderer.h"
#include "render/texture_storage_thread.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <unistd.h>

namespace velvet::cli {
namespace {

double msSince(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

/// The kB value of a /proc/self/status line ("VmHWM", "VmRSS").
double statusMb(const char* field) {
    std::ifstream in("/proc/self/status");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind(field, 0) == 0) {
            std::istringstream s(line.substr(line.find(':') + 1));
            double kb = 0;
            s >> kb;
            return kb / 1024.0;
        }
    return NAN;
}

/// Resets the peak resident size (VmHWM) to the current one (Linux 4.0+, proc(5) clear_refs 5).
void resetPeak() {
    std::ofstream("/proc/self/clear_refs") << "5";
}

/// A woven-looking RGBA8 map: threads of two colours with per-texel noise, so that neither PNG
/// nor the cache's deflate finds it trivial (about 45 % of the raw size).
Image fabricMap(int side) {
    Image img(side, side, 4);
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) {
            std::uint32_t h = std::uint32_t(x) * 0x9E3779B1u ^ std::uint32_t(y) * 0x85EBCA77u;
            h ^= h >> 15, h *= 0x2C1B3C6Du, h ^= h >> 12;
            const float noise = float(h & 255u) / 255.0f * 0.08f;
            const bool warp = ((x / 8) + (y / 8)) % 2 == 0;
            float* p = img.at(x, y);
            p[0] = (warp ? 0.55f : 0.25f) + noise;
            p[1] = (warp ? 0.08f : 0.05f) + noise * 0.5f;
            p[2] = (warp ? 0.12f : 0.30f) + noise;
            p[3] = 1.0f;
        }
    return img;
}

} // namespace

int runTextureBench(bool json, bool quick) {
    std::string error;
    const int side = quick ? 2048 : 4096;
    char dirTemplate[] = "/tmp/velvet-bench-textures-XXXXXX";
    if (!::mkdtemp(dirTemplate)) {
        std::cerr << "velvet bench: cannot make a temporary folder\n";
        return RenderFailure;
    }
    const std::filesystem::path dir = dirTemplate;
    const std::filesystem::path png = dir / "fabric.png", cacheDir = dir / "cache";
    {
        if (!writeImage(png, fabricMap(side), PixelFormat::UInt8, &error)) {
            std::cerr << "velvet bench: " << error << "\n";
            return RenderFailure;
        }
    }
    std::vector<std::pair<std::string, double>> figures;
    auto put = [&](const std::string& key, double v) { figures.emplace_back(key, v); };
    ColorManagement cm;
    cm.loadDefault(&error);
    const std::string space = resolveTextureColorSpace(cm, png, TextureUsage::Color, {});
    // The map's GPU size with every level, as the new path stores it (RGBA8 / SRGB8_ALPHA8).
    double gpuBytes = 0;
    for (int w = side; w >= 1; w /= 2)
        gpuBytes += double(w) * w * 4;
    put("texture_side", side);
    put("texture_gpu_mb_rgba8_mips", gpuBytes / (1 << 20));

    auto context = render::HeadlessContext::create(&error);
    if (!context) {
        std::cerr << "velvet bench: no headless OpenGL context: " << error << "\n";
        return RenderFailure;
    }
    int code = Ok;
    {
        // 1. The load on its own (no GL): the float path of before issue 16 (decode to float,
        // OCIO, every level in float; the separable filter of now), then the 8-bit path with the
        // cache cold and warm.
        MipLoadOptions options;
        options.cacheDir = cacheDir;
        {
            const double before = statusMb("VmRSS:");
            resetPeak();
            const auto t = std::chrono::steady_clock::now();
            TextureCache floats(cm);
            const Texture tex = floats.get(png, TextureUsage::Color);
            std::vector<Image> chain =
                tex.image ? mipChain(*tex.image, &error) : std::vector<Image>{};
            put("texture_float_path_ms", msSince(t));
            (void)chain; // alive until here: its levels count in the peak
            put("texture_float_path_peak_mb", statusMb("VmHWM:") - before);
        }
        {
            const double before = statusMb("VmRSS:");
            resetPeak();
            MipLoadResult first = loadMipTexture(png, space, TextureUsage::Color, cm, options);
            put("texture_first_load_ms", first.milliseconds);
            put("texture_first_load_peak_mb", statusMb("VmHWM:") - before);
            put("texture_first_load_decoded", first.decoded ? 1 : 0);
            put("texture_first_hash_ms", first.hashMs);
            put("texture_first_decode_ms", first.decodeMs);
            put("texture_first_filter_ms", first.filterMs);
            put("texture_first_cache_write_ms", first.cacheWriteMs);
        }
        {
            MipLoadResult second = loadMipTexture(png, space, TextureUsage::Color, cm, options);
            put("texture_second_load_ms", second.milliseconds);
            put("texture_second_load_from_cache", second.fromCache ? 1 : 0);
            put("texture_second_hash_ms", second.hashMs);
            put("texture_second_cache_read_ms", second.cacheReadMs);
        }
        put("texture_first_load_speedup_vs_float_path",
            figures[size_t(2)].second / std::max(1e-6, figures[size_t(4)].second));

        // 2. The editor's way: a renderer with asynchronous textures drawing frames while the
        // map loads (cache cold), then the peak memory of the whole load and upload; level 0
        // streamed from the cache entry (the default) and, beside it, held whole in memory
        // until uploaded (VELVET_TEXTURE_STREAMING=0, prefix async_whole_).
        const auto measureAsync = [&](const std::string& prefix, bool storageThread) -> bool {
            render::Renderer renderer;
            render::OffscreenTarget target;
            if (!renderer.initialize(&error) || !target.resize(320, 180, &error)) {
                std::cerr << "velvet bench: " << error << "\n";
                return false;
            }
            renderer.setAsyncTextures(true);
            if (storageThread) { // as the editor: storage made on a thread of its own
                auto worker = render::HeadlessContext::workerSharingCurrent(&error);
                if (!worker) {
                    std::cerr << "velvet bench: " << error << "\n";
                    return false;
                }
                renderer.setTextureStorageContext(std::move(worker));
            }
            Scene scene;
            renderer.setScene(scene);
            renderer.finishEnvironment();
            render::FrameSettings fs;
            fs.width = 320, fs.height = 180;
            std::vector<double> plain;
            for (int i = 0; i < 5; ++i) {
                const auto t = std::chrono::steady_clock::now();
                renderer.render(fs, target.framebuffer(), &error);
                renderer.lastTimings();
                plain.push_back(msSince(t));
            }
            std::sort(plain.begin(), plain.end());
            std::filesystem::remove_all(cacheDir); // cold again, for each variant
            std::filesystem::remove_all(dir / "xdg");
            setenv("XDG_CACHE_HOME", (dir / "xdg").c_str(), 1);
            TextureRef ref;
            ref.file = png.string();
            scene.material.setTexture(TextureSlot::BaseColor, ref);
            scene.material.setTexture(TextureSlot::SheenColor, ref); // one file, two slots
            const double before = statusMb("VmRSS:");
            resetPeak();
            const auto loadStart = std::chrono::steady_clock::now();
            renderer.setScene(scene);
            int frames = 0;
            double worstFrame = 0;
            int worstIndex = -1;
            double worstUploadBefore = 0;
            while (renderer.textureProgress().loading > 0 && frames < 100000) {
                const auto t = std::chrono::steady_clock::now();
                const double uploadedBefore = double(renderer.textureUploadStats().bytes);
                renderer.render(fs, target.framebuffer(), &error);
                renderer.lastTimings();
                if (msSince(t) > worstFrame)
                    worstFrame = msSince(t), worstIndex = frames,
                    worstUploadBefore =
                        double(renderer.textureUploadStats().bytes) - uploadedBefore;
                ++frames;
            }
            const double peak = statusMb("VmHWM:") - before;
            const double total = msSince(loadStart);
            const render::TextureUploadStats& up = renderer.textureUploadStats();
            put(prefix + "worst_frame_index", worstIndex);
            put(prefix + "worst_frame_uploaded_mb", worstUploadBefore / (1 << 20));
            put(prefix + "load_total_ms", total);
            put(prefix + "frames_drawn_while_loading", frames);
            put(prefix + "frames_with_coarse_proxy", up.proxyFrames);
            put(prefix + "frame_median_without_texture_ms", plain[plain.size() / 2]);
            put(prefix + "worst_frame_while_loading_ms", worstFrame);
            put(prefix + "worst_frame_upload_ms", up.worstFrameMs);
            put(prefix + "worst_frame_upload_mb", double(up.worstFrameBytes) / (1 << 20));
            put(prefix + "streamed_from_cache_mb", double(up.streamedBytes) / (1 << 20));
            put(prefix + "peak_mb", peak);
            put(prefix + "peak_vs_gpu_size", peak / (gpuBytes / (1 << 20)));
            put(prefix + "decodes_for_two_slots", double(renderer.textureDecodes()));
            put(prefix + "storage_made_off_thread", up.storageOffThread);
            return true;
        };
        setenv("VELVET_TEXTURE_STREAMING", "0", 1);
        const bool whole = measureAsync("async_whole_", false);
        unsetenv("VELVET_TEXTURE_STREAMING");
        // The storage allocated on the drawing thread (async_same_thread_) and, as the editor
        // does, on a thread of its own (async_).
        if (!whole || !measureAsync("async_same_thread_", false) || !measureAsync("async_", true))
            return RenderFailure;
    }
    std::filesystem::remove_all(dir);

    if (json) {
        std::cout << "{\"gl_renderer\": \"" << context->renderer() << "\"";
        for (const auto& [k, v] : figures)
            std::cout << ", \"" << k << "\": " << (std::isfinite(v) ? v : 0.0);
        std::cout << "}\n";
    } else {
        std::cout << "velvet bench --textures on " << context->renderer() << "\n\n";
        for (const auto& [k, v] : figures)
            std::cout << "  " << std::left << std::setw(40) << k << std::right << std::setw(12)
                      << std::fixed << std::setprecision(3) << v << "\n";
    }
    return code;
}

} // namespace velvet::cli

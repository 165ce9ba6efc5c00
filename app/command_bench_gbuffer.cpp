// velvet bench's G-buffer layout comparison (issue 13): the 24-byte G-buffer with its eight lobe
// channels beside the compact 16-byte one it replaced, in the same process and the same frames.
// Two renderers (one per layout, so switching never reallocates targets mid-measurement) draw
// the same scene alternately; the figures are medians of G-buffer + lighting GPU time and of
// wall-clock frame time, for the default velvet (no lobe map: the lobe channels are written but
// unused) and for a velvet with four lobe maps (sheen colour and roughness, clear coat,
// anisotropy), which the compact layout draws as their means.
#include "app/cli.h"
#include "core/document_io.h"
#include "core/image.h"
#include "render/gbuffer_layout.h"
#include "render/offscreen.h"
#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <glm/vec4.hpp>
#include <system_error>
#include <unistd.h>

namespace velvet::cli {
namespace {

/// A 256x256 noise-like map (values in [0.2, 1]) in @p dir: texture work that cannot be cached
/// away as one texel.
std::filesystem::path writeMap(const std::filesystem::path& dir, const char* name,
                               std::string* error) {
    Image img(256, 256, 4);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const float v = 0.2f + 0.8f * float((x * 37 + y * 91 + (x ^ y) * 13) % 256) / 255.0f;
            for (int c = 0; c < 4; ++c)
                img.at(x, y)[c] = c == 3 ? 1.0f : v;
        }
    const std::filesystem::path file = dir / name;
    if (!writeImage(file, img, PixelFormat::UInt8, error))
        return {};
    return file;
}

struct LayoutTimes {
    std::vector<double> gpuCompact, gpuLobes, wallCompact, wallLobes;
};

} // namespace

bool gbufferLayoutFigures(int width, int height, int frames,
                          std::vector<std::pair<std::string, double>>& figures,
                          std::string* error) {
    auto put = [&](const std::string& key, double v) { figures.emplace_back(key, v); };
    put("gbuffer_bytes_per_pixel", render::gbufferBytesPerPixel());
    put("gbuffer_bytes_per_pixel_compact", render::gbufferBytesPerPixel(/*compact=*/true));

    std::error_code ec;
    const std::filesystem::path dir = std::filesystem::temp_directory_path(ec) /
                                      ("velvet-bench-gbuffer-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir, ec);
    Problems problems;
    Scene velvet = defaultScene(&problems);
    Scene mapped = velvet;
    for (auto [slot, name] : {std::pair{TextureSlot::SheenColor, "sheen_color.png"},
                              std::pair{TextureSlot::SheenRoughness, "sheen_roughness.png"},
                              std::pair{TextureSlot::Clearcoat, "clearcoat.png"},
                              std::pair{TextureSlot::Anisotropy, "anisotropy.png"}}) {
        TextureRef ref;
        ref.file = writeMap(dir, name, error).string();
        if (ref.file.empty())
            return false;
        ref.colorSpace = "Raw";
        mapped.material.setTexture(slot, ref);
    }
    mapped.material.setScalar(ParamId::ClearcoatWeight, 0.5f);
    mapped.material.setScalar(ParamId::AnisotropyStrength, 0.6f);

    render::Renderer compact, lobes;
    render::OffscreenTarget target;
    if (!compact.initialize(error) || !lobes.initialize(error) ||
        !target.resize(width, height, error))
        return false;
    compact.setCompactGBuffer(true);
    render::FrameSettings fs;
    fs.width = width;
    fs.height = height;

    for (auto [label, scene] : {std::pair{"default", &velvet}, std::pair{"mapped", &mapped}}) {
        LayoutTimes t;
        for (render::Renderer* r : {&compact, &lobes}) {
            r->setScene(*scene);
            r->finishEnvironment();
            r->finishGraph();
            if (!r->render(fs, target.framebuffer(), error)) // warm-up
                return false;
        }
        for (int i = 0; i < frames; ++i)
            for (render::Renderer* r : {&compact, &lobes}) {
                const auto start = std::chrono::steady_clock::now();
                if (!r->render(fs, target.framebuffer(), error))
                    return false;
                const render::FrameTimings ft = r->lastTimings();
                const double wall = std::chrono::duration<double, std::milli>(
                                        std::chrono::steady_clock::now() - start)
                                        .count();
                const bool isCompact = r == &compact;
                (isCompact ? t.gpuCompact : t.gpuLobes).push_back(ft.gbufferMs + ft.lightingMs);
                (isCompact ? t.wallCompact : t.wallLobes).push_back(wall);
            }
        const std::string k = std::string("layout_") + label;
        const double gc = median(t.gpuCompact), gl = median(t.gpuLobes);
        const double wc = median(t.wallCompact), wl = median(t.wallLobes);
        put(k + "_compact16_gbuffer_lighting_ms", gc);
        put(k + "_lobes24_gbuffer_lighting_ms", gl);
        put(k + "_lobes24_vs_compact16", gl / std::max(gc, 1e-6));
        put(k + "_compact16_frame_ms", wc);
        put(k + "_lobes24_frame_ms", wl);
        put(k + "_frame_lobes24_vs_compact16", wl / std::max(wc, 1e-6));
    }
    std::filesystem::remove_all(dir, ec);
    return true;
}

} // namespace velvet::cli

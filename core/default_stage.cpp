#include "core/default_stage.h"

#include "core/document_io.h"
#include "core/resources.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <numbers>
#include <utility>
#include <vector>

namespace velvet {
namespace {

constexpr float kBandLowDeg = -35.0f; ///< backdrop band: below the horizon…
constexpr float kBandHighDeg = 20.0f; ///< …to above it
constexpr float kWindowDeg = 60.0f;   ///< azimuth window (a widescreen frame)
constexpr float kClampPercentile = 0.99f;

float luminance(const glm::vec4& c) {
    return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

} // namespace

float backdropRotationDeg(const Image& map) {
    if (map.empty())
        return 0.0f;
    const int w = map.width, h = map.height;
    constexpr float pi = std::numbers::pi_v<float>;
    // Rows of the band (row y's centre is at polar angle theta = (y + 0.5) / h * pi).
    std::vector<int> rows;
    std::vector<float> rowWeight; // solid angle of a texel: cos(elevation)
    for (int y = 0; y < h; ++y) {
        const float elevation = 90.0f - (float(y) + 0.5f) / float(h) * 180.0f;
        if (elevation >= kBandLowDeg && elevation <= kBandHighDeg) {
            rows.push_back(y);
            rowWeight.push_back(std::cos(elevation * pi / 180.0f));
        }
    }
    if (rows.empty())
        return 0.0f;
    std::vector<float> band;
    band.reserve(rows.size() * size_t(w));
    for (int y : rows)
        for (int x = 0; x < w; ++x) {
            const float l = luminance(map.rgba(x, y));
            band.push_back(std::isfinite(l) ? std::max(l, 0.0f) : 0.0f);
        }
    std::vector<float> sorted = band;
    const size_t k = std::min(sorted.size() - 1, size_t(kClampPercentile * float(sorted.size())));
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(k), sorted.end());
    const float clampAt = sorted[k];
    // Each column's weighted sum, then a circular window of columns.
    std::vector<double> column(size_t(w), 0.0);
    for (size_t r = 0; r < rows.size(); ++r)
        for (int x = 0; x < w; ++x)
            column[size_t(x)] +=
                double(rowWeight[r]) * std::min(band[r * size_t(w) + size_t(x)], clampAt);
    // A Hann window (weights falling smoothly to 0 at its edges): a symmetric bright area scores
    // highest with its centre in the middle of the frame, not anywhere it merely fits.
    const int half = std::max(1, int(std::lround(kWindowDeg / 360.0f * float(w) / 2.0f)));
    std::vector<double> weight(size_t(2 * half + 1));
    for (int dx = -half; dx <= half; ++dx)
        weight[size_t(dx + half)] = 0.5 * (1.0 + std::cos(double(pi) * dx / (half + 1)));
    std::vector<double> score(size_t(w), 0.0);
    for (int c = 0; c < w; ++c)
        for (int dx = -half; dx <= half; ++dx)
            score[size_t(c)] += weight[size_t(dx + half)] * column[size_t(((c + dx) % w + w) % w)];
    const int first = int(std::max_element(score.begin(), score.end()) - score.begin());
    // A bright area wider than the window scores the same over a run of columns: take the
    // middle of that run.
    const double best = score[size_t(first)], tie = best * (1.0 - 1e-6);
    int left = 0, right = 0;
    while (left < w && score[size_t(((first - left - 1) % w + w) % w)] >= tie)
        ++left;
    while (right < w && score[size_t((first + right + 1) % w)] >= tie)
        ++right;
    const int bestColumn = left + right >= w ? first : ((first + (right - left) / 2) % w + w) % w;
    // Column c looks along azimuth phi = (u - 0.5) 360 degrees, phi = 0 being -Z
    // (equirectDirection). A world direction at azimuth a sees the map's azimuth a + rotation
    // (common_environment.glsl, toEnvironment), so -Z (a = 0) sees phi when rotation = phi.
    const float phi = ((float(bestColumn) + 0.5f) / float(w) - 0.5f) * 360.0f;
    float rotation = std::round(phi);
    rotation = std::fmod(rotation + 360.0f, 360.0f);
    return rotation;
}

std::optional<float> hdriDefaultRotationDeg(const std::filesystem::path& hdri, std::string* error) {
    // The shipped HDRIs' answers, so a new document and `velvet render` read no HDRI for them
    // (50-120 ms each on the 2-core VM); test_render_default_stage recomputes every entry from
    // its file and fails when one differs.
    static const std::pair<const char*, float> kShipped[] = {
        {"city.exr", 336.0f},  {"forest.exr", 22.0f}, {"interior.exr", 17.0f},
        {"studio.exr", 69.0f}, {"sunset.exr", 34.0f},
    };
    std::error_code ec;
    const auto shipped = std::filesystem::weakly_canonical(resources::path("hdri"), ec);
    const auto folder = std::filesystem::weakly_canonical(hdri, ec).parent_path();
    if (!ec && folder == shipped)
        for (const auto& [name, rotation] : kShipped)
            if (hdri.filename() == name)
                return rotation;
    return computeHdriDefaultRotationDeg(hdri, error);
}

std::optional<float> computeHdriDefaultRotationDeg(const std::filesystem::path& hdri,
                                                   std::string* error) {
    static std::mutex mutex;
    static std::map<std::string, std::pair<std::filesystem::file_time_type, float>> cache;
    std::error_code ec;
    const auto stamp = std::filesystem::last_write_time(hdri, ec);
    if (ec) {
        if (error)
            *error = hdri.string() + ": " + ec.message();
        return std::nullopt;
    }
    const std::string key = hdri.lexically_normal().string();
    {
        std::lock_guard lock(mutex);
        if (auto it = cache.find(key); it != cache.end() && it->second.first == stamp)
            return it->second.second;
    }
    Image image;
    if (!readImage(hdri, image, error))
        return std::nullopt;
    const float rotation = backdropRotationDeg(image);
    std::lock_guard lock(mutex);
    cache[key] = {stamp, rotation};
    return rotation;
}

Camera framedCamera(Camera camera, float radius, float fill) {
    // The sphere's silhouette subtends asin(r / d) from its centre; it fills `fill` of the
    // height when tan(asin(r / d)) = fill tan(fov / 2).
    const float halfFov = camera.fovYDeg * std::numbers::pi_v<float> / 360.0f;
    const float silhouette = std::atan(fill * std::tan(halfFov));
    camera.target = glm::vec3(0.0f);
    camera.distance = radius / std::sin(silhouette);
    camera.orthoHeight = 2.0f * radius / fill;
    return camera;
}

Scene stageScene(Problems* problems) {
    Scene scene = defaultScene(problems);
    if (!scene.environment.hdri.empty()) {
        std::string error;
        if (auto rotation = hdriDefaultRotationDeg(scene.environment.hdri, &error))
            scene.environment.rotationDeg = *rotation;
        else if (problems)
            problems->warning(scene.environment.hdri, "environment.rotation",
                              "cannot compute the default rotation: " + error);
    }
    scene.environment.background = BackgroundMode::Blurred;
    scene.camera = framedCamera(scene.camera);
    return scene;
}

Scene stageSceneWithMaterial(Material material, Problems* problems) {
    Scene scene = stageScene(problems);
    scene.material = std::move(material);
    scene.materialPreset.clear();
    return scene;
}

bool thumbnailOnDrape(const Material& material) {
    return std::any_of(material.tags.begin(), material.tags.end(),
                       [](const std::string& tag) { return tag == "fabric" || tag == "leather"; });
}

Scene thumbnailScene(Material material, Problems* problems) {
    const bool drape = thumbnailOnDrape(material);
    Scene scene = stageSceneWithMaterial(std::move(material), problems);
    if (drape) {
        scene.mesh.kind = PreviewMeshKind::ClothDrape;
        applyStageDefaults(scene.environment, scene.mesh.kind);
    }
    return scene;
}

} // namespace velvet

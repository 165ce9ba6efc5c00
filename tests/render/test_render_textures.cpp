// Texture slots and preview meshes in the renderer: what each case proves is stated on it. One
// renderer for the whole file (programs compiled once), 64x64 renders, the grey-furnace setup
// (uniform white environment, Lambertian, no specular) so a pixel equals its albedo.
#include "core/image.h"
#include "core/image_ops.h"
#include "core/mesh_import.h"
#include "render/offscreen.h"
#include "render/renderer.h"
#include "render/texture_set.h"
#include "render_test_util.h"

#include <QTemporaryDir>
#include <QtTest>
#include <algorithm>
#include <cmath>
#include <epoxy/gl.h>
#include <filesystem>
#include <fstream>
#include <glm/geometric.hpp>

using namespace velvet;
namespace fs = std::filesystem;

namespace {

constexpr int kSize = 64;

/// sRGB EOTF (IEC 61966-2-1) of an 8-bit code.
float srgbToLinear(int code) {
    const double c = code / 255.0;
    return float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
}

Scene furnace() {
    Scene scene;
    Material& m = scene.material;
    m.setColor(ParamId::BaseColor, glm::vec3(1.0f));
    m.setScalar(ParamId::Metallic, 0.0f);
    m.setScalar(ParamId::SpecularWeight, 0.0f);
    m.setScalar(ParamId::SheenWeight, 0.0f);
    m.setScalar(ParamId::ClearcoatWeight, 0.0f);
    scene.lights.clear();
    scene.environment.hdri.clear();
    scene.environment.color = glm::vec3(1.0f);
    scene.environment.intensity = 1.0f;
    return scene;
}

/// Mean linear RGB over the central 6x6 pixels (the sphere faces the camera there).
glm::vec3 centre(const Image& img) {
    glm::vec3 sum(0.0f);
    for (int y = kSize / 2 - 3; y < kSize / 2 + 3; ++y)
        for (int x = kSize / 2 - 3; x < kSize / 2 + 3; ++x)
            sum += glm::vec3(img.rgba(x, y));
    return sum / 36.0f;
}

Image flat(int w, int h, glm::vec4 value) {
    Image img(w, h, 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 4; ++c)
                img.at(x, y)[c] = value[c];
    return img;
}

} // namespace

class TestRenderTextures : public QObject {
    Q_OBJECT
    QTemporaryDir m_dir;
    test::OffscreenRenderer m_fixture;

    fs::path path(const char* name) const { return fs::path(m_dir.path().toStdString()) / name; }

    void write(const fs::path& file, const Image& image) {
        std::string error;
        QVERIFY2(writeImage(file, image, PixelFormat::UInt8, &error), error.c_str());
    }

    Image render(const Scene* scene, Problems* problems = nullptr,
                 render::DebugView view = render::DebugView::Final) {
        return m_fixture.draw(scene, view, problems);
    }

    Scene textured(TextureSlot slot, const fs::path& file, const std::string& colorSpace = {}) {
        Scene scene = furnace();
        TextureRef ref;
        ref.file = file.string();
        ref.colorSpace = colorSpace;
        scene.material.setTexture(slot, ref);
        return scene;
    }

private slots:
    void initTestCase() {
        const std::string error = m_fixture.start(kSize);
        QVERIFY2(error.empty(), error.c_str());
    }
    void cleanupTestCase() {
        m_fixture.stop(); // with the context still current
    }

    // A flat 8-bit 128 base-colour texture tagged "sRGB texture" is decoded to linear
    // 0.2158 by OCIO on load; times a white factor under the white furnace the pixel is 0.2158.
    // Tagged Raw, the same file is taken as data: 128 / 255 = 0.502.
    void baseColorColourSpace() {
        write(path("grey128.png"),
              flat(8, 8, glm::vec4(128.0f / 255.0f, 128.0f / 255.0f, 128.0f / 255.0f, 1.0f)));
        Problems problems;
        Scene srgb = textured(TextureSlot::BaseColor, path("grey128.png"), "sRGB texture");
        const glm::vec3 a = centre(render(&srgb, &problems));
        QVERIFY(problems.items.empty());
        const float expected = srgbToLinear(128);
        qInfo("sRGB texture: %.4f (expected %.4f); ", a.x, expected);
        QVERIFY(std::abs(expected - 0.2158f) < 1e-3f);
        for (int k = 0; k < 3; ++k)
            QVERIFY2(std::abs(a[k] - expected) < 0.005f, qPrintable(QString::number(a[k])));
        Scene raw = textured(TextureSlot::BaseColor, path("grey128.png"), "Raw");
        const glm::vec3 b = centre(render(&raw, &problems));
        qInfo("Raw: %.4f (expected 0.502)", b.x);
        for (int k = 0; k < 3; ++k)
            QVERIFY2(std::abs(b[k] - 128.0f / 255.0f) < 0.005f, qPrintable(QString::number(b[k])));
        // The factor multiplies the texture (glTF).
        raw.material.setColor(ParamId::BaseColor, glm::vec3(0.5f, 1.0f, 1.0f));
        QVERIFY(std::abs(centre(render(&raw)).x - 0.251f) < 0.005f);
    }

    // A slot's UV transform (issue 17 item 6) moves the lookup: three vertical stripes (red,
    // green, blue, a third of the width each); an offset of a third in u moves the centre
    // pixel to the next stripe, two thirds to the one after; an offset in v or of a whole
    // period changes nothing.
    void uvOffsetShiftsAKnownPixel() {
        Image stripes(24, 8, 4);
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 24; ++x) {
                glm::vec4 c(0.1f, 0.1f, 0.1f, 1.0f);
                c[x / 8] = 0.8f;
                std::copy(&c.x, &c.x + 4, stripes.at(x, y));
            }
        write(path("stripes.png"), stripes);
        Scene scene = textured(TextureSlot::BaseColor, path("stripes.png"), "Raw");
        const auto stripeAtCentre = [&](glm::vec2 offset) {
            TextureRef ref = scene.material.texture(TextureSlot::BaseColor);
            ref.uv.offset = offset;
            scene.material.setTexture(TextureSlot::BaseColor, ref);
            const glm::vec4 p = render(&scene).rgba(kSize / 2, kSize / 2);
            const int k = p.r > p.g && p.r > p.b ? 0 : (p.g > p.b ? 1 : 2);
            qInfo("offset (%.3f, %.3f): centre %.3f %.3f %.3f -> stripe %d", offset.x, offset.y,
                  p.r, p.g, p.b, k);
            return std::max({p.r, p.g, p.b}) > 0.6f ? k : -1; // -1: on a seam, not in a stripe
        };
        const int k0 = stripeAtCentre({0.0f, 0.0f});
        QVERIFY(k0 >= 0);
        QCOMPARE(stripeAtCentre({1.0f / 3.0f, 0.0f}), (k0 + 1) % 3);
        QCOMPARE(stripeAtCentre({2.0f / 3.0f, 0.0f}), (k0 + 2) % 3);
        QCOMPARE(stripeAtCentre({0.0f, 0.37f}), k0); // v does not cross vertical stripes
        QCOMPARE(stripeAtCentre({1.0f, 0.0f}), k0);  // a whole period: the same texel
    }

    // An atlas of two flat halves: each region picks its own colour, with no bleeding from the
    // other half at the centre of the sphere.
    void atlasRegionPicksSubImage() {
        Image atlas(16, 8, 4);
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 16; ++x) {
                const glm::vec4 c =
                    x < 8 ? glm::vec4(0.8f, 0.2f, 0.2f, 1.0f) : glm::vec4(0.2f, 0.2f, 0.8f, 1.0f);
                for (int k = 0; k < 4; ++k)
                    atlas.at(x, y)[k] = c[k];
            }
        write(path("atlas.png"), atlas);
        for (const bool left : {true, false}) {
            Scene scene = textured(TextureSlot::BaseColor, path("atlas.png"), "Raw");
            TextureRef ref = scene.material.texture(TextureSlot::BaseColor);
            ref.useRegion = true;
            ref.region = {left ? 0 : 8, 0, 8, 8};
            scene.material.setTexture(TextureSlot::BaseColor, ref);
            const glm::vec3 c = centre(render(&scene));
            const glm::vec3 expected =
                left ? glm::vec3(204, 51, 51) / 255.0f : glm::vec3(51, 51, 204) / 255.0f;
            qInfo("%s half: %.3f %.3f %.3f", left ? "left" : "right", c.x, c.y, c.z);
            QVERIFY(glm::length(c - expected) < 0.01f);
        }
    }

    // Emission is drawn per pixel (gbuffer.frag writes it into the HDR target): an emissive map
    // of a white and a black half lights exactly the sphere pixels whose UV falls in the white
    // half, at colour x strength, and leaves the others black (averaging the map, as slots
    // without room in the G-buffer are, would give every pixel half of it). A clearcoat dims
    // emission by its Fresnel (KHR_materials_clearcoat), which the emissive debug view leaves out.
    void emissiveMapIsPerPixel() {
        Image halves(16, 8, 4);
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 16; ++x)
                for (int k = 0; k < 4; ++k)
                    halves.at(x, y)[k] = k == 3 ? 1.0f : (x < 8 ? 1.0f : 0.0f);
        write(path("emissive_halves.png"), halves);
        const glm::vec3 emission(2.0f, 1.0f, 0.5f); // colour (1, 0.5, 0.25) x 2 nits
        Scene dark = furnace();
        dark.environment.color = glm::vec3(0.0f); // nothing but emission lights the image
        dark.material.setColor(ParamId::BaseColor, glm::vec3(0.0f));
        dark.material.setColor(ParamId::EmissiveColor, glm::vec3(1.0f, 0.5f, 0.25f));
        dark.material.setScalar(ParamId::EmissiveStrength, 2.0f);

        const Image uniform = render(&dark); // no map: every sphere pixel emits fully
        Scene mapped = dark;
        TextureRef ref;
        ref.file = path("emissive_halves.png").string();
        ref.colorSpace = "Raw";
        mapped.material.setTexture(TextureSlot::Emissive, ref);
        Problems problems;
        const Image image = render(&mapped, &problems);
        QVERIFY(!problems.hasErrors());
        int sphere = 0, full = 0, black = 0;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                if (glm::length(glm::vec3(uniform.rgba(x, y)) - emission) > 0.01f)
                    continue; // background
                ++sphere;
                const glm::vec3 c(image.rgba(x, y));
                full += glm::length(c - emission) < 0.01f;
                black += glm::length(c) < 0.01f;
            }
        qInfo("sphere pixels %d: full emission %d, none %d", sphere, full, black);
        QVERIFY(sphere > kSize * kSize / 8);
        QVERIFY2(full > sphere / 5 && black > sphere / 5, "both halves of the map show");
        // The rest lie along the two seams and near the poles, where the map is minified.
        QVERIFY2(full + black > sphere * 6 / 10, "only seams and poles are filtered");

        Scene coated = dark;
        coated.material.setScalar(ParamId::ClearcoatWeight, 1.0f);
        const glm::vec3 c = centre(render(&coated));
        // Schlick at normal incidence: the coat reflects F0 = 0.04, so 0.96 of the emission.
        QVERIFY2(glm::length(c - emission * 0.96f) < 0.02f,
                 qPrintable(QStringLiteral("%1 %2 %3").arg(c.x).arg(c.y).arg(c.z)));
        const glm::vec3 view = centre(render(&coated, nullptr, render::DebugView::Emissive));
        QVERIFY2(glm::length(view - emission) < 0.01f,
                 qPrintable(QStringLiteral("%1 %2 %3").arg(view.x).arg(view.y).arg(view.z)));
    }

    // An HDRI edited in another program is read again at the next frame (its cache key holds the
    // file's modification stamp) and shows behind the sphere without a new scene.
    void editedHdriIsReadAgain() {
        const fs::path hdri = path("edited.exr");
        std::string error;
        QVERIFY2(writeImage(hdri, flat(8, 4, glm::vec4(0.25f, 0.25f, 0.25f, 1.0f)),
                            PixelFormat::Half, &error),
                 error.c_str());
        Scene scene = furnace();
        scene.environment.hdri = hdri.string();
        const float before = render(&scene).rgba(1, 1).x; // a corner: the background
        QVERIFY2(std::abs(before - 0.25f) < 0.01f, qPrintable(QString::number(before)));
        // Another size, so the stamp differs even where the clock is coarse.
        QVERIFY2(writeImage(hdri, flat(16, 8, glm::vec4(0.75f, 0.75f, 0.75f, 1.0f)),
                            PixelFormat::Half, &error),
                 error.c_str());
        const float after = render(nullptr).rgba(1, 1).x; // same scene, next frame
        QVERIFY2(std::abs(after - 0.75f) < 0.01f, qPrintable(QString::number(after)));
    }

    // A flat normal map (0.5, 0.5, 1) leaves the lit image as without one (8-bit 128 is 0.502,
    // a tilt of 0.3 degrees); a tilted map does change it.
    void flatNormalMapChangesNothing() {
        write(path("flat_normal.png"),
              flat(8, 8, glm::vec4(128.0f / 255.0f, 128.0f / 255.0f, 1.0f, 1.0f)));
        write(path("tilted_normal.png"), flat(8, 8, glm::vec4(0.9f, 0.5f, 0.6f, 1.0f)));
        Scene plain = furnace();
        plain.material.setColor(ParamId::BaseColor, glm::vec3(0.5f));
        plain.environment.color = glm::vec3(0.1f);
        Light light;
        light.direction = {-0.5f, -0.3f, -0.8f};
        plain.lights = {light};
        const Image without = render(&plain);
        Scene mapped = plain;
        mapped.material.setTexture(TextureSlot::Normal, {path("flat_normal.png").string()});
        Problems problems;
        const Image with = render(&mapped, &problems);
        QVERIFY(problems.items.empty());
        float worst = 0.0f, brightest = 0.0f;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x)
                for (int k = 0; k < 3; ++k) {
                    worst = std::max(worst, std::abs(with.rgba(x, y)[k] - without.rgba(x, y)[k]));
                    brightest = std::max(brightest, without.rgba(x, y)[k]);
                }
        qInfo("flat normal map: worst difference %.5f of %.3f", worst, brightest);
        QVERIFY(worst <= 0.01f * brightest);
        mapped.material.setTexture(TextureSlot::Normal, {path("tilted_normal.png").string()});
        QVERIFY(std::abs(centre(render(&mapped)).x - centre(without).x) > 0.02f);
    }

    // A texture file rewritten on disk (as another program saves it) shows in the next frame
    // without setScene and without compiling a shader; nor does a value edit compile one.
    void changedFileReloadsWithoutCompiling() {
        const fs::path file = path("reload.png");
        write(file, flat(8, 8, glm::vec4(128.0f / 255.0f, 128.0f / 255.0f, 128.0f / 255.0f, 1.0f)));
        Scene scene = textured(TextureSlot::BaseColor, file, "Raw");
        const float before = centre(render(&scene)).x;
        const int compiles = m_fixture.renderer->shaderCompileCount();
        write(file, flat(8, 8, glm::vec4(64.0f / 255.0f, 64.0f / 255.0f, 64.0f / 255.0f, 1.0f)));
        const float after = centre(render(nullptr)).x;
        qInfo("before %.4f, after %.4f", before, after);
        QVERIFY(std::abs(before - 128.0f / 255.0f) < 0.005f);
        QVERIFY(std::abs(after - 64.0f / 255.0f) < 0.005f);
        QCOMPARE(m_fixture.renderer->shaderCompileCount(), compiles);
        scene.material.setColor(ParamId::BaseColor, glm::vec3(0.5f));
        m_fixture.renderer->update(scene, ScenePart::MaterialValues);
        render(nullptr);
        QCOMPARE(m_fixture.renderer->shaderCompileCount(), compiles);
        // A slot newly filled is structure: the G-buffer program specialised to the material's
        // slots is built once for it (render/material_graph_program.h, GeometryFeatures).
        scene.material.setTexture(TextureSlot::Occlusion, {file.string()});
        render(&scene);
        render(nullptr);
        QCOMPARE(m_fixture.renderer->shaderCompileCount(), compiles + 1);
    }

    // Material textures carry core::mipChain's levels (OpenImageIO, Blackman-Harris), not the
    // GPU's: level 1 read back from the slot's GL texture equals mipChain(image)[1] within half
    // float precision, and differs from a 2x2 box average (glGenerateTextureMipmap) at a step.
    void mipLevelsComeFromMipChain() {
        const fs::path file = path("mips.png");
        Image img(16, 8, 4);
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) {
                float* p = img.at(x, y);
                p[0] = x < 8 ? 0.0f : 1.0f;                     // a step on a 2-texel boundary
                p[1] = float((x * 37 + y * 11) % 256) / 255.0f; // texture
                p[2] = float(y) / 7.0f;
                p[3] = 1.0f;
            }
        write(file, img);
        Image decoded;
        std::string error;
        QVERIFY2(readImage(file, decoded, &error), error.c_str());
        const std::vector<Image> chain = mipChain(decoded, &error);
        QVERIFY2(chain.size() == 5, error.c_str()); // 16x8, 8x4, 4x2, 2x1, 1x1

        render::TextureSet set;
        Material material;
        TextureRef ref;
        ref.file = file.string();
        ref.colorSpace = "Raw"; // data: the file's values, unconverted
        material.setTexture(TextureSlot::BaseColor, ref);
        Problems problems;
        set.setMaterial(material, &problems);
        QVERIFY(!problems.hasErrors());
        const unsigned tex = set.texture(TextureSlot::BaseColor);
        QVERIFY(tex != 0);
        GLint w = 0, h = 0;
        glGetTextureLevelParameteriv(tex, 1, GL_TEXTURE_WIDTH, &w);
        glGetTextureLevelParameteriv(tex, 1, GL_TEXTURE_HEIGHT, &h);
        QCOMPARE(w, 8);
        QCOMPARE(h, 4);
        std::vector<float> level(size_t(w) * h * 4);
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glGetTextureImage(tex, 1, GL_RGBA, GL_FLOAT, GLsizei(level.size() * sizeof(float)),
                          level.data());
        float worst = 0.0f, fromBox = 0.0f;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                for (int c = 0; c < 3; ++c) {
                    // Row 0 of the image is texture row 0 (t = 0, glTF's v = 0 at the top).
                    const float got = level[(size_t(y) * w + x) * 4 + c];
                    worst = std::max(worst, std::abs(got - chain[1].rgba(x, y)[c]));
                    float box = 0.0f;
                    for (int dy = 0; dy < 2; ++dy)
                        for (int dx = 0; dx < 2; ++dx)
                            box += decoded.rgba(2 * x + dx, 2 * y + dy)[c] / 4.0f;
                    fromBox = std::max(fromBox, std::abs(got - box));
                }
        qInfo("level 1: max |GL - mipChain| = %.5f, max |GL - 2x2 box| = %.4f", double(worst),
              double(fromBox));
        QVERIFY2(worst <= 2e-3f, qPrintable(QString::number(worst))); // RGBA16F storage
        QVERIFY(fromBox > 0.01f);
    }

    // A missing texture is a problem naming the file and the slot; the parameter value is drawn.
    void missingTextureFallsBack() {
        Scene scene = textured(TextureSlot::BaseColor, path("missing.png"));
        scene.material.setColor(ParamId::BaseColor, glm::vec3(0.3f));
        Problems problems;
        const glm::vec3 c = centre(render(&scene, &problems));
        QVERIFY(problems.hasErrors());
        QVERIFY(problems.items[0].toString().find("missing.png") != std::string::npos);
        QVERIFY(std::abs(c.x - 0.3f) < 0.005f);
    }

    // Every procedural preview mesh draws (it covers the centre, nothing is reported); a custom
    // mesh that fails to import is an error naming the file and the sphere is drawn instead.
    void meshSelection() {
        Scene sphere = furnace();
        const Image sphereImage = render(&sphere, nullptr, render::DebugView::Depth);
        for (const PreviewMeshKind kind :
             {PreviewMeshKind::Cube, PreviewMeshKind::RoundedCube, PreviewMeshKind::Plane,
              PreviewMeshKind::ClothDrape, PreviewMeshKind::ShaderBall}) {
            Scene scene = furnace();
            scene.mesh.kind = kind;
            Problems problems;
            const Image depth = render(&scene, &problems, render::DebugView::Depth);
            QVERIFY(problems.items.empty());
            QVERIFY2(depth.rgba(kSize / 2, kSize / 2).x > 0.0f,
                     qPrintable(QString::number(int(kind))));
            float differs = 0.0f;
            for (int y = 0; y < kSize; ++y)
                for (int x = 0; x < kSize; ++x)
                    differs =
                        std::max(differs, std::abs(depth.rgba(x, y).x - sphereImage.rgba(x, y).x));
            QVERIFY(differs > 0.01f); // not the sphere
        }
        Scene broken = furnace();
        broken.mesh.kind = PreviewMeshKind::Custom;
        broken.mesh.file = path("nothing.obj").string();
        Problems problems;
        const Image depth = render(&broken, &problems, render::DebugView::Depth);
        QVERIFY(problems.hasErrors());
        QVERIFY(problems.items[0].toString().find("nothing.obj") != std::string::npos);
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x)
                QVERIFY(std::abs(depth.rgba(x, y).x - sphereImage.rgba(x, y).x) < 1e-5f);
        // A custom OBJ (a tetrahedron) imports, is drawn, and reports nothing.
        std::ofstream(path("tet.obj")) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                          "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
        Scene custom = furnace();
        custom.mesh = {PreviewMeshKind::Custom, path("tet.obj").string()};
        problems = {};
        render(&custom, &problems);
        QVERIFY(problems.items.empty());
    }
};

QTEST_GUILESS_MAIN(TestRenderTextures)
#include "test_render_textures.moc"

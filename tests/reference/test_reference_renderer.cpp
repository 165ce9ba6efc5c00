// The reference path tracer (reference/reference_renderer.h) against known answers: a white
// furnace (a white Lambertian sphere under a uniform white environment is invisible: every pixel
// converges to the environment's radiance), determinism (the same seed gives the same image
// whatever the thread count; another seed another), and Monte Carlo convergence (the error
// against a 16x-spp image at least halves for every 4x spp), and a directional light drawn as
// the disc of its angular diameter.
#include "core/graph/graph.h"
#include "core/image.h"
#include "core/material.h"
#include "core/scene.h"
#include "reference/graph_material.h"
#include "reference/reference_renderer.h"

#include <QTemporaryDir>
#include <QTest>
#include <cmath>
#include <glm/geometric.hpp>

using namespace velvet;

namespace {

/// A white diffuse sphere (no specular, sheen or clearcoat) under a uniform white environment.
Scene furnaceScene() {
    Scene s;
    s.lights.clear();
    s.environment = Environment{};
    s.environment.hdri.clear();
    s.environment.color = glm::vec3(1.0f);
    s.environment.intensity = 1.0f;
    s.material.setColor(ParamId::BaseColor, glm::vec3(1.0f));
    s.material.setScalar(ParamId::Metallic, 0.0f);
    s.material.setScalar(ParamId::Roughness, 1.0f);
    s.material.setScalar(ParamId::SpecularWeight, 0.0f);
    s.material.setScalar(ParamId::SheenWeight, 0.0f);
    s.material.setScalar(ParamId::ClearcoatWeight, 0.0f);
    return s;
}

/// A lit, shiny scene whose pixels vary (a gold sphere under the key light and a grey sky).
Scene variedScene() {
    Scene s;
    s.environment.hdri.clear();
    s.environment.color = glm::vec3(0.3f, 0.35f, 0.4f);
    s.material.setColor(ParamId::BaseColor, glm::vec3(1.0f, 0.78f, 0.34f));
    s.material.setScalar(ParamId::Metallic, 1.0f);
    s.material.setScalar(ParamId::Roughness, 0.35f);
    return s;
}

reference::Result renderOrFail(const Scene& scene, reference::Options o) {
    reference::Result r;
    std::string error;
    if (!reference::render(scene, o, r, &error))
        qWarning("reference render failed: %s", error.c_str());
    return r;
}

/// The red channel's mean over the centre 8x8 pixels of a 24x24 image: all on the sphere and
/// seen within 30 degrees of its normal.
double centreMean(const Image& image) {
    double sum = 0.0;
    for (int y = 8; y < 16; ++y)
        for (int x = 8; x < 16; ++x)
            sum +=
                image
                    .pixels[(size_t(y) * size_t(image.width) + size_t(x)) * size_t(image.channels)];
    return sum / 64.0;
}

double rmse(const Image& a, const Image& b) {
    double sum = 0.0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        const double d = double(a.pixels[i]) - double(b.pixels[i]);
        sum += d * d;
    }
    return std::sqrt(sum / double(a.pixels.size()));
}

} // namespace

class TestReferenceRenderer : public QObject {
    Q_OBJECT

private slots:
    void whiteFurnaceIsInvisible() {
        reference::Options o;
        o.width = o.height = 24;
        o.samplesPerPixel = 1024;
        o.maxBounces = 16; // a convex sphere: few paths bounce more than once
        // Enough samples that Russian roulette's noise stays under the tolerance (64 spp: 5 %).
        const reference::Result r = renderOrFail(furnaceScene(), o);
        QCOMPARE(r.image.width, 24);
        QCOMPARE(r.passesDone, o.samplesPerPixel);
        // The centre pixel is on the sphere; the mean covers sphere and background alike.
        const int c = r.image.channels;
        const float* centre = &r.image.pixels[(size_t(12) * 24 + 12) * size_t(c)];
        for (int k = 0; k < 3; ++k)
            QVERIFY2(std::abs(centre[k] - 1.0f) < 0.05f, qPrintable(QString::number(centre[k])));
        double mean = 0.0;
        for (int y = 0; y < 24; ++y)
            for (int x = 0; x < 24; ++x)
                mean += r.image.pixels[(size_t(y) * 24 + x) * size_t(c)];
        mean /= 24.0 * 24.0;
        QVERIFY2(std::abs(mean - 1.0) < 0.02, qPrintable(QString::number(mean)));
    }

    // A directional light is the disc of its angular diameter (Light::sourceAngleDeg), a point
    // light the ball of its source radius (Light::sourceRadius), as the viewport's penumbrae take
    // them. Known answers for a white Lambertian sphere in the dark under a light from the side:
    // where the whole disc is above the horizon the disc gives what the delta light gives (the
    // mean of n.l over the cone, times the disc's normalisation, is n.c exactly); past the delta
    // light's terminator, within the disc's half-angle, the disc still lights the sphere.
    void directionalLightIsADiscOfItsAngularDiameter_data() {
        QTest::addColumn<bool>("point");
        QTest::newRow("directional, 20 degrees") << false;
        QTest::newRow("point at 3 m, radius 0.6 m") << true;
    }
    void directionalLightIsADiscOfItsAngularDiameter() {
        Scene s = furnaceScene();
        s.environment.color = glm::vec3(0.0f);
        QFETCH(bool, point);
        Light light;
        light.type = point ? LightType::Point : LightType::Directional;
        light.direction = glm::vec3(-1.0f, 0.0f, 0.0f); // towards -x: lights the +x half
        light.position = glm::vec3(3.0f, 0.0f, 0.0f);
        light.range = 1000.0f;
        light.intensity = 3.14159265f * (point ? 4.0f : 1.0f); // about n.c at the near side
        light.sourceAngleDeg = 0.0f;
        light.sourceRadius = 0.0f;
        s.lights = {light};
        reference::Options o;
        o.width = o.height = 32;
        o.samplesPerPixel = 64;
        o.maxBounces = 1;
        const reference::Result delta = renderOrFail(s, o);
        s.lights[0].sourceAngleDeg = 20.0f; // half-angle 10 degrees: sin 0.17
        s.lights[0].sourceRadius = 0.6f;    // from 3 m: sin 0.2
        const reference::Result disc = renderOrFail(s, o);
        QCOMPARE(disc.image.width, 32);
        const int c = disc.image.channels;
        int whole = 0, softened = 0, darkWithDisc = 0;
        double worst = 0.0, sumDelta = 0.0, sumDisc = 0.0;
        float brightest = 0.0f;
        for (size_t i = 0; i < size_t(32 * 32); ++i)
            brightest = std::max(brightest, delta.image.pixels[i * size_t(c)]);
        for (size_t i = 0; i < size_t(32 * 32); ++i) {
            const float a = delta.image.pixels[i * size_t(c)], b = disc.image.pixels[i * size_t(c)];
            if (a > 0.3f * brightest) { // n.c above the disc's sin plus a pixel's spread
                ++whole;
                worst = std::max(worst, double(std::abs(b - a)));
                sumDelta += a;
                sumDisc += b;
            } else if (a == 0.0f && b > 0.002f * brightest) {
                ++softened; // past the delta's terminator, lit by part of the disc
            } else if (a > 0.05f && b == 0.0f) {
                ++darkWithDisc;
            }
        }
        const double ratio = sumDisc / std::max(sumDelta, 1e-9);
        qInfo("%d pixels see the whole disc (largest difference %.4f, disc / delta %.4f), %d lit "
              "past the delta's terminator",
              whole, worst, ratio, softened);
        QVERIFY(whole >= 30);
        // Without the disc's normalisation the ratio would be (1 + cos 10 degrees) / 2 = 0.9924.
        QVERIFY2(std::abs(ratio - 1.0) < 0.003, qPrintable(QString::number(ratio)));
        QVERIFY2(worst < 0.04, qPrintable(QString::number(worst)));
        QVERIFY2(softened >= 6, qPrintable(QString::number(softened)));
        QCOMPARE(darkWithDisc, 0);
    }

    // A rough white metal under the same furnace: its BRDF (brdf::evalDirectional) carries
    // Turquin 2019's multiple-scattering compensation (core/brdf_energy.h), so it reflects all the
    // light it receives and is invisible too (before it: 0.91 at roughness 0.5 and 0.32 at 1.0 at
    // the sphere's centre, BENCHMARKS.md).
    void roughWhiteMetalFurnaceIsInvisible() {
        for (float rough : {0.5f, 1.0f}) {
            Scene scene = furnaceScene();
            scene.material.setScalar(ParamId::Metallic, 1.0f);
            scene.material.setScalar(ParamId::Roughness, rough);
            reference::Options o;
            o.width = o.height = 24;
            o.samplesPerPixel = 256;
            o.maxBounces = 16;
            const reference::Result r = renderOrFail(scene, o);
            QCOMPARE(r.passesDone, o.samplesPerPixel);
            const double centre = centreMean(r.image);
            qInfo("white metal, roughness %.1f, furnace: centre %.4f", rough, centre);
            QVERIFY2(std::abs(centre - 1.0) < 0.03,
                     qPrintable(QString("roughness %1: %2").arg(rough).arg(centre)));
        }
    }

    // The material's occlusion (here the graph's occlusion output, 0.4, at strength 0.5: 0.7)
    // scales the indirect light a hit receives, as glTF defines it: under the white furnace the
    // white Lambertian sphere (convex: every path leaves after one bounce) reads 0.7; a
    // directional light on a black environment is not scaled at all.
    void occlusionScalesIndirectLightOnly() {
        using namespace velvet::graph;
        Graph g;
        const NodeId out = g.addNode(kOutputTypeId).node;
        const NodeId ao = g.addNode("constant.float").node;
        QVERIFY(g.setInputValue(ao, 0, glm::vec4(0.4f)));
        const graph::NodeType* outType = findNodeType(kOutputTypeId);
        QVERIFY(outType && outType->inputIndex("occlusion") >= 0);
        QVERIFY(g.connect({ao, 0, out, PortIndex(outType->inputIndex("occlusion"))}));
        reference::Options o;
        o.width = o.height = 24;
        o.samplesPerPixel = 512;
        o.maxBounces = 16;
        Scene furnace = furnaceScene();
        furnace.material.setScalar(ParamId::OcclusionStrength, 0.5f);
        furnace.material.graph = SharedGraph(g);
        const reference::Result r = renderOrFail(furnace, o);
        const double centre = centreMean(r.image);
        qInfo("furnace with occlusion 0.7: centre %.4f", centre);
        QVERIFY2(std::abs(centre - 0.7) < 0.02, qPrintable(QString::number(centre)));

        // A directional light on the black environment: the same image with and without it.
        Scene lit = variedScene();
        lit.environment.color = glm::vec3(0.0f);
        Light key;
        key.type = LightType::Directional;
        key.direction = glm::vec3(0.5f, -0.6f, -0.62f);
        key.intensity = 3.0f;
        lit.lights = {key};
        o.samplesPerPixel = 4;
        const reference::Result plain = renderOrFail(lit, o);
        lit.material.graph = SharedGraph(g);
        const reference::Result occluded = renderOrFail(lit, o);
        QVERIFY(!plain.image.pixels.empty());
        QVERIFY(plain.image.pixels == occluded.image.pixels);
    }

    // The material graph is evaluated at every hit by the graph compiler's CPU twin: a graph
    // feeding constants renders exactly what the same values as parameters render, and a
    // checker feeding the base colour shows per-hit variation a constant cannot.
    void graphDrivesTheMaterialPerHit() {
        using namespace velvet::graph;
        reference::Options o;
        o.width = o.height = 20;
        o.samplesPerPixel = 4;
        Scene byParams = variedScene();
        byParams.material.setColor(ParamId::BaseColor, glm::vec3(0.2f, 0.5f, 0.9f));
        byParams.material.setScalar(ParamId::Roughness, 0.6f);
        byParams.material.setScalar(ParamId::Metallic, 0.0f);

        Graph g;
        const NodeId out = g.addNode(kOutputTypeId).node;
        const NodeId colour = g.addNode("constant.color").node;
        const NodeId rough = g.addNode("constant.float").node;
        const NodeId metal = g.addNode("constant.float").node;
        QVERIFY(g.setInputValue(colour, 0, glm::vec4(0.2f, 0.5f, 0.9f, 0.0f)));
        QVERIFY(g.setInputValue(rough, 0, glm::vec4(0.6f)));
        QVERIFY(g.setInputValue(metal, 0, glm::vec4(0.0f)));
        QVERIFY(g.connect({colour, 0, out, PortIndex(outputInputForParam(ParamId::BaseColor))}));
        QVERIFY(g.connect({rough, 0, out, PortIndex(outputInputForParam(ParamId::Roughness))}));
        QVERIFY(g.connect({metal, 0, out, PortIndex(outputInputForParam(ParamId::Metallic))}));
        Scene byGraph = variedScene(); // gold parameters, overwritten by the graph
        byGraph.material.graph = SharedGraph(g);
        const reference::Result a = renderOrFail(byParams, o);
        const reference::Result b = renderOrFail(byGraph, o);
        QVERIFY(!a.image.pixels.empty());
        QVERIFY(a.image.pixels == b.image.pixels);

        // A black and white checker (8 squares per UV unit) into the base colour: neighbouring
        // pixels on the sphere differ far more than under a constant grey.
        Graph checker;
        const NodeId out2 = checker.addNode(kOutputTypeId).node;
        const NodeId squares = checker.addNode("noise.checker").node;
        QVERIFY(checker.setInputValue(squares, 1, glm::vec4(8.0f)));
        QVERIFY(checker.setInputValue(squares, 2, glm::vec4(1.0f)));
        QVERIFY(checker.setInputValue(squares, 3, glm::vec4(0.0f)));
        QVERIFY(checker.connect(
            {squares, 0, out2, PortIndex(outputInputForParam(ParamId::BaseColor))}));
        Scene checkered = byParams;
        checkered.material.graph = SharedGraph(checker);
        Scene grey = byParams;
        grey.material.setColor(ParamId::BaseColor, glm::vec3(0.5f));
        o.samplesPerPixel = 16;
        const auto contrast = [](const Image& img) {
            double sum = 0.0;
            for (int y = 6; y < 14; ++y) // the middle of the sphere
                for (int x = 6; x < 13; ++x)
                    sum += std::abs(img.rgba(x + 1, y).g - img.rgba(x, y).g);
            return sum;
        };
        const double withChecker = contrast(renderOrFail(checkered, o).image);
        const double withGrey = contrast(renderOrFail(grey, o).image);
        QVERIFY2(withChecker > 3.0 * withGrey,
                 qPrintable(QStringLiteral("%1 vs %2").arg(withChecker).arg(withGrey)));
    }

    // The KHR lobes' texture slots multiply their factors at every hit, in the channel
    // texture_ref.h names: a constant grey map (128/255 in every channel) renders as the factor
    // times 128/255 does.
    void lobeTextureSlotsScaleTheirFactors_data() {
        QTest::addColumn<int>("slot");
        QTest::addColumn<int>("param");
        QTest::newRow("clearcoat") << int(TextureSlot::Clearcoat) << int(ParamId::ClearcoatWeight);
        QTest::newRow("clearcoatRoughness")
            << int(TextureSlot::ClearcoatRoughness) << int(ParamId::ClearcoatRoughness);
        QTest::newRow("sheenRoughness")
            << int(TextureSlot::SheenRoughness) << int(ParamId::SheenRoughness);
        QTest::newRow("specular") << int(TextureSlot::Specular) << int(ParamId::SpecularWeight);
    }
    void lobeTextureSlotsScaleTheirFactors() {
        QFETCH(int, slot);
        QFETCH(int, param);
        QTemporaryDir dir;
        const std::string file = dir.filePath("grey.png").toStdString();
        Image grey(4, 4, 4);
        std::fill(grey.pixels.begin(), grey.pixels.end(), 128.0f / 255.0f);
        std::string error;
        QVERIFY2(writeImage(file, grey, PixelFormat::UInt8, &error), error.c_str());
        Scene base = variedScene();
        base.material.setScalar(ParamId::Metallic, 0.0f);
        base.material.setScalar(ParamId::ClearcoatWeight, 0.8f);
        base.material.setScalar(ParamId::ClearcoatRoughness, 0.5f);
        base.material.setScalar(ParamId::SheenWeight, 1.0f);
        base.material.setScalar(ParamId::SheenRoughness, 0.8f);
        Scene textured = base;
        TextureRef ref;
        ref.file = file;
        textured.material.setTexture(TextureSlot(slot), ref);
        Scene scaled = base;
        scaled.material.setScalar(ParamId(param),
                                  base.material.scalar(ParamId(param)) * (128.0f / 255.0f));
        Scene untouched = base;
        reference::Options o;
        o.width = o.height = 16;
        o.samplesPerPixel = 4;
        const Image a = renderOrFail(textured, o).image;
        const Image b = renderOrFail(scaled, o).image;
        const Image c = renderOrFail(untouched, o).image;
        QVERIFY(!a.pixels.empty());
        QVERIFY2(rmse(a, b) < 1e-4, qPrintable(QString::number(rmse(a, b))));
        QVERIFY2(rmse(a, c) > 1e-3, "the slot changed nothing");
    }

    // KHR_materials_anisotropy at a hit: the mesh tangent turned by the rotation, counter-
    // clockwise toward the bitangent (cross(n, t) w), made orthogonal to the shading normal.
    void anisotropyDirectionFromTheTangentFrame() {
        using reference::anisotropyWorldDirection;
        const glm::vec3 n(0, 0, 1);
        const auto near = [](glm::vec3 a, glm::vec3 b) { return glm::length(a - b) < 1e-5f; };
        QVERIFY(near(anisotropyWorldDirection(n, {1, 0, 0, 1}, {{1, 0}, 0}), {1, 0, 0}));
        QVERIFY(near(anisotropyWorldDirection(n, {1, 0, 0, 1}, {{1, 0}, 90}), {0, 1, 0}));
        QVERIFY(near(anisotropyWorldDirection(n, {1, 0, 0, -1}, {{1, 0}, 90}), {0, -1, 0}));
        QVERIFY(near(anisotropyWorldDirection(n, {1, 0, 0, 1}, {{0, 2}, 0}), {0, 1, 0}));
        QVERIFY(near(anisotropyWorldDirection(n, {1, 0, 0, 1}, {{0, 1}, 90}), {-1, 0, 0}));
        // A tangent not in the plane is projected; none at all still gives a unit, orthogonal one.
        QVERIFY(near(anisotropyWorldDirection(n, {2, 0, 1, 1}, {{1, 0}, 0}), {1, 0, 0}));
        const glm::vec3 any = anisotropyWorldDirection(n, {0, 0, 0, 1}, {{1, 0}, 0});
        QVERIFY(std::abs(glm::length(any) - 1.0f) < 1e-5f && std::abs(any.z) < 1e-5f);
    }

    void anisotropyChangesTheImage() {
        reference::Options o;
        o.width = o.height = 16;
        o.samplesPerPixel = 4;
        Scene iso = variedScene();
        Scene aniso = iso;
        aniso.material.setScalar(ParamId::AnisotropyStrength, 0.8f);
        Scene turned = aniso;
        turned.material.setScalar(ParamId::AnisotropyRotation, 90.0f);
        const Image a = renderOrFail(iso, o).image, b = renderOrFail(aniso, o).image,
                    c = renderOrFail(turned, o).image;
        QVERIFY(!a.pixels.empty());
        QVERIFY2(rmse(a, b) > 1e-3, qPrintable(QString::number(rmse(a, b))));
        QVERIFY2(rmse(b, c) > 1e-3, qPrintable(QString::number(rmse(b, c))));
    }

    void sameSeedSameImageWhateverTheThreads() {
        reference::Options o;
        o.width = o.height = 20;
        o.samplesPerPixel = 4;
        o.threads = 1;
        const reference::Result one = renderOrFail(variedScene(), o);
        o.threads = 2;
        const reference::Result two = renderOrFail(variedScene(), o);
        QVERIFY(!one.image.pixels.empty());
        QVERIFY(one.image.pixels == two.image.pixels);
        o.seed = 7;
        const reference::Result other = renderOrFail(variedScene(), o);
        QVERIFY(other.image.pixels != one.image.pixels);
    }

    void errorHalvesForFourTimesTheSamples() {
        reference::Options o;
        o.width = o.height = 24;
        o.samplesPerPixel = 256;
        o.seed = 99; // independent of the images compared with it
        const Image truth = renderOrFail(variedScene(), o).image;
        o.seed = 1;
        o.samplesPerPixel = 4;
        const double e4 = rmse(renderOrFail(variedScene(), o).image, truth);
        o.samplesPerPixel = 16;
        const double e16 = rmse(renderOrFail(variedScene(), o).image, truth);
        // Monte Carlo's 1/sqrt(spp): 4x the samples halve the error; the stratified first
        // vertex (path_sampling.h's Rng::stratify) converges a little faster (2.8 measured), the
        // truth's own noise lowers the ratio a little. Above 4.5 the comparison itself is broken.
        const double ratio = e4 / e16;
        QVERIFY2(ratio > 1.6 && ratio < 4.5,
                 qPrintable(QStringLiteral("%1 / %2 = %3").arg(e4).arg(e16).arg(ratio)));
    }
};

QTEST_APPLESS_MAIN(TestReferenceRenderer)
#include "test_reference_renderer.moc"

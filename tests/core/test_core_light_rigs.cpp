// Light rigs (core/light_rigs.h): every rig is a valid scene (saved, validated and read back
// equal), ids are unique and found again by matchingLightRig, the default scene uses the first
// rig, lights that aim do so at the mesh, and an edited rig matches none.
#include "core/document_io.h"
#include "core/light_rigs.h"

#include <QTest>
#include <glm/geometric.hpp>
#include <set>

using namespace velvet;

class TestCoreLightRigs : public QObject {
    Q_OBJECT

private slots:
    void idsAreUniqueAndFound() {
        std::set<std::string_view> ids;
        for (const LightRig& rig : lightRigs()) {
            QVERIFY2(ids.insert(rig.id).second, rig.id.data());
            QVERIFY(!rig.label.empty() && !rig.description.empty());
            const auto lights = lightRigLights(rig.id);
            QVERIFY(lights.has_value());
            QCOMPARE(matchingLightRig(*lights).value_or(""), rig.id);
        }
        QVERIFY(lightRigs().size() >= 6);
        QVERIFY(!lightRigLights("no-such-rig").has_value());
    }

    void everyRigIsAValidSceneThatRoundTrips() {
        for (const LightRig& rig : lightRigs()) {
            Scene scene = defaultScene();
            scene.lights = *lightRigLights(rig.id);
            Problems problems;
            const auto back = parseScene(sceneToJson(scene), "rig.json", {}, problems);
            QVERIFY2(back && !problems.hasErrors(),
                     problems.items.empty() ? rig.id.data()
                                            : problems.items.front().toString().c_str());
            QVERIFY(back->lights == scene.lights);
        }
    }

    void defaultSceneUsesTheKeyRig() {
        QCOMPARE(matchingLightRig(defaultScene().lights).value_or(""), std::string_view("key"));
        QCOMPARE(lightRigs().front().id, std::string_view("key"));
    }

    void aimedLightsPointAtTheMesh() {
        for (const LightRig& rig : lightRigs()) {
            // Held here: a range-for over *lightRigLights(...) would iterate a destroyed
            // temporary (ASan: stack-use-after-scope).
            const std::optional<std::vector<Light>> lights = lightRigLights(rig.id);
            QVERIFY(lights);
            for (const Light& light : *lights) {
                if (light.type == LightType::Spot ||
                    (light.type == LightType::Area && light.shape == AreaShape::Rectangle)) {
                    // From the light towards the origin, within a degree.
                    const glm::vec3 toMesh = glm::normalize(-light.position);
                    QVERIFY2(glm::dot(glm::normalize(light.direction), toMesh) > 0.9998f,
                             light.name.c_str());
                }
                if (light.type == LightType::Directional)
                    QVERIFY2(light.direction.y < 0.0f, light.name.c_str()); // from above
            }
        }
    }

    void colouredPointsAreManyDistinctAndReachTheMesh() {
        const auto lights = *lightRigLights("coloured-points");
        QCOMPARE(lights.size(), size_t(64));
        std::set<std::tuple<float, float, float>> colours;
        for (const Light& light : lights) {
            QCOMPARE(light.type, LightType::Point);
            colours.insert({light.color.r, light.color.g, light.color.b});
            // The unit sphere's surface lies within the light's range.
            QVERIFY(glm::length(light.position) - 1.0f < light.range);
        }
        QVERIFY(colours.size() >= 32);
    }

    void editedRigMatchesNone() {
        auto lights = *lightRigLights("three-point");
        lights[1].intensity += 0.5f;
        QVERIFY(!matchingLightRig(lights).has_value());
        lights.clear();
        QCOMPARE(matchingLightRig(lights).value_or(""), std::string_view("environment"));
    }
};

QTEST_APPLESS_MAIN(TestCoreLightRigs)
#include "test_core_light_rigs.moc"

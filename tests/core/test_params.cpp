// Proves the parameter and texture-slot metadata is self-consistent, since panels, serializers
// and schemas are generated from it: a bad entry would break all of them at once.
#include "core/material.h"
#include "core/scene.h"

#include <QtTest>
#include <array>
#include <cmath>
#include <limits>
#include <set>
#include <string>

using namespace velvet;

class TestParams : public QObject {
    Q_OBJECT
private slots:
    // core/param_meta.h's builders, the one way the metadata tables fill a ParamMeta.
    void metadataBuilders() {
        const ParamMeta f = floatParam("a.b", "A", "G", -1, 4, 0.5f, "nits", "tip", 2.0f);
        QCOMPARE(f.type, ParamType::Float);
        QCOMPARE(f.id, std::string_view("a.b"));
        QCOMPARE(f.group, std::string_view("G"));
        QCOMPARE(f.min, -1.0f);
        QCOMPARE(f.max, 4.0f);
        QCOMPARE(f.defaultValue, glm::vec3(0.5f));
        QCOMPARE(f.unit, std::string_view("nits"));
        QCOMPARE(f.softMax, 2.0f);
        QCOMPARE(f.colorSpace, ColorSpace::None);
        const ParamMeta c = colorParam("c", "C", "G", 0, 8, glm::vec3(1, 2, 3), "tip");
        QCOMPARE(c.type, ParamType::Color);
        QCOMPARE(c.colorSpace, ColorSpace::Linear);
        QCOMPARE(c.max, 8.0f);
        QCOMPARE(c.defaultValue, glm::vec3(1, 2, 3));
        static constexpr std::array<std::string_view, 3> names{"x", "y", "z"};
        const ParamMeta k = choiceParam("k", "K", "G", names, 2, "tip");
        QCOMPARE(k.type, ParamType::Choice);
        QCOMPARE(k.min, 0.0f);
        QCOMPARE(k.max, 2.0f);
        QCOMPARE(k.defaultValue.x, 2.0f);
        QCOMPARE(k.choices.size(), size_t(3));
        QCOMPARE(k.choices[1], std::string_view("y"));
        // The material table is built with them: its choices and colours read as above.
        const ParamMeta& distribution = paramMeta(ParamId::Distribution);
        QCOMPARE(distribution.group, std::string_view("BRDF"));
        QCOMPARE(distribution.max, float(distribution.choices.size() - 1));
        QCOMPARE(paramMeta(ParamId::BaseColor).colorSpace, ColorSpace::Linear);
        QCOMPARE(paramMeta(ParamId::EmissiveStrength).softMax, 20.0f);
    }
    void everyParamIdHasMeta() {
        QCOMPARE(static_cast<int>(paramMetas().size()), kParamCount);
        for (int i = 0; i < kParamCount; ++i) {
            const ParamMeta& m = paramMeta(static_cast<ParamId>(i));
            QVERIFY2(!m.id.empty(), "empty id");
            QVERIFY2(!m.label.empty(), std::string(m.id).c_str());
            QVERIFY2(!m.group.empty(), std::string(m.id).c_str());
            QVERIFY2(!m.tooltip.empty(), std::string(m.id).c_str());
            QCOMPARE(paramIdFromString(m.id), static_cast<ParamId>(i));
        }
        QCOMPARE(paramIdFromString("lobes.base.nothing"), ParamId::Count);
    }

    void idsUniqueAndPathShaped() {
        std::set<std::string_view> ids;
        for (const ParamMeta& m : paramMetas()) {
            QVERIFY2(ids.insert(m.id).second, std::string(m.id).c_str());
            QVERIFY2(m.id.find('.') != std::string_view::npos, std::string(m.id).c_str());
            QVERIFY2(m.id.front() != '.' && m.id.back() != '.', std::string(m.id).c_str());
            QVERIFY2(m.id.find("..") == std::string_view::npos, std::string(m.id).c_str());
        }
        // A leaf may not also be an object: "a.b" and "a.b.c" cannot both exist.
        for (std::string_view a : ids)
            for (std::string_view b : ids)
                QVERIFY2(!(b.size() > a.size() && b.substr(0, a.size()) == a && b[a.size()] == '.'),
                         std::string(b).c_str());
    }

    void defaultsInRange() {
        for (const ParamMeta& m : paramMetas()) {
            const std::string id(m.id);
            QVERIFY2(m.min < m.max, id.c_str());
            const int channels = m.type == ParamType::Color ? 3 : 1;
            for (int c = 0; c < channels; ++c) {
                QVERIFY2(m.defaultValue[c] >= m.min && m.defaultValue[c] <= m.max, id.c_str());
            }
            if (m.softMax != 0.0f)
                QVERIFY2(m.softMax > m.min && m.softMax <= m.max, id.c_str());
            QCOMPARE(m.colorSpace == ColorSpace::Linear, m.type == ParamType::Color);
        }
    }

    void choicesSane() {
        for (const ParamMeta& m : paramMetas()) {
            const std::string id(m.id);
            if (m.type != ParamType::Choice) {
                QVERIFY2(m.choices.empty(), id.c_str());
                continue;
            }
            QVERIFY2(m.choices.size() >= 2, id.c_str());
            QCOMPARE(m.min, 0.0f);
            QCOMPARE(m.max, static_cast<float>(m.choices.size() - 1));
            QCOMPARE(m.defaultValue.x, std::round(m.defaultValue.x));
            std::set<std::string_view> names;
            for (std::string_view n : m.choices) {
                QVERIFY2(names.insert(n).second, id.c_str());
                for (char ch : n) // file names are lowercase-hyphenated
                    QVERIFY2((ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') || ch == '-',
                             std::string(n).c_str());
            }
        }
    }

    void textureSlotsSane() {
        QCOMPARE(static_cast<int>(textureSlotMetas().size()), kTextureSlotCount);
        std::set<std::string_view> ids;
        for (const TextureSlotMeta& s : textureSlotMetas()) {
            QVERIFY(!s.id.empty() && !s.label.empty() && !s.tooltip.empty());
            QVERIFY2(ids.insert(s.id).second, std::string(s.id).c_str());
        }
    }

    void sceneEnumNamesUnique() {
        for (auto names :
             {lightTypeNames(), areaShapeNames(), backgroundModeNames(), previewMeshKindNames()}) {
            std::set<std::string_view> seen(names.begin(), names.end());
            QCOMPARE(seen.size(), names.size());
        }
    }

    void defaultMaterialUsesDefaults() {
        const Material m;
        for (int i = 0; i < kParamCount; ++i)
            QCOMPARE(m.value(static_cast<ParamId>(i)),
                     paramMeta(static_cast<ParamId>(i)).defaultValue);
        QVERIFY(m.tags.empty());
    }

    void setValueClamps() {
        Material m;
        m.setScalar(ParamId::Roughness, 2.0f);
        QCOMPARE(m.scalar(ParamId::Roughness), 1.0f);
        m.setScalar(ParamId::Roughness, -1.0f);
        QCOMPARE(m.scalar(ParamId::Roughness), 0.0f);
        m.setColor(ParamId::BaseColor, {1.5f, -0.5f, 0.25f});
        QCOMPARE(m.color(ParamId::BaseColor), glm::vec3(1.0f, 0.0f, 0.25f));
        m.setChoice(ParamId::Visibility, 99);
        QCOMPARE(m.choice(ParamId::Visibility),
                 static_cast<int>(paramMeta(ParamId::Visibility).choices.size() - 1));
        m.setValue(ParamId::Diffuse, glm::vec3(0.6f)); // choices round to an index
        QCOMPARE(m.choice(ParamId::Diffuse), 1);
    }

    void setValueRejectsNaN() {
        Material m;
        m.setScalar(ParamId::Roughness, 0.25f);
        m.setScalar(ParamId::Roughness, std::numeric_limits<float>::quiet_NaN());
        QVERIFY(std::isfinite(m.scalar(ParamId::Roughness)));
        QCOMPARE(m.scalar(ParamId::Roughness), paramMeta(ParamId::Roughness).defaultValue.x);
        m.setScalar(ParamId::Ior, std::numeric_limits<float>::infinity());
        QVERIFY(std::isfinite(m.scalar(ParamId::Ior)));
        m.setColor(ParamId::SheenColor, {std::nanf(""), 0.5f, 0.5f});
        QVERIFY(std::isfinite(m.color(ParamId::SheenColor).x));
    }

    void resetValue() {
        Material m;
        m.setScalar(ParamId::Metallic, 1.0f);
        m.resetValue(ParamId::Metallic);
        QCOMPARE(m.scalar(ParamId::Metallic), paramMeta(ParamId::Metallic).defaultValue.x);
        QVERIFY(m == Material{});
    }
};

QTEST_APPLESS_MAIN(TestParams)
#include "test_params.moc"

// The post-chain model: catalogue metadata, chain edits, stage rules with their explanations,
// chain presets (round trips, all-or-nothing loading with JSON paths), the generated schema, and
// scene loading checking effects against the catalogue.
//
// Regenerating resources/schemas/post-chain.schema.json and the catalogue in docs/post-effects.md
// after a catalogue change:
//   VELVET_UPDATE_SCHEMAS=1 VELVET_UPDATE_DOCS=1 ctest --test-dir build -R test_core_post_chain
#include "core/atomic_file.h"
#include "core/document_io.h"
#include "core/post_chain_io.h"
#include "core/post_effects.h"
#include "shipped_schema.h"

#include <QtTest>
#include <filesystem>
#include <set>

using namespace velvet;
namespace fs = std::filesystem;

namespace {

PostChain chainOf(std::initializer_list<const char*> types) {
    PostChain c;
    for (const char* t : types)
        c.effects.push_back(makeEffect(t));
    return c;
}

std::string allMessages(const Problems& p) {
    std::string s;
    for (const Problem& x : p.items)
        s += x.toString() + "\n";
    return s;
}

} // namespace

class TestCorePostChain : public QObject {
    Q_OBJECT
private slots:
    void toneMapOperatorsAreFoundByName() {
        // The renderer's built-in curves reach the tonemap effect by these names.
        for (const char* name : {"pbr-neutral", "aces", "reinhard", "linear"})
            QVERIFY2(toneMapOperatorIndex(name) >= 0, name);
        QCOMPARE(toneMapOperatorIndex("pbr-neutral"), 0);
        QCOMPARE(toneMapOperatorIndex("no-such-curve"), -1);
    }
    void catalogueIsWellFormed() {
        std::set<std::string_view> types;
        for (const EffectMeta& m : postEffectCatalogue()) {
            QVERIFY2(types.insert(m.type).second, std::string(m.type).c_str());
            QVERIFY(!m.params.empty());
            QVERIFY(m.reads & kReadsColor);
            std::set<std::string_view> ids;
            for (const ParamMeta& p : m.params) {
                QVERIFY(ids.insert(p.id).second);
                for (int k = 0; k < paramComponents(p); ++k)
                    QVERIFY2(p.defaultValue[k] >= p.min && p.defaultValue[k] <= p.max,
                             (std::string(m.type) + "." + std::string(p.id)).c_str());
                QVERIFY(!p.tooltip.empty());
            }
        }
        // Every effect of the issue is there.
        for (const char* t :
             {"bloom", "tonemap", "gaussian_blur", "vignette", "pixelate", "night_vision",
              "motion_blur", "toon", "depth_of_field", "pointillism", "paintbrush", "vaporwave",
              "color_grading", "film_grain", "chromatic_aberration", "sharpen", "fxaa"})
            QVERIFY2(findPostEffect(t), t);
        QVERIFY(findPostEffect("motion_blur")->reads & kReadsCameraMotion);
        QVERIFY(findPostEffect("toon")->reads & kReadsNormals);
        QCOMPARE(describeReads(findPostEffect("motion_blur")->reads),
                 std::string("colour, depth, previous frame, camera motion"));
    }

    void chainEdits() {
        PostChain c = chainOf({"bloom", "tonemap", "vignette"});
        QVERIFY(setEffectEnabled(c, 2, false));
        QVERIFY(!c.effects[2].enabled);
        QVERIFY(duplicateEffect(c, 0));
        QCOMPARE(c.effects.size(), size_t(4));
        QCOMPARE(c.effects[1].type, std::string("bloom"));
        QVERIFY(moveEffect(c, 3, 0));
        QCOMPARE(c.effects[0].type, std::string("vignette"));
        QCOMPARE(c.effects[3].type, std::string("tonemap"));
        QVERIFY(moveEffect(c, 0, 3));
        QCOMPARE(c.effects[3].type, std::string("vignette"));
        QVERIFY(removeEffect(c, 1));
        QCOMPARE(c.effects.size(), size_t(3));
        QVERIFY(!removeEffect(c, 7));
        QVERIFY(!moveEffect(c, 0, 9));
        QVERIFY(!duplicateEffect(c, 3));
        QVERIFY(!setEffectEnabled(c, 3, true));
    }

    /// Ids: unique per created or loaded instance, kept by copies, new for a duplicate, not part
    /// of an instance's value (a loaded chain equals the saved one), never written to a file.
    void effectIdsAreStableIdentities() {
        PostChain chain;
        chain.effects = {makeEffect("bloom"), makeEffect("vignette"), makeEffect("fxaa")};
        const std::set<EffectId> ids{chain.effects[0].id, chain.effects[1].id, chain.effects[2].id};
        QCOMPARE(ids.size(), size_t(3));
        QVERIFY(!ids.count(0));
        const EffectId vignette = chain.effects[1].id;
        QVERIFY(moveEffect(chain, 1, 2));
        QCOMPARE(findEffectIndex(chain, vignette), 2L);
        QCOMPARE(findEffectIndex(chain, 0), -1L);
        const PostChain copy = chain;
        QCOMPARE(copy.effects[2].id, vignette);
        QVERIFY(duplicateEffect(chain, 2));
        QCOMPARE(chain.effects[2].id, vignette);
        QVERIFY(chain.effects[3].id != vignette && !ids.count(chain.effects[3].id));
        QCOMPARE(chain.effects[3], chain.effects[2]); // same value, other identity

        const std::string text = postChainToJson({"ids", copy});
        QVERIFY2(text.find("\"id\"") == std::string::npos, text.c_str());
        Problems problems;
        const std::optional<PostChainPreset> loaded = parsePostChain(text, "ids.json", problems);
        QVERIFY(loaded);
        QCOMPARE(loaded->chain, copy);
        QVERIFY(loaded->chain.effects[0].id != copy.effects[0].id); // loading creates instances
    }

    /// The value rules, in core next to the metadata: clamped per channel, a choice rounded, a
    /// non-finite value replaced by the default; setEffectParam applies them by id.
    void valueRulesClampAndRound() {
        const EffectMeta& grading = *findPostEffect("color_grading");
        const ParamMeta& gain = *findEffectParam(grading, "gain");
        QCOMPARE(constrainParamValue(gain, glm::vec3(-1.0f, 2.0f, 9.0f)),
                 glm::vec3(0.0f, 2.0f, gain.max));
        const ParamMeta& curve = *findEffectParam(*findPostEffect("tonemap"), "operator");
        QCOMPARE(constrainParamValue(curve, glm::vec3(2.5f)).x, 3.0f);
        QCOMPARE(constrainParamValue(curve, glm::vec3(99.0f)).x, curve.max);
        const ParamMeta& contrast = *findEffectParam(grading, "contrast");
        QCOMPARE(constrainParamValue(contrast, glm::vec3(std::nanf(""))).x,
                 contrast.defaultValue.x);

        PostChain chain;
        chain.effects = {makeEffect("tonemap"), makeEffect("color_grading")};
        const EffectId id = chain.effects[1].id;
        QVERIFY(setEffectParam(chain, id, "gain", glm::vec3(-1.0f, 2.0f, 9.0f)));
        QCOMPARE(chain.effects[1].params["gain"], (std::vector<float>{0.0f, 2.0f, gain.max}));
        QVERIFY(setEffectParam(chain, id, "contrast", glm::vec3(7.0f, 1.0f, 1.0f)));
        QCOMPARE(chain.effects[1].params["contrast"], (std::vector<float>{contrast.max}));
        QVERIFY(!setEffectParam(chain, id, "no_such_param", glm::vec3(1.0f)));
        QVERIFY(!setEffectParam(chain, id + 1000, "contrast", glm::vec3(1.0f)));
        QVERIFY(checkEffectParams(chain).empty()); // what the rules store, a file accepts
    }

    void seedOrderIsValid() {
        // Seed 004: pre-passes, HDR effects, paintbrush, tone mapping, LDR effects.
        const PostChain c = chainOf({"bloom", "motion_blur", "depth_of_field", "paintbrush",
                                     "tonemap", "vignette", "fxaa"});
        QVERIFY(checkStageOrder(c).empty());
        QVERIFY(checkEffectParams(c).empty());
        QVERIFY(checkStageOrder(defaultPostChain()).empty());
        // Stage "any" effects may sit anywhere.
        QVERIFY(checkStageOrder(chainOf({"gaussian_blur", "bloom", "pixelate", "tonemap",
                                         "gaussian_blur", "vignette"}))
                    .empty());
    }

    void stageViolationsAreExplained() {
        auto issues = checkStageOrder(chainOf({"vignette", "tonemap"}));
        QCOMPARE(issues.size(), size_t(1));
        QCOMPARE(issues[0].index, size_t(1));
        qInfo("%s", issues[0].message.c_str());
        QVERIFY(issues[0].message.find("must come before \"vignette\"") != std::string::npos);
        QVERIFY(issues[0].message.find("display values") != std::string::npos);

        issues = checkStageOrder(chainOf({"motion_blur", "bloom", "tonemap"}));
        QCOMPARE(issues.size(), size_t(1));
        QVERIFY(issues[0].message.find("pre-pass") != std::string::npos);

        issues = checkStageOrder(chainOf({"tonemap", "toon"}));
        QCOMPARE(issues.size(), size_t(1));
        QVERIFY(issues[0].message.find("scene-linear HDR") != std::string::npos);

        issues = checkStageOrder(chainOf({"tonemap", "vignette", "tonemap"}));
        QVERIFY(!issues.empty());
        QVERIFY(issues[0].message.find("already tone maps") != std::string::npos);

        // Paintbrush comes after the other HDR effects.
        issues = checkStageOrder(chainOf({"paintbrush", "toon"}));
        QCOMPARE(issues.size(), size_t(1));
    }

    void paramChecks() {
        PostChain c = chainOf({"gaussian_blur"});
        c.effects[0].params["sigma"] = {100.0f};
        c.effects[0].params["sigmaa"] = {1.0f};
        c.effects.push_back(EffectInstance{"blom", true, {}});
        const auto issues = checkEffectParams(c);
        QCOMPARE(issues.size(), size_t(3));
        std::string all;
        for (const auto& i : issues)
            all += i.message + "\n";
        qInfo("%s", all.c_str());
        QVERIFY(all.find("did you mean \"bloom\"") != std::string::npos);
        QVERIFY(all.find("[0.1, 32]") != std::string::npos);
    }

    void shippedPresetsLoadAndRoundTrip() {
        int count = 0;
        for (const auto& entry :
             fs::directory_iterator(fs::path(VELVET_SOURCE_DIR) / "resources/post-chains")) {
            Problems problems;
            const auto preset = loadPostChainFile(entry.path(), problems);
            QVERIFY2(preset && problems.items.empty(), allMessages(problems).c_str());
            QVERIFY(!preset->name.empty());
            QVERIFY(checkEffectParams(preset->chain).empty());
            const std::string text = postChainToJson(*preset);
            const auto again = parsePostChain(text, "round trip", problems);
            QVERIFY2(again, allMessages(problems).c_str());
            QVERIFY(*again == *preset);
            QCOMPARE(postChainToJson(*again), text);
            ++count;
        }
        QVERIFY(count >= 6);
    }

    void saveAndLoadFile() {
        QTemporaryDir dir;
        PostChainPreset preset{"Mine", defaultPostChain()};
        preset.chain.effects[2].enabled = false;
        preset.chain.effects[2].params["color"] = {0.25f, 0.5f, 0.75f};
        const fs::path file = fs::path(dir.path().toStdString()) / "mine.json";
        std::string error;
        QVERIFY2(savePostChainFile(preset, file, &error), error.c_str());
        Problems problems;
        const auto loaded = loadPostChainFile(file, problems);
        QVERIFY2(loaded, allMessages(problems).c_str());
        QVERIFY(*loaded == preset);
    }

    void badPresetsAreRefusedWithPaths_data() {
        QTest::addColumn<QString>("json");
        QTest::addColumn<QString>("expected");
        const QString head = R"({"format": "velvet.post-chain", "version": 1, "effects": )";
        QTest::newRow("unknown type")
            << head + R"([{"type": "blom"}]})"
            << R"(effects[0].type: unknown effect type "blom" (did you mean "bloom"?))";
        QTest::newRow("out of range")
            << head + R"([{"type": "gaussian_blur", "params": {"sigma": [99]}}]})"
            << "effects[0].params.sigma[0]: expected a number in [0.1, 32], got 99";
        QTest::newRow("unknown param")
            << head + R"([{"type": "vignette", "params": {"strength": 0.3}}]})"
            << R"(effects[0].params.strength: unknown key "strength")";
        QTest::newRow("bad choice")
            << head + R"([{"type": "tonemap", "params": {"operator": "acse"}}]})"
            << R"(effects[0].params.operator: expected one of "pbr-neutral")";
        QTest::newRow("order") << head + R"([{"type": "vignette"}, {"type": "tonemap"}]})"
                               << R"(effects[1]: "tonemap" (effects[1]) is a tone mapping effect)";
        QTest::newRow("newer") << R"({"format": "velvet.post-chain", "version": 9, "effects": []})"
                               << "version: version 9 is newer";
        QTest::newRow("scene format")
            << R"({"format": "velvet.scene", "version": 1, "effects": []})"
            << R"(format: expected "velvet.post-chain")";
        QTest::newRow("colour size")
            << head + R"([{"type": "vignette", "params": {"color": [1, 0]}}]})"
            << "effects[0].params.color";
    }
    void badPresetsAreRefusedWithPaths() {
        QFETCH(QString, json);
        QFETCH(QString, expected);
        Problems problems;
        const auto preset = parsePostChain(json.toStdString(), "bad.json", problems);
        const std::string all = allMessages(problems);
        qInfo("%s", all.c_str());
        QVERIFY(!preset);
        QVERIFY2(all.find(expected.toStdString()) != std::string::npos, all.c_str());
    }

    void schemaFileIsGenerated() {
        const fs::path file =
            fs::path(VELVET_SOURCE_DIR) / "resources/schemas/post-chain.schema.json";
        const std::string generated = postChainJsonSchema();
        const std::string problem = test::checkShippedSchema(file, generated);
        QVERIFY2(problem.empty(), problem.c_str());
        QVERIFY(generated.find("\"const\": \"paintbrush\"") != std::string::npos);
    }

    // docs/post-effects.md embeds the catalogue generated from the metadata (`velvet
    // post-catalogue`), so every effect, parameter, range and default there is the code's.
    void docsCatalogueIsGenerated() {
        const fs::path file = fs::path(VELVET_SOURCE_DIR) / "docs/post-effects.md";
        std::string error;
        const auto text = readWholeFile(file, 1 << 24, &error);
        QVERIFY2(text, error.c_str());
        const std::string begin = "<!-- catalogue:begin -->\n", end = "<!-- catalogue:end -->";
        const size_t a = text->find(begin), b = text->find(end);
        QVERIFY2(a != std::string::npos && b != std::string::npos && a < b,
                 "docs/post-effects.md lacks the catalogue markers");
        const std::string generated = postEffectCatalogueMarkdown();
        const char* update = std::getenv("VELVET_UPDATE_DOCS");
        if (update && std::string(update) == "1" &&
            text->substr(a + begin.size(), b - a - begin.size()) != generated) {
            const std::string updated =
                text->substr(0, a + begin.size()) + generated + text->substr(b);
            QVERIFY2(writeFileAtomically(file, updated, &error), error.c_str());
            qWarning("VELVET_UPDATE_DOCS=1: rewrote the catalogue in %s", file.string().c_str());
            return;
        }
        QVERIFY2(text->substr(a + begin.size(), b - a - begin.size()) == generated,
                 "the catalogue in docs/post-effects.md is out of date; regenerate with "
                 "VELVET_UPDATE_DOCS=1 (or paste `velvet post-catalogue`)");
        for (const EffectMeta& m : postEffectCatalogue()) {
            QVERIFY(generated.find("(`" + std::string(m.type) + "`)") != std::string::npos);
            for (const ParamMeta& p : m.params)
                QVERIFY(generated.find("| `" + std::string(p.id) + "` |") != std::string::npos);
        }
    }

    void sceneEffectsAreChecked() {
        const std::string scene =
            R"({"format": "velvet.scene", "version": 1, "post": {"effects": [
                {"type": "tonemap", "params": {"operator": "aces"}},
                {"type": "bloom", "params": {"intensity": [0.5]}},
                {"type": "vignete"}]}})";
        Problems problems;
        QVERIFY(!parseScene(scene, "s.json", {}, problems));
        const std::string all = allMessages(problems);
        qInfo("%s", all.c_str());
        QVERIFY(all.find("post.effects[2].type: unknown effect type \"vignete\"") !=
                std::string::npos);

        Problems ok;
        const auto loaded = parseScene(
            R"({"format": "velvet.scene", "version": 1, "post": {"effects": [
                {"type": "bloom", "params": {"threshold": 1.5}},
                {"type": "tonemap", "params": {"operator": "agx"}}]}})",
            "s.json", {}, ok);
        QVERIFY2(loaded, allMessages(ok).c_str());
        QCOMPARE(loaded->post.effects[1].params.at("operator"), std::vector<float>{4.0f});
        QCOMPARE(loaded->post.effects[0].params.at("threshold"), std::vector<float>{1.5f});
    }
};

QTEST_GUILESS_MAIN(TestCorePostChain)
#include "test_core_post_chain.moc"

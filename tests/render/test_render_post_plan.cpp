// The post chain's plan (render/post_plan.h) without a GL context: which effects fuse into which
// passes, what is skipped, where the implicit tone map goes, when the display transform draws a
// tone map, where fusion stops for lack of parameter slots, and that a still chain plans once;
// and that shader files are named by role.
#include "core/post_effects.h"
#include "render/post_effect.h"
#include "render/post_plan.h"

#include <QtTest>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace velvet;
using namespace velvet::render;
using Kind = PostPlanStep::Kind;

namespace {

PostChain chainOf(std::initializer_list<const char*> types) {
    PostChain c;
    for (const char* t : types)
        c.effects.push_back(makeEffect(t));
    return c;
}

/// "bloom | tonemap+vignette | fxaa": one name per step.
QString shape(const PostPlan& plan) {
    QStringList names;
    for (const PostPlanStep& s : plan.steps)
        names << QString::fromStdString(s.name);
    return names.join(" | ");
}

} // namespace

class TestRenderPostPlan : public QObject {
    Q_OBJECT
private slots:
    void defaultChainFusesTheToneMapWithTheVignette() {
        const PostPlan plan = planPostChain(defaultPostChain(), {});
        QCOMPARE(shape(plan), QString("bloom | tonemap+vignette | fxaa"));
        QVERIFY(plan.toneMaps);
        QCOMPARE(plan.steps[0].kind, Kind::Single);
        QCOMPARE(plan.steps[1].kind, Kind::Fused);
        QCOMPARE(plan.steps[1].effects, (std::vector<int>{1, 2}));
        QVERIFY(plan.steps[1].encodes); // the tone curve calls displayEncode()
        QCOMPARE(plan.steps[1].paramSlots, 2 + int(findPostEffect("vignette")->params.size()));
        QCOMPARE(plan.steps[2].kind, Kind::Single);
        QCOMPARE(plan.steps[2].effects, (std::vector<int>{3}));
        QVERIFY(!plan.steps[2].encodes);
    }

    void disabledAndUnknownEffectsAreSkipped() {
        PostChain chain = chainOf({"tonemap", "vignette", "sharpen", "film_grain", "night_vision"});
        QCOMPARE(shape(planPostChain(chain, {})),
                 QString("tonemap+vignette | sharpen | film_grain+night_vision"));
        // Disabling the non-pointwise effect between them joins its neighbours into one pass.
        chain.effects[2].enabled = false;
        QCOMPARE(shape(planPostChain(chain, {})),
                 QString("tonemap+vignette+film_grain+night_vision"));
        chain.effects[1].enabled = false;
        const PostPlan plan = planPostChain(chain, {});
        QCOMPARE(shape(plan), QString("tonemap+film_grain+night_vision"));
        QCOMPARE(plan.steps[0].effects, (std::vector<int>{0, 3, 4}));
        chain.effects.insert(chain.effects.begin() + 1, EffectInstance{"no_such_effect"});
        QCOMPARE(shape(planPostChain(chain, {})), QString("tonemap+film_grain+night_vision"));
        for (EffectInstance& e : chain.effects)
            e.enabled = false;
        const PostPlan none = planPostChain(chain, {});
        QVERIFY(none.steps.empty());
        QVERIFY(!none.toneMaps);
    }

    void hdrOnlyChainDoesNotToneMap() {
        const PostPlan plan = planPostChain(chainOf({"bloom", "toon", "color_grading"}), {});
        QCOMPARE(shape(plan), QString("bloom | toon+color_grading"));
        QVERIFY(!plan.toneMaps);
        QVERIFY(!plan.steps[1].encodes);
    }

    void implicitToneMapGoesBeforeTheFirstLdrEffect() {
        const PostChain chain = chainOf({"bloom", "color_grading", "vignette", "fxaa"});
        const PostPlan plan = planPostChain(chain, {/*implicitToneMapper=*/2, false});
        QCOMPARE(shape(plan), QString("bloom | color_grading+tonemap+vignette | fxaa"));
        QCOMPARE(plan.steps[1].effects, (std::vector<int>{1, kImplicitToneMap, 2}));
        QVERIFY(plan.toneMaps);
        QCOMPARE(plan.implicitToneMap.type, std::string("tonemap"));
        QCOMPARE(effectFloat(plan.effect(chain, kImplicitToneMap), "operator"), 2.0f);
        // The effective list counts the implicit tone map: fxaa is the fifth effect run.
        QCOMPARE(plan.steps[2].listIndex, size_t(4));
        // An explicit (even later) tone map means none is added.
        PostChain explicitChain = chain;
        explicitChain.effects.push_back(makeEffect("tonemap"));
        QVERIFY(planPostChain(explicitChain, {}).implicitToneMap.type.empty());
    }

    void displayOperatorAndForcedDisplayDrawTheToneMapAlone() {
        PostChain chain = chainOf({"color_grading", "tonemap", "vignette"});
        QCOMPARE(shape(planPostChain(chain, {})), QString("color_grading+tonemap+vignette"));
        const PostPlan forced = planPostChain(chain, {0, /*forceDisplayTransform=*/true});
        QCOMPARE(shape(forced), QString("color_grading | tonemap (display) | vignette"));
        QCOMPARE(forced.steps[1].kind, Kind::DisplayToneMap);
        QVERIFY(!forced.steps[0].encodes && !forced.steps[2].encodes);
        chain.effects[1].params["operator"] = {6.0f}; // "display"
        QCOMPARE(planPostChain(chain, {}), forced);
    }

    void fusionStopsWhenParameterSlotsRunOut() {
        const int perEffect = int(findPostEffect("color_grading")->params.size());
        const int fit = kPostMaxSlots / perEffect;
        PostChain chain;
        for (int i = 0; i < fit + 1; ++i)
            chain.effects.push_back(makeEffect("color_grading"));
        const PostPlan plan = planPostChain(chain, {});
        QCOMPARE(plan.steps.size(), size_t(2));
        QCOMPARE(int(plan.steps[0].effects.size()), fit);
        QCOMPARE(plan.steps[0].paramSlots, fit * perEffect);
        QCOMPARE(plan.steps[1].effects, (std::vector<int>{fit}));
    }

    void cacheReplansOnlyWhenTheChainOrOptionsChange() {
        PostPlanCache cache;
        PostChain chain = defaultPostChain();
        cache.plan(chain, {});
        cache.plan(chain, {});
        QCOMPARE(cache.buildCount(), 1);
        chain.effects[2].enabled = false;
        QCOMPARE(shape(cache.plan(chain, {})), QString("bloom | tonemap | fxaa"));
        QCOMPARE(cache.buildCount(), 2);
        cache.plan(chain, {0, true});
        QCOMPARE(cache.buildCount(), 3);
        QCOMPARE(shape(cache.plan(chain, {0, true})), QString("bloom | tonemap (display) | fxaa"));
        QCOMPARE(cache.buildCount(), 3);
    }

    /// docs/post-effects.md, "Shader files by role": a file with a main() is a stage (.frag,
    /// .vert, .comp), one without is include-only (.glsl); post_* files are chain effects, one
    /// per catalogue type (post_<type>.glsl when pointwise, else post_<type>.frag), besides the
    /// shared post_common.glsl.
    void shaderFilesAreNamedByRole() {
        namespace fs = std::filesystem;
        const fs::path dir = fs::path(VELVET_SOURCE_DIR) / "resources" / "shaders";
        int files = 0;
        for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
            const std::string name = entry.path().filename().string();
            const std::string ext = entry.path().extension().string();
            std::ifstream in(entry.path());
            std::stringstream text;
            text << in.rdbuf();
            const bool hasMain = text.str().find("void main(") != std::string::npos;
            QVERIFY2(hasMain == (ext == ".frag" || ext == ".vert" || ext == ".comp"),
                     qPrintable(QString::fromStdString(name) +
                                (hasMain ? ": has a main(), so not .glsl" : ": include-only")));
            ++files;
            if (name.rfind("post_", 0) != 0 || name == "post_common.glsl")
                continue;
            const std::string type = entry.path().stem().string().substr(5);
            const EffectMeta* meta = findPostEffect(type);
            QVERIFY2(meta, qPrintable(QString::fromStdString(name) + ": no such effect"));
            QCOMPARE(QString::fromStdString(ext), meta->pointwise ? QString(".glsl") : ".frag");
        }
        QVERIFY(files > 20);
        for (const EffectMeta& m : postEffectCatalogue()) {
            const std::string file =
                "post_" + std::string(m.type) + (m.pointwise ? ".glsl" : ".frag");
            QVERIFY2(fs::exists(dir / file), file.c_str());
        }
    }
};

QTEST_GUILESS_MAIN(TestRenderPostPlan)
#include "test_render_post_plan.moc"

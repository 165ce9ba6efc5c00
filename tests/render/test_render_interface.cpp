// The shader contracts described once in C++ (render/render_interface.h) and generated into
// "render_interface.glsl" (blocks, debug-view ids, BRDF term ids, tone mappers): the generated
// text names what the C++ names, and no shader file declares them again by hand.
#include "render/render_interface.h"
#include "render_test_util.h"

#include <QtTest>
#include <filesystem>
#include <regex>

using namespace velvet;

class TestRenderInterface : public QObject {
    Q_OBJECT

private slots:
    // The blocks carry the C++ member names, every DebugView its number, and the light-view
    // tests agree with C++ for every view (checked by evaluating the generated ranges).
    void generatedTextMatchesTheCppDescription() {
        const std::string glsl = render::renderInterfaceGlsl();
        for (const char* member :
             {"mat4 viewMatrix;", "mat4 projMatrix;", "mat4 viewProjMatrix;", "ivec4 modes;",
              "vec4 envSh[9];", "vec4 lightDirection[MAX_LIGHTS];", "} frame;", "} ibl;"})
            QVERIFY2(glsl.find(member) != std::string::npos, member);
        QVERIFY(glsl.find("#define MAX_LIGHTS " + std::to_string(render::kMaxDirectionalLights) +
                          "\n") != std::string::npos);
        const std::regex define("#define (DEBUG_[A-Z_]+) ([0-9]+)\n");
        int count = 0;
        for (auto it = std::sregex_iterator(glsl.begin(), glsl.end(), define);
             it != std::sregex_iterator(); ++it, ++count)
            QCOMPARE(std::stoi((*it)[2]), count); // dense, in enum order
        QCOMPARE(count, int(render::DebugView::SpecularOcclusion) + 1);
        int lightViews = 0;
        for (int v = 0; v < count; ++v)
            lightViews += render::isLightView(render::DebugView(v));
        QCOMPARE(lightViews, 7); // Final, LightsPerPixel and the five lobe views
        // The term ids and tone mappers are the enums' numbers.
        for (const std::string d :
             {"#define DISTRIBUTION_BECKMANN " + std::to_string(int(Distribution::Beckmann)),
              "#define VISIBILITY_KELEMEN " + std::to_string(int(Visibility::Kelemen)),
              "#define FRESNEL_EXACT_DIELECTRIC " + std::to_string(int(Fresnel::ExactDielectric)),
              "#define DIFFUSE_BURLEY " + std::to_string(int(Diffuse::Burley)),
              "#define SHEEN_CHARLIE_NEUBELT " + std::to_string(int(SheenModel::CharlieNeubelt)),
              "#define TONEMAP_LINEAR " + std::to_string(int(render::ToneMapper::Linear))})
            QVERIFY2(glsl.find(d + "\n") != std::string::npos, d.c_str());
        // The material record and the post chain's block, members in C++ order.
        const size_t record = glsl.find("struct GpuMaterial {");
        QVERIFY(record != std::string::npos);
        QVERIFY(glsl.find("vec4 baseColorMetallic;", record) < glsl.find("ivec4 terms2;", record));
        const std::string post = render::postInterfaceGlsl();
        QVERIFY(post.find("uniform PostFrame {") != std::string::npos);
        for (const char* member : {"mat4 viewProj;", "mat4 prevViewProj;", "vec4 misc;", "} post;"})
            QVERIFY2(post.find(member) != std::string::npos, member);
    }

    // One copy: no shader file declares the frame, IBL or post block, the material record or a
    // debug-view id itself.
    void noShaderRedeclaresThem() {
        const std::filesystem::path dir =
            std::filesystem::path(VELVET_SOURCE_DIR) / "resources/shaders";
        int files = 0;
        for (const auto& e : std::filesystem::directory_iterator(dir)) {
            const std::string text = test::readText(e.path());
            const std::string name = e.path().filename().string();
            ++files;
            QVERIFY2(text.find("uniform FrameBlock") == std::string::npos, name.c_str());
            QVERIFY2(text.find("uniform IblBlock") == std::string::npos, name.c_str());
            QVERIFY2(text.find("uniform PostFrame") == std::string::npos, name.c_str());
            QVERIFY2(text.find("struct GpuMaterial") == std::string::npos, name.c_str());
            QVERIFY2(!std::regex_search(text, std::regex("#define DEBUG_[A-Z_]+ [0-9]")),
                     name.c_str());
            QVERIFY2(text.find("#define MAX_LIGHTS") == std::string::npos, name.c_str());
            QVERIFY2(!std::regex_search(
                         text, std::regex("#define (DISTRIBUTION|VISIBILITY|FRESNEL|DIFFUSE|"
                                          "SHEEN_CHARLIE)_[A-Z_]+ [0-9]")),
                     name.c_str());
            QVERIFY2(!std::regex_search(
                         text, std::regex("#define TONEMAP_(PBR_NEUTRAL|ACES_FITTED|REINHARD|"
                                          "LINEAR) [0-9]")),
                     name.c_str());
        }
        QVERIFY(files > 10);
    }
};

QTEST_GUILESS_MAIN(TestRenderInterface)
#include "test_render_interface.moc"

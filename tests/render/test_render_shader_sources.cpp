// The shader folder keeps one copy of each shared piece (issue 11, "Duplicates"): every GPU hash
// is defined only in common_hash.glsl, and the G-buffer is decoded for shading only in
// gbuffer_read.glsl (the full-screen lighting and the three many-light paths include it). Reads
// resources/shaders/ as text: no GPU needed. The render tests prove the images did not move.
#include <QtTest>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

/// Shader file name -> its text, for every file of resources/shaders/.
std::map<std::string, std::string> shaderSources() {
    std::map<std::string, std::string> out;
    for (const auto& entry :
         fs::directory_iterator(fs::path(VELVET_SOURCE_DIR) / "resources/shaders")) {
        if (!entry.is_regular_file())
            continue;
        std::ifstream in(entry.path(), std::ios::binary);
        std::ostringstream text;
        text << in.rdbuf();
        out[entry.path().filename().string()] = text.str();
    }
    return out;
}

/// The files whose text contains @p needle.
std::vector<std::string> filesContaining(const std::map<std::string, std::string>& sources,
                                         const std::string& needle) {
    std::vector<std::string> files;
    for (const auto& [name, text] : sources)
        if (text.find(needle) != std::string::npos)
            files.push_back(name);
    return files;
}

} // namespace

class TestRenderShaderSources : public QObject {
    Q_OBJECT
private slots:
    void eachHashIsDefinedOnce() {
        const auto sources = shaderSources();
        QVERIFY(sources.size() > 20); // the folder was found
        for (const char* definition : {"uvec2 pcg2d(uvec2", "float hash13(vec3"})
            QCOMPARE(filesContaining(sources, definition),
                     std::vector<std::string>{"common_hash.glsl"});
        // pcg2d's constants appear nowhere else either (a renamed copy).
        QCOMPARE(filesContaining(sources, "1013904223u"),
                 std::vector<std::string>{"common_hash.glsl"});
        // Its users include it.
        for (const char* user : {"common_environment.glsl", "post_common.glsl"})
            QVERIFY2(sources.at(user).find("#include \"common_hash.glsl\"") != std::string::npos,
                     user);
    }

    void theGBufferIsDecodedOnce() {
        const auto sources = shaderSources();
        // Reading the base colour and material targets and rebuilding a Surface from them.
        for (const char* decode : {"texelFetch(gMaterialTex", "texelFetch(gBaseColorOcclusionTex",
                                   "decodeBaseColor(rt0", "= decodeMaterialId(rt2"})
            QCOMPARE(filesContaining(sources, decode),
                     std::vector<std::string>{"gbuffer_read.glsl"});
        for (const char* user : {"lighting.frag", "light_common.glsl"})
            QVERIFY2(sources.at(user).find("#include \"gbuffer_read.glsl\"") != std::string::npos,
                     user);
    }
};

QTEST_APPLESS_MAIN(TestRenderShaderSources)
#include "test_render_shader_sources.moc"

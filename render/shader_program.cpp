#include "render/shader_program.h"

#include "core/resources.h"
#include "render/gbuffer_layout.h"
#include "render/render_interface.h"
#include "render/stage_interface.h"

#include <epoxy/gl.h>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

namespace velvet::render {
namespace {

/// "baseColor" -> "BASE_COLOR", "metallicRoughness" -> "METALLIC_ROUGHNESS".
std::string macroName(std::string_view id) {
    std::string m;
    for (char c : id) {
        if (std::isupper(static_cast<unsigned char>(c)) && !m.empty())
            m += '_';
        m += char(std::toupper(static_cast<unsigned char>(c)));
    }
    return m;
}

std::string bindingsGlsl() {
    std::ostringstream s;
    s << "// Generated from render/shader_program.h; do not edit.\n"
      << "#define BINDING_FRAME_UBO " << binding::kFrameUbo << "\n"
      << "#define BINDING_MATERIAL_SSBO " << binding::kMaterialSsbo << "\n"
      << "#define BINDING_ENVIRONMENT_TEX " << binding::kEnvironmentTex << "\n"
      << "#define BINDING_SHEEN_LUT_TEX " << binding::kSheenLutTex << "\n"
      << "#define BINDING_HDR_TEX " << binding::kHdrTex << "\n"
      << "#define BINDING_IBL_UBO " << binding::kIblUbo << "\n"
      << "#define BINDING_IBL_SPECULAR_TEX " << binding::kIblSpecularTex << "\n"
      << "#define BINDING_IBL_DFG_TEX " << binding::kIblDfgTex << "\n"
      << "#define BINDING_IBL_IRRADIANCE_TEX " << binding::kIblIrradianceTex << "\n"
      << "#define BINDING_DISPLAY_LUT_TEX_FIRST " << binding::kDisplayLutTexFirst << "\n"
      << "#define BINDING_MATERIAL_TEX_FIRST " << binding::kMaterialTexFirst << "\n"
      << "#define MAX_MATERIALS " << kMaxMaterials << "\n"
      << "#define BINDING_GBUFFER_LOBES0_TEX " << binding::kGBufferLobes0Tex << "\n"
      << "#define BINDING_GBUFFER_LOBES1_TEX " << binding::kGBufferLobes1Tex << "\n";
    // The material texture slots (core/texture_ref.h): their count, one TEX_<ID> per slot and
    // the uniform locations of common_material_textures.glsl, so a new slot cannot leave the
    // GLSL behind (uTexRegion takes 1 .. count, then uTexUvLinear, then uTexUvOffset).
    s << "#define TEX_SLOT_COUNT " << kTextureSlotCount << "\n"
      << "#define TEX_UV_LINEAR_LOCATION " << textureUvLinearLocation() << "\n"
      << "#define TEX_UV_OFFSET_LOCATION " << textureUvOffsetLocation() << "\n";
    for (int i = 0; i < kTextureSlotCount; ++i)
        s << "#define TEX_" << macroName(textureSlotMetas()[size_t(i)].id) << " " << i << "\n";
    return s.str();
}

bool readSource(const std::string& name, const GeneratedSources& generated, std::string& text,
                std::string* error) {
    for (const auto& [generatedName, generatedText] : generated)
        if (name == generatedName) {
            text = generatedText;
            return true;
        }
    if (name == "gbuffer_layout.glsl") {
        text = gbufferGlsl();
        return true;
    }
    if (name == "render_interface.glsl") {
        text = renderInterfaceGlsl();
        return true;
    }
    if (name == "stage_interface.glsl") {
        text = stageInterfaceGlsl();
        return true;
    }
    if (name == "post_interface.glsl") {
        text = postInterfaceGlsl();
        return true;
    }
    if (name == "render_bindings.glsl") {
        text = bindingsGlsl();
        return true;
    }
    const auto path = resources::path("shaders") / name;
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        if (error)
            *error = path.string() + ": cannot open shader source";
        return false;
    }
    std::ostringstream ss;
    ss << in.rdbuf();
    text = ss.str();
    return true;
}

bool expand(const std::string& name, std::string& out, std::vector<std::string>& files,
            std::set<std::string>& included, std::vector<std::string>& stack,
            const std::vector<std::string>* defines, const GeneratedSources& generated,
            std::string* error) {
    for (const auto& s : stack)
        if (s == name) {
            if (error)
                *error = name + ": include cycle";
            return false;
        }
    if (!included.insert(name).second)
        return true; // every include behaves as if guarded by #pragma once
    std::string text;
    if (!readSource(name, generated, text, error))
        return false;
    const int index = int(files.size());
    files.push_back(name);
    stack.push_back(name);

    static const std::regex includeRe(R"(^\s*#\s*include\s+"([^"]+)\"\s*$)");
    std::istringstream lines(text);
    std::string line;
    int lineNo = 0;
    bool needLine = defines == nullptr; // included files start with a #line
    if (needLine)
        out += "#line 1 " + std::to_string(index) + "\n";
    while (std::getline(lines, line)) {
        ++lineNo;
        if (!line.empty() && line.back() == '\r')
            line.pop_back();
        std::smatch m;
        if (defines && line.rfind("#version", 0) == 0) {
            out += line + "\n";
            for (const auto& d : *defines)
                out += "#define " + d + "\n";
            out += "#line " + std::to_string(lineNo + 1) + " " + std::to_string(index) + "\n";
            continue;
        }
        if (std::regex_match(line, m, includeRe)) {
            if (!expand(m[1].str(), out, files, included, stack, nullptr, generated, error)) {
                if (error && error->find(" (included from ") == std::string::npos)
                    *error += " (included from " + name + ":" + std::to_string(lineNo) + ")";
                return false;
            }
            out += "#line " + std::to_string(lineNo + 1) + " " + std::to_string(index) + "\n";
            continue;
        }
        out += line + "\n";
    }
    stack.pop_back();
    return true;
}

/// Preprocesses and compiles one stage without asking its status (the driver may still be
/// compiling on another thread, GL_KHR_parallel_shader_compile). @p files maps its #line indices.
bool startStage(GLenum stage, const std::string& file, const std::vector<std::string>& defines,
                const GeneratedSources& generated, GLuint& shader, std::vector<std::string>& files,
                std::string* error) {
    std::string source;
    if (!preprocessShader(file, defines, source, files, error, generated))
        return false;
    shader = glCreateShader(stage);
    const char* src = source.c_str();
    glShaderSource(shader, 1, &src, nullptr);
    glCompileShader(shader);
    return true;
}

/// The compile status of a started stage (waits for it); false + the mapped log on failure.
bool stageCompiled(GLuint shader, const std::string& file, const std::vector<std::string>& files,
                   std::string* error) {
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (ok)
        return true;
    GLint len = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &len);
    std::string log(size_t(std::max(len, 1)), '\0');
    glGetShaderInfoLog(shader, len, nullptr, log.data());
    if (error)
        *error = "shader compile error in " + file + ":\n" + mapShaderLog(log.c_str(), files);
    return false;
}

bool compileStage(GLenum stage, const std::string& file, const std::vector<std::string>& defines,
                  const GeneratedSources& generated, GLuint& shader, std::string* error) {
    std::vector<std::string> files;
    if (!startStage(stage, file, defines, generated, shader, files, error))
        return false;
    if (!stageCompiled(shader, file, files, error)) {
        glDeleteShader(shader);
        shader = 0;
        return false;
    }
    return true;
}

/// The link status of @p program (waits for it); false + the driver log on failure.
bool programLinked(GLuint program, const std::string& name, std::string* error) {
    GLint ok = GL_FALSE;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (ok)
        return true;
    GLint len = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &len);
    std::string log(size_t(std::max(len, 1)), '\0');
    glGetProgramInfoLog(program, len, nullptr, log.data());
    if (error)
        *error = "shader link error (" + name + "):\n" + log.c_str();
    return false;
}

} // namespace

bool preprocessShader(const std::string& file, const std::vector<std::string>& defines,
                      std::string& out, std::vector<std::string>& files, std::string* error,
                      const GeneratedSources& generated) {
    out.clear();
    files.clear();
    std::set<std::string> included;
    std::vector<std::string> stack;
    return expand(file, out, files, included, stack, &defines, generated, error);
}

std::string mapShaderLog(const std::string& log, const std::vector<std::string>& files) {
    static const std::regex mesaRe(R"((\d+):(\d+)\((\d+)\))");
    static const std::regex nvRe(R"(^(\d+)\((\d+)\))");
    std::istringstream in(log);
    std::string line, out;
    while (std::getline(in, line)) {
        std::smatch m;
        auto fileOf = [&](const std::string& idx) {
            const size_t i = std::stoul(idx);
            return i < files.size() ? files[i] : idx;
        };
        if (std::regex_search(line, m, mesaRe) && m.position(0) == 0)
            line = fileOf(m[1].str()) + ":" + m[2].str() + ":" + m[3].str() + m.suffix().str();
        else if (std::regex_search(line, m, nvRe))
            line = fileOf(m[1].str()) + ":" + m[2].str() + m.suffix().str();
        out += "  " + line + "\n";
    }
    return out;
}

ShaderProgram::~ShaderProgram() {
    release();
}

void ShaderProgram::release() {
    if (m_program)
        glDeleteProgram(m_program);
    m_program = 0;
}

bool ShaderProgram::build(const std::string& vertexFile, const std::string& fragmentFile,
                          const std::vector<std::string>& defines, std::string* error) {
    return build(vertexFile, fragmentFile, defines, {}, error);
}

bool ShaderProgram::build(const std::string& vertexFile, const std::string& fragmentFile,
                          const std::vector<std::string>& defines,
                          const GeneratedSources& generated, std::string* error) {
    ProgramBuild build;
    return build.start(vertexFile, fragmentFile, defines, generated, error) &&
           build.finish(*this, error);
}

bool enableParallelShaderCompile() {
    if (!epoxy_has_gl_extension("GL_KHR_parallel_shader_compile"))
        return false;
    // KHR_parallel_shader_compile: 0xFFFFFFFF asks for the implementation's maximum.
    glMaxShaderCompilerThreadsKHR(0xFFFFFFFFu);
    return true;
}

ProgramBuild::~ProgramBuild() {
    abandon();
}

void ProgramBuild::abandon() {
    // Deleting objects the driver is still compiling is allowed; it drops the work.
    for (GLuint* shader : {&m_vertex, &m_fragment})
        if (*shader) {
            glDeleteShader(*shader);
            *shader = 0;
        }
    if (m_program)
        glDeleteProgram(m_program);
    m_program = 0;
}

bool ProgramBuild::start(const std::string& vertexFile, const std::string& fragmentFile,
                         const std::vector<std::string>& defines, const GeneratedSources& generated,
                         std::string* error) {
    abandon();
    m_parallel = epoxy_has_gl_extension("GL_KHR_parallel_shader_compile");
    m_vertexFile = vertexFile;
    m_fragmentFile = fragmentFile;
    if (!startStage(GL_VERTEX_SHADER, vertexFile, defines, generated, m_vertex, m_vertexFiles,
                    error) ||
        !startStage(GL_FRAGMENT_SHADER, fragmentFile, defines, generated, m_fragment,
                    m_fragmentFiles, error)) {
        abandon();
        return false;
    }
    // Linking uncompiled stages is allowed: the link waits for them (or fails with them), and
    // finish() reports the compile log first.
    m_program = glCreateProgram();
    glAttachShader(m_program, m_vertex);
    glAttachShader(m_program, m_fragment);
    glLinkProgram(m_program);
    return true;
}

bool ProgramBuild::ready() const {
    if (!m_program || !m_parallel)
        return true;
    // KHR_parallel_shader_compile: COMPLETION_STATUS_KHR on a program covers its link, which
    // includes the attached stages' compiles; unlike LINK_STATUS it never blocks.
    GLint done = GL_FALSE;
    glGetProgramiv(m_program, GL_COMPLETION_STATUS_KHR, &done);
    return done == GL_TRUE;
}

bool ProgramBuild::finish(ShaderProgram& target, std::string* error) {
    if (!m_program) {
        if (error)
            *error = "ProgramBuild::finish without a build in flight";
        return false;
    }
    const bool ok = stageCompiled(m_vertex, m_vertexFile, m_vertexFiles, error) &&
                    stageCompiled(m_fragment, m_fragmentFile, m_fragmentFiles, error) &&
                    programLinked(m_program, m_vertexFile + " + " + m_fragmentFile, error);
    if (ok) {
        target.release();
        target.m_program = m_program;
        m_program = 0; // the target owns it now
    }
    abandon(); // the stage objects (and a failed program)
    return ok;
}

ComputeProgram::~ComputeProgram() {
    release();
}

void ComputeProgram::release() {
    if (m_program)
        glDeleteProgram(m_program);
    m_program = 0;
}

bool ComputeProgram::build(const std::string& file, const std::vector<std::string>& defines,
                           const GeneratedSources& generated, std::string* error) {
    GLuint cs = 0;
    if (!compileStage(GL_COMPUTE_SHADER, file, defines, generated, cs, error))
        return false;
    const GLuint program = glCreateProgram();
    glAttachShader(program, cs);
    glLinkProgram(program);
    glDeleteShader(cs);
    if (!programLinked(program, file, error)) {
        glDeleteProgram(program);
        return false;
    }
    release();
    m_program = program;
    return true;
}

} // namespace velvet::render

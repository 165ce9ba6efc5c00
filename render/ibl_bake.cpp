#include "render/ibl_bake.h"

#include "core/atomic_file.h"
#include "core/brdf.h"
#include "core/cache_dir.h"
#include "core/content_hash.h"
#include "core/ibl.h"
#include "core/ibl_cache.h"
#include "render/shader_program.h"
#include "render/sheen_lut.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <epoxy/gl.h>

namespace velvet::render {
namespace {

constexpr int kLutCacheVersion = 1;
constexpr int kGroup = 8;      ///< local size of the cube compute shaders (8 x 8)
constexpr int kDfgGroupX = 64; ///< ibl_dfg.comp runs one row per group (64 x 1)

/// Compiles one compute shader file into a program (0 + message on failure, naming file:line).
GLuint buildCompute(const std::string& file, std::string* error, std::string* sources = nullptr) {
    std::string source;
    std::vector<std::string> files;
    if (!preprocessShader(file, {}, source, files, error))
        return 0;
    if (sources) // the bake's signature hashes what was compiled (IblBaker::cacheSignature)
        *sources += source;
    const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
    const char* text = source.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        GLint len = 0;
        glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &len);
        std::string log(size_t(std::max(len, 1)), '\0');
        glGetShaderInfoLog(shader, len, nullptr, log.data());
        if (error)
            *error = "shader compile error in " + file + ":\n" + mapShaderLog(log.c_str(), files);
        glDeleteShader(shader);
        return 0;
    }
    const GLuint program = glCreateProgram();
    glAttachShader(program, shader);
    glLinkProgram(program);
    glDeleteShader(shader);
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint len = 0;
        glGetProgramiv(program, GL_INFO_LOG_LENGTH, &len);
        std::string log(size_t(std::max(len, 1)), '\0');
        glGetProgramInfoLog(program, len, nullptr, log.data());
        if (error)
            *error = "shader link error (" + file + "):\n" + log.c_str();
        glDeleteProgram(program);
        return 0;
    }
    return program;
}

int floorPow2(int x) {
    int p = 1;
    while (p * 2 <= x)
        p *= 2;
    return p;
}

GLuint makeCube(int size, int levels) {
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &tex);
    glTextureStorage2D(tex, levels, GL_RGBA16F, size, size);
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER,
                        levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    for (GLenum w : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glTextureParameteri(tex, w, GL_CLAMP_TO_EDGE);
    glTextureParameteri(tex, GL_TEXTURE_MAX_LEVEL, levels - 1);
    return tex;
}

std::string cacheHeader() {
    return "velvet-ibl-dfg " + std::to_string(kLutCacheVersion) + " " +
           std::to_string(ibl::kDfgLutSize) + " " + std::to_string(ibl::kDfgLutSamples) + "\n";
}

} // namespace

IblBaker::IblBaker() = default;

IblBaker::~IblBaker() {
    abandonWarmUp();
    release(m_ready);
    release(m_pending);
    for (GLuint p : {m_equirectProgram, m_downsampleProgram, m_prefilterProgram, m_dfgProgram})
        if (p)
            glDeleteProgram(p);
    for (GLuint t : {m_dfgLut, m_sheenLut})
        if (t)
            glDeleteTextures(1, &t);
}

void IblBaker::release(Bake& bake) {
    for (unsigned* t : {&bake.radiance, &bake.specular})
        if (*t) {
            glDeleteTextures(1, t);
            *t = 0;
        }
    bake = {};
}

std::filesystem::path IblBaker::dfgCacheFile() {
    const std::filesystem::path dir = velvetCacheDir();
    if (dir.empty())
        return {};
    return dir /
           ("ibl_dfg_v" + std::to_string(kLutCacheVersion) + "_" +
            std::to_string(ibl::kDfgLutSize) + "_" + std::to_string(ibl::kDfgLutSamples) + ".bin");
}

bool IblBaker::initialize(std::string* error) {
    std::string sources;
    if (!(m_equirectProgram = buildCompute("ibl_equirect_to_cube.comp", error, &sources)) ||
        !(m_downsampleProgram = buildCompute("ibl_downsample.comp", error, &sources)) ||
        !(m_prefilterProgram = buildCompute("ibl_prefilter.comp", error, &sources)) ||
        !(m_dfgProgram = buildCompute("ibl_dfg.comp", error)))
        return false;
    m_compileCount += 4;
    m_shaderHash = hex64(xxhash64(sources, 0));

    // The sheen, Burley diffuse and specular albedo tables (render/sheen_lut.h: the tables the
    // C++ twins look up).
    m_sheenLut = createSheenAlbedoLut();

    constexpr int D = ibl::kDfgLutSize;
    glCreateTextures(GL_TEXTURE_2D, 1, &m_dfgLut);
    glTextureStorage2D(m_dfgLut, 1, GL_RG32F, D, D);
    glTextureParameteri(m_dfgLut, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(m_dfgLut, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(m_dfgLut, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(m_dfgLut, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);

    // The DFG LUT from the cache when it holds exactly this version; else made on the GPU first.
    const std::string header = cacheHeader();
    const size_t payload = size_t(D) * D * 2 * sizeof(float);
    if (const auto file = dfgCacheFile(); !file.empty()) {
        std::string ignored;
        if (auto data = readWholeFile(file, header.size() + payload, &ignored);
            data && data->size() == header.size() + payload && data->rfind(header, 0) == 0) {
            glTextureSubImage2D(m_dfgLut, 0, 0, 0, D, D, GL_RG, GL_FLOAT,
                                data->data() + header.size());
            m_dfgReady = true;
        }
    }
    if (!m_dfgReady) {
        m_jobs.push_back({JobKind::Dfg, 0, 0, D, ibl::kDfgLutSamples, 0});
        m_unitsTotal += jobUnits(m_jobs.back());
    }
    return true;
}

bool IblBaker::reload(std::string* error, int* compiled) {
    struct {
        unsigned* program;
        const char* file;
    } programs[] = {{&m_equirectProgram, "ibl_equirect_to_cube.comp"},
                    {&m_downsampleProgram, "ibl_downsample.comp"},
                    {&m_prefilterProgram, "ibl_prefilter.comp"},
                    {&m_dfgProgram, "ibl_dfg.comp"}};
    std::string errors, sources;
    for (auto& p : programs) {
        std::string message;
        const GLuint program =
            buildCompute(p.file, &message, p.program == &m_dfgProgram ? nullptr : &sources);
        if (!program) { // the last good program stays
            errors += (errors.empty() ? "" : "\n") + message;
            continue;
        }
        glDeleteProgram(*p.program);
        *p.program = program;
        ++m_compileCount;
        if (compiled)
            ++*compiled;
    }
    // A cache entry baked by other shaders is another entry; programs that failed keep their
    // build, whose source is no longer on disk: no cache until a reload builds them all.
    m_shaderHash = errors.empty() ? hex64(xxhash64(sources, 0)) : std::string();
    // New programs: llvmpipe compiles their machine code again at the first dispatch.
    abandonWarmUp();
    m_warmedUp = false;
    if (!errors.empty() && error)
        *error = errors;
    return errors.empty();
}

void IblBaker::abandonWarmUp() {
    if (m_warm.started) {
        release(m_warm.bake);
        if (m_warm.source.texture)
            glDeleteTextures(1, &m_warm.source.texture);
    }
    m_warm = {};
}

bool IblBaker::warmUpStep() {
    // llvmpipe compiles a shader's machine code at its first dispatch, for the formats and
    // sampler states bound then (a mip-mapped source differs from a single level): a whole bake
    // of a tiny mip-mapped environment (and a DFG dispatch with nothing to write) pays that
    // once, instead of charging it to the first slice of each kind of job. It is itself sliced,
    // one frame at a time: each frame runs tiny warm-up slices until one of them took longer
    // than kWarmUpFrameMs (a machine-code compile), so a frame pays for about one program.
    constexpr double kWarmUpFrameMs = 4.0;
    const auto t0 = std::chrono::steady_clock::now();
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    if (!m_warm.jobsDone) {
        // The real bake's state, set aside while the warm-up's runs through the same code.
        const Bake savedPending = m_pending;
        const std::deque<Job> savedJobs = m_jobs;
        const GLuint savedSource = m_source;
        const int savedWidth = m_sourceWidth;
        const double savedTotal = m_unitsTotal, savedDone = m_unitsDone;
        const IblBakeOptions savedOptions = m_options;
        const IblBakeStats savedStats = m_stats;
        const Bake savedReady = m_ready;
        m_options.faceSize = 16;
        m_options.samples = 4;
        m_ready = {};
        if (!m_warm.started) {
            Image img(8, 4, 3);
            std::fill(img.pixels.begin(), img.pixels.end(), 1.0f);
            m_warm.source = uploadEquirect(img, "warm-up");
            m_warm.started = true;
            m_pending = {};
            m_jobs.clear();
            request(m_warm.source);
        } else {
            m_pending = m_warm.bake;
            m_jobs = m_warm.jobs;
            m_source = m_warm.sourceTexture;
            m_sourceWidth = m_warm.sourceWidth;
        }
        while (!m_jobs.empty()) {
            Job& job = m_jobs.front();
            const double ms = runSlice(job);
            if (job.row >= job.size)
                m_jobs.pop_front();
            if (ms > kWarmUpFrameMs)
                break;
        }
        m_warm.bake = m_pending;
        m_warm.jobs = m_jobs;
        m_warm.sourceTexture = m_source;
        m_warm.sourceWidth = m_sourceWidth;
        m_warm.jobsDone = m_jobs.empty();
        m_ready = savedReady;
        m_pending = savedPending;
        m_jobs = savedJobs;
        m_source = savedSource;
        m_sourceWidth = savedWidth;
        m_unitsTotal = savedTotal;
        m_unitsDone = savedDone;
        m_options = savedOptions;
        m_stats = savedStats;
    } else {
        // Last warm-up frame: the DFG program (its own frame: another compile).
        GLint previousProgram = 0;
        glGetIntegerv(GL_CURRENT_PROGRAM, &previousProgram);
        glUseProgram(m_dfgProgram);
        glProgramUniform1i(m_dfgProgram, 0, 0); // uSize 0: every invocation returns at once
        glBindImageTexture(0, m_dfgLut, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
        glDispatchCompute(1, 1, 1);
        glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        glUseProgram(GLuint(previousProgram));
        glFinish();
        abandonWarmUp();
        std::fill(std::begin(m_msPerUnit), std::end(m_msPerUnit), 0.0);
        m_warmedUp = true;
    }
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    m_warmUpMs += ms;
    ++m_warmUpFrames;
    m_worstWarmUpFrameMs = std::max(m_worstWarmUpFrameMs, ms);
    return m_warmedUp;
}

std::string IblBaker::cacheSignature() const {
    if (m_shaderHash.empty())
        return {};
    return "ibl v" + std::to_string(kIblCacheVersion) + " face " +
           std::to_string(m_options.faceSize) + " levels " +
           std::to_string(m_options.specularLevels) + " samples " +
           std::to_string(m_options.samples) + " shaders " + m_shaderHash;
}

void IblBaker::request(const GpuEnvironment& env) {
    if (env.key == m_pending.key && m_pending.specular)
        return; // already being baked
    if (env.key == m_ready.key && m_ready.specular) {
        if (m_pending.specular) { // back to the ready one: drop the pending bake
            release(m_pending);
            std::erase_if(m_jobs, [](const Job& j) { return j.kind != JobKind::Dfg; });
        }
        return;
    }
    release(m_pending);
    std::erase_if(m_jobs, [](const Job& j) { return j.kind != JobKind::Dfg; });

    if (env.cached) { // from the disk cache (render/environment_map.h): ready at once
        const IblCacheEntry& c = *env.cached;
        Bake b;
        b.key = env.key;
        b.faceSize = c.faceSize;
        b.levels = c.levels;
        b.specular = makeCube(b.faceSize, b.levels);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
        for (int level = 0; level < b.levels; ++level) {
            const int size = std::max(b.faceSize >> level, 1);
            glTextureSubImage3D(b.specular, level, 0, 0, 0, size, size, 6, GL_RGBA, GL_HALF_FLOAT,
                                c.specular[size_t(level)].data());
        }
        release(m_ready);
        m_ready = b;
        ++m_cacheAdoptions;
        m_unitsTotal = m_unitsDone = 0;
        for (const Job& j : m_jobs) // a DFG job may still be queued
            m_unitsTotal += jobUnits(j) * (1.0 - double(j.row) / j.size);
        return;
    }

    Bake& b = m_pending;
    b.key = env.key;
    b.faceSize = m_options.faceSize > 0
                     ? m_options.faceSize
                     : std::clamp(floorPow2(std::max(env.width / 4, 1)), 16, 256);
    const int maxLevels = 1 + int(std::log2(float(b.faceSize)));
    b.levels = std::clamp(m_options.specularLevels, 1, maxLevels);
    b.radiance = makeCube(b.faceSize, maxLevels);
    b.specular = makeCube(b.faceSize, b.levels);
    m_source = env.texture;
    m_sourceWidth = env.width;
    b.cacheFile = env.cacheFile;
    b.cacheKey = env.cacheKey;
    b.sh = env.sh;

    // Queue: radiance level 0 per face, its mips, the mirror level, then each prefiltered level
    // per face. Rows within a job are split by step() to fit the slice target.
    for (int f = 0; f < 6; ++f)
        m_jobs.push_back({JobKind::EquirectToCube, f, 0, b.faceSize, 1, 0});
    for (int level = 1; level < maxLevels; ++level)
        for (int f = 0; f < 6; ++f)
            m_jobs.push_back({JobKind::RadianceMips, f, level, b.faceSize >> level, 1, 0});
    m_jobs.push_back({JobKind::CopyLevel0, 0, 0, b.faceSize, 1, 0});
    for (int level = 1; level < b.levels; ++level)
        for (int f = 0; f < 6; ++f)
            m_jobs.push_back({JobKind::Prefilter, f, level, std::max(b.faceSize >> level, 1),
                              m_options.samples, 0});
    // Progress restarts with the new bake (a DFG job still queued counts too).
    m_unitsTotal = m_unitsDone = 0;
    for (const Job& j : m_jobs)
        m_unitsTotal += jobUnits(j) * (1.0 - double(j.row) / j.size);
}

float IblBaker::progress() const {
    if (m_jobs.empty())
        return 1.0f;
    return m_unitsTotal > 0 ? float(std::min(m_unitsDone / m_unitsTotal, 0.999)) : 0.0f;
}

double IblBaker::runSlice(Job& job) {
    // Rows for this slice: as many as the cost measured for this kind of job allows within the
    // target; a first slice of unknown cost does a single group of rows.
    const int group = job.kind == JobKind::Dfg ? 1 : kGroup;
    double& msPerUnit = m_msPerUnit[int(job.kind)];
    int rows = group;
    if (msPerUnit > 0.0) {
        const double perRow = msPerUnit * double(job.size) * job.samples;
        rows = int(m_options.sliceTargetMs / std::max(perRow, 1e-9)) / group * group;
    }
    // The hard cap on work per slice, whole row groups (but at least one).
    const double unitsPerRow = double(job.size) * job.samples;
    const int cappedRows =
        int(m_options.maxSliceUnits / std::max(unitsPerRow, 1.0)) / group * group;
    rows = std::min(rows, std::max(cappedRows, group));
    rows = std::clamp(rows, group, job.size - job.row);
    if (job.kind == JobKind::CopyLevel0)
        rows = job.size - job.row;

    const auto t0 = std::chrono::steady_clock::now();
    const GLuint groupsX = GLuint((job.size + kGroup - 1) / kGroup);
    const GLuint groupsY = GLuint((rows + group - 1) / group);
    switch (job.kind) {
    case JobKind::Dfg:
        glUseProgram(m_dfgProgram);
        glProgramUniform1i(m_dfgProgram, 0, job.size);
        glProgramUniform1i(m_dfgProgram, 1, job.row);
        glProgramUniform1i(m_dfgProgram, 2, job.samples);
        glProgramUniform1f(m_dfgProgram, 3, brdf::kMinRoughness);
        glBindImageTexture(0, m_dfgLut, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
        glDispatchCompute(GLuint((job.size + kDfgGroupX - 1) / kDfgGroupX), groupsY, 1);
        break;
    case JobKind::EquirectToCube: {
        const float lod =
            std::max(std::log2(float(m_sourceWidth) / (4.0f * float(m_pending.faceSize))), 0.0f);
        glUseProgram(m_equirectProgram);
        glProgramUniform1i(m_equirectProgram, 0, job.face);
        glProgramUniform1i(m_equirectProgram, 1, job.size);
        glProgramUniform1i(m_equirectProgram, 2, job.row);
        glProgramUniform1f(m_equirectProgram, 3, lod);
        glBindTextureUnit(0, m_source);
        glBindImageTexture(0, m_pending.radiance, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        glDispatchCompute(groupsX, groupsY, 1);
        break;
    }
    case JobKind::RadianceMips:
        glUseProgram(m_downsampleProgram);
        glProgramUniform1i(m_downsampleProgram, 0, job.face);
        glProgramUniform1i(m_downsampleProgram, 1, job.size);
        glProgramUniform1i(m_downsampleProgram, 2, job.row);
        glBindImageTexture(0, m_pending.radiance, job.level - 1, GL_TRUE, 0, GL_READ_ONLY,
                           GL_RGBA16F);
        glBindImageTexture(1, m_pending.radiance, job.level, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        glDispatchCompute(groupsX, groupsY, 1);
        break;
    case JobKind::CopyLevel0:
        glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        glCopyImageSubData(m_pending.radiance, GL_TEXTURE_CUBE_MAP, 0, 0, 0, 0, m_pending.specular,
                           GL_TEXTURE_CUBE_MAP, 0, 0, 0, 0, job.size, job.size, 6);
        break;
    case JobKind::Prefilter:
        glUseProgram(m_prefilterProgram);
        glProgramUniform1i(m_prefilterProgram, 0, job.face);
        glProgramUniform1i(m_prefilterProgram, 1, job.size);
        glProgramUniform1i(m_prefilterProgram, 2, job.row);
        glProgramUniform1f(m_prefilterProgram, 3,
                           ibl::roughnessOfLevel(job.level, m_pending.levels));
        glProgramUniform1i(m_prefilterProgram, 4, job.samples);
        glProgramUniform1i(m_prefilterProgram, 5, m_pending.faceSize);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        glBindTextureUnit(0, m_pending.radiance);
        glBindImageTexture(0, m_pending.specular, job.level, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        glDispatchCompute(groupsX, groupsY, 1);
        break;
    }
    glFinish();
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();

    const double units = double(rows) * job.size * job.samples;
    if (job.kind != JobKind::CopyLevel0) {
        // Cost model: the latest measurement, smoothed (the machine is shared; slices vary).
        const double latest = ms / std::max(units, 1.0);
        msPerUnit = msPerUnit > 0.0 ? 0.5 * (msPerUnit + latest) : latest;
    }
    job.row += rows;
    m_unitsDone += units;
    m_stats.slices++;
    m_stats.totalMs += ms;
    m_stats.worstSliceMs = std::max(m_stats.worstSliceMs, ms);
    if (job.kind != JobKind::CopyLevel0) // a copy, not shader work
        m_stats.worstSliceUnits = std::max(m_stats.worstSliceUnits, units);
    if (m_stats.sliceMs.size() < 4096)
        m_stats.sliceMs.push_back(ms);
    return ms;
}

void IblBaker::completeDfg() {
    m_dfgReady = true;
    const auto file = dfgCacheFile();
    if (file.empty())
        return;
    constexpr int D = ibl::kDfgLutSize;
    std::string data = cacheHeader();
    const size_t offset = data.size();
    data.resize(offset + size_t(D) * D * 2 * sizeof(float));
    glGetTextureImage(m_dfgLut, 0, GL_RG, GL_FLOAT, GLsizei(data.size() - offset),
                      data.data() + offset);
    // The cache is an optimisation: when it cannot be written the LUT is simply made again by
    // the next process.
    std::error_code ec;
    std::filesystem::create_directories(file.parent_path(), ec);
    std::string ignored;
    writeFileAtomically(file, data, &ignored);
}

bool IblBaker::step(double budgetMs) {
    if (m_jobs.empty())
        return true;
    glFinish(); // what the host queued is not the bake's time
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    if (!m_warmedUp && budgetMs < 1e8) {
        // Sliced baking only (finish(), headless, has no frame to keep short): a frame that
        // warms up does nothing else.
        warmUpStep();
        glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        glBindTextureUnit(0, 0);
        return false;
    }
    GLint previousProgram = 0;
    glGetIntegerv(GL_CURRENT_PROGRAM, &previousProgram);
    double spent = 0.0;
    while (!m_jobs.empty() && spent < budgetMs) {
        Job& job = m_jobs.front();
        spent += runSlice(job);
        if (job.row < job.size)
            continue;
        const JobKind kind = job.kind;
        m_jobs.pop_front();
        if (kind == JobKind::Dfg) {
            completeDfg();
        } else if (std::none_of(m_jobs.begin(), m_jobs.end(),
                                [](const Job& j) { return j.kind != JobKind::Dfg; })) {
            // The pending bake is complete: it replaces the ready one.
            glDeleteTextures(1, &m_pending.radiance);
            m_pending.radiance = 0;
            release(m_ready);
            m_ready = m_pending;
            m_pending = {};
            if (!m_ready.cacheFile.empty())
                writeDiskCache(m_ready);
            m_source = 0;
        }
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindTextureUnit(0, 0);
    glUseProgram(GLuint(previousProgram));
    if (m_jobs.empty())
        m_unitsTotal = m_unitsDone = 0;
    return m_jobs.empty();
}

void IblBaker::writeDiskCache(const Bake& bake) {
    // What the next process uploads instead of decoding and baking (core/ibl_cache.h): the
    // equirect as the GPU holds it (m_source, the environment being baked, still alive) and
    // every level of the prefiltered cube, read back as the half floats they are.
    IblCacheEntry e;
    glGetTextureLevelParameteriv(m_source, 0, GL_TEXTURE_WIDTH, &e.width);
    glGetTextureLevelParameteriv(m_source, 0, GL_TEXTURE_HEIGHT, &e.height);
    if (e.width < 1 || e.height < 1)
        return;
    e.sh = bake.sh;
    e.faceSize = bake.faceSize;
    e.levels = bake.levels;
    glPixelStorei(GL_PACK_ALIGNMENT, 2);
    glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    e.equirect.resize(size_t(e.width) * size_t(e.height) * 3u);
    glGetTextureImage(m_source, 0, GL_RGB, GL_HALF_FLOAT, GLsizei(e.equirect.size() * 2),
                      e.equirect.data());
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    for (int level = 0; level < bake.levels; ++level) {
        const size_t size = size_t(std::max(bake.faceSize >> level, 1));
        std::vector<std::uint16_t> faces(size * size * 6u * 4u);
        glGetTextureImage(bake.specular, level, GL_RGBA, GL_HALF_FLOAT, GLsizei(faces.size() * 2),
                          faces.data());
        e.specular.push_back(std::move(faces));
    }
    // The cache is an optimisation: an entry that cannot be written is baked again next time.
    std::string ignored;
    if (writeIblCache(bake.cacheFile, bake.cacheKey, e, &ignored))
        ++m_cacheWrites;
}

void IblBaker::finish() {
    while (!step(1e9)) {
    }
}

Image IblBaker::readSpecularFace(int level, int face) const {
    if (!m_ready.specular || level < 0 || level >= m_ready.levels || face < 0 || face > 5)
        return {};
    const int size = std::max(m_ready.faceSize >> level, 1);
    Image img(size, size, 4);
    glGetTextureSubImage(m_ready.specular, level, 0, 0, face, size, size, 1, GL_RGBA, GL_FLOAT,
                         GLsizei(img.pixels.size() * sizeof(float)), img.pixels.data());
    return img;
}

std::vector<glm::vec2> IblBaker::readDfgLut() const {
    constexpr int D = ibl::kDfgLutSize;
    std::vector<glm::vec2> lut(size_t(D) * D);
    glGetTextureImage(m_dfgLut, 0, GL_RG, GL_FLOAT, GLsizei(lut.size() * sizeof(glm::vec2)),
                      lut.data());
    return lut;
}

} // namespace velvet::render

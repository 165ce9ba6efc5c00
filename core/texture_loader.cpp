#include "core/texture_loader.h"

#include "core/texture_cache.h"

#include <utility>

namespace velvet {

TextureLoader::TextureLoader(const ColorManagement& colorManagement, MipLoadOptions options,
                             bool async)
    : m_colorManagement(colorManagement), m_options(std::move(options)), m_async(async) {
    if (m_async)
        m_worker = std::thread([this] { workerLoop(); });
}

TextureLoader::~TextureLoader() {
    {
        std::lock_guard lock(m_mutex);
        m_stop = true;
        m_queue.clear();
    }
    m_wake.notify_all();
    if (m_worker.joinable())
        m_worker.join();
}

std::shared_ptr<TextureJob> TextureLoader::request(const std::filesystem::path& file,
                                                   const std::string& colorSpace,
                                                   TextureUsage usage, bool leaveFinestInCache) {
    auto job = std::make_shared<TextureJob>(file, colorSpace, usage,
                                            leaveFinestInCache && m_options.leaveFinestInCache);
    if (!m_async) {
        run(*job, /*deferCacheWrite=*/false);
        return job;
    }
    {
        std::lock_guard lock(m_mutex);
        m_queue.push_back(job);
    }
    m_wake.notify_one();
    return job;
}

void TextureLoader::wait(const TextureJob& job) {
    std::unique_lock lock(m_mutex);
    m_done.wait(lock, [&] { return job.ready(); });
}

std::vector<Problem> TextureLoader::takeLateProblems() {
    std::lock_guard lock(m_mutex);
    return std::exchange(m_late, {});
}

void TextureLoader::run(TextureJob& job, bool deferCacheWrite) {
    MipLoadOptions options = m_options;
    // Level 0 left in the cache needs the entry written before the levels are published.
    options.leaveFinestInCache = job.m_leaveFinestInCache;
    options.writeCache = !deferCacheWrite || options.leaveFinestInCache;
    MipLoadResult result =
        loadMipTexture(job.m_file, job.m_colorSpace, job.m_usage, m_colorManagement, options);
    if (result.decoded)
        ++m_decodes;
    if (result.fromCache)
        ++m_cacheHits;
    // What the cache write needs outlives the published result only as long as the write.
    MipLoadResult forCache;
    if (!options.writeCache && result.texture && !result.fromCache && !result.cacheKey.empty()) {
        forCache.texture = result.texture;
        forCache.cacheEntry = result.cacheEntry;
        forCache.cacheKey = result.cacheKey;
    }
    {
        std::lock_guard lock(m_mutex);
        job.m_result = std::move(result);
        job.m_ready.store(true, std::memory_order_release);
    }
    m_done.notify_all();
    if (forCache.texture) {
        storeMipTexture(forCache);
        if (!forCache.problems.empty()) {
            std::lock_guard lock(m_mutex);
            for (Problem& p : forCache.problems) {
                p.file = job.m_file.string();
                m_late.push_back(std::move(p));
            }
        }
    }
}

void TextureLoader::workerLoop() {
    for (;;) {
        std::shared_ptr<TextureJob> job;
        {
            std::unique_lock lock(m_mutex);
            m_wake.wait(lock, [&] { return m_stop || !m_queue.empty(); });
            if (m_stop)
                return;
            job = m_queue.front().lock();
            m_queue.pop_front();
        }
        if (job) // null: every holder let go (the slot changed again meanwhile)
            run(*job, /*deferCacheWrite=*/true);
    }
}

} // namespace velvet

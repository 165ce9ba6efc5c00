#pragma once
/// @file texture_loader.h
/// Loads GPU textures (core/mip_texture.h) off the drawing thread: a request returns at once
/// with a job the caller polls (TextureJob::ready) at each frame, and a worker thread reads the
/// on-disk cache or decodes and filters the file meanwhile. A fresh build is written to the
/// cache after the job is published, so the writing never delays the picture, except when level
/// 0 is to stay in the entry (MipLoadOptions::leaveFinestInCache): then the entry comes first.
/// Synchronous loaders (headless rendering, tests) run each request on the caller's thread instead.
/// No GL here: render/texture_set.h uploads what the jobs hand over.

#include "core/mip_texture.h"

#include <atomic>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <thread>

namespace velvet {

/// One request: immutable inputs, and the result once ready() says so.
class TextureJob {
public:
    TextureJob(std::filesystem::path file, std::string colorSpace, TextureUsage usage,
               bool leaveFinestInCache)
        : m_file(std::move(file)), m_colorSpace(std::move(colorSpace)), m_usage(usage),
          m_leaveFinestInCache(leaveFinestInCache) {}
    const std::filesystem::path& file() const { return m_file; }
    const std::string& colorSpace() const { return m_colorSpace; }
    TextureUsage usage() const { return m_usage; }
    /// True once result() may be read (from any thread).
    bool ready() const { return m_ready.load(std::memory_order_acquire); }
    /// The loaded levels and problems; only when ready().
    const MipLoadResult& result() const { return m_result; }

private:
    friend class TextureLoader;
    std::filesystem::path m_file;
    std::string m_colorSpace;
    TextureUsage m_usage;
    bool m_leaveFinestInCache;
    std::atomic<bool> m_ready{false};
    MipLoadResult m_result;
};

class TextureLoader {
public:
    /// @p async false: request() loads at once on the caller's thread. The ColorManagement must
    /// outlive the loader.
    TextureLoader(const ColorManagement& colorManagement, MipLoadOptions options, bool async);
    /// Waits for the job in progress (if any); queued jobs are dropped.
    ~TextureLoader();
    TextureLoader(const TextureLoader&) = delete;
    TextureLoader& operator=(const TextureLoader&) = delete;

    /// Queues @p file (in the resolved @p colorSpace). A job whose every holder has let go
    /// before the worker reaches it is skipped. @p leaveFinestInCache false overrides the
    /// options' MipLoadOptions::leaveFinestInCache for this job (a retry after a band of the
    /// entry could not be read).
    std::shared_ptr<TextureJob> request(const std::filesystem::path& file,
                                        const std::string& colorSpace, TextureUsage usage,
                                        bool leaveFinestInCache = true);
    /// Blocks until @p job is ready (headless rendering waits for every texture).
    void wait(const TextureJob& job);
    bool async() const { return m_async; }

    /// Image files decoded (cache misses) and cache hits since construction.
    std::uint64_t decodeCount() const { return m_decodes.load(); }
    std::uint64_t cacheHits() const { return m_cacheHits.load(); }
    /// Problems found after a job was published (a cache entry that could not be written).
    std::vector<Problem> takeLateProblems();

private:
    void run(TextureJob& job, bool deferCacheWrite);
    void workerLoop();

    const ColorManagement& m_colorManagement;
    MipLoadOptions m_options;
    bool m_async;
    std::mutex m_mutex;
    std::condition_variable m_wake, m_done;
    std::deque<std::weak_ptr<TextureJob>> m_queue;
    std::vector<Problem> m_late;
    bool m_stop = false;
    std::atomic<std::uint64_t> m_decodes{0}, m_cacheHits{0};
    std::thread m_worker;
};

} // namespace velvet

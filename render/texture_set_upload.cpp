// TextureSet's GPU side: each texture's storage (made on the storage thread where there is one)
// and the upload of its levels, coarsest first, within each frame's byte budget.
#include "core/mip_cache.h"
#include "render/texture_set.h"
#include "render/texture_set_entry.h"
#include "render/texture_storage_thread.h"

#include <algorithm>
#include <cstdio>
#include <epoxy/gl.h>

namespace velvet::render {
namespace {

GLenum internalFormat(MipFormat f) {
    switch (f) {
    case MipFormat::Rgba8:
        return GL_RGBA8;
    case MipFormat::Srgb8Alpha8:
        return GL_SRGB8_ALPHA8; // the GPU decodes sRGB before filtering (GL 4.5 section 8.24)
    case MipFormat::Rgba16F:
        return GL_RGBA16F;
    }
    return GL_RGBA8;
}

} // namespace

void TextureSet::releaseTexture(Entry& e) {
    if (e.storage)
        TextureStorageThread::abandon(*e.storage);
    e.storage.reset();
    if (e.texture)
        glDeleteTextures(1, &e.texture);
    e.texture = 0;
}

void TextureSet::setStorageContext(std::unique_ptr<WorkerGlContext> context) {
    dropEntries(); // their storage in flight belongs to the old thread
    m_storageThread =
        context ? std::make_unique<TextureStorageThread>(std::move(context)) : nullptr;
}

bool TextureSet::takeFinished(Entry& e, Problems* problems) {
    if (!e.job || !e.job->ready())
        return false;
    const MipLoadResult& r = e.job->result();
    e.problems = r.problems;
    if (problems)
        reportProblems(e, *problems);
    ++m_generation;
    if (!r.texture || r.texture->levels.empty()) {
        e.finest = -1; // the slot falls back to the parameter value
        e.data.reset();
        e.uploadLevel = -1;
        e.generation = m_generation;
        e.job.reset();
        return true;
    }
    const MipTexture& t = *r.texture;
    if ((!e.texture && !e.storage) || e.width != t.width() || e.height != t.height() ||
        e.format != t.format) {
        releaseTexture(e);
        e.levels = int(t.levels.size());
        const TextureStorageRequest request{t.width(), t.height(), e.levels,
                                            unsigned(internalFormat(t.format))};
        // A large texture's storage is made on the storage thread where there is one (the
        // editor): llvmpipe zero-fills it as it allocates (texture_storage_thread.h).
        if (m_async && m_storageThread && t.byteSize() >= kOffThreadStorageBytes)
            e.storage = m_storageThread->allocate(request);
        else
            e.texture = createSlotTexture(request);
        e.width = t.width();
        e.height = t.height();
        e.format = t.format;
        e.finest = -1;
        ++m_allocations;
    }
    e.data = r.texture;
    e.uploadLevel = int(t.levels.size()) - 1;
    e.uploadRow = 0;
    e.bandRows = 0;
    e.bytesTotal = t.byteSize();
    e.bytesDone = 0;
    e.mean = t.mean;
    e.meanLevel = t.linearLevel(256);
    e.generation = m_generation;
    e.job.reset(); // the result's levels live on in e.data until uploaded
    return true;
}

bool TextureSet::readBand(Entry& e, const MipLevel& l, std::uint64_t rowBytes, std::uint64_t fit) {
    if (e.bandRows > 0 && e.uploadRow >= e.bandRow && e.uploadRow < e.bandRow + e.bandRows)
        return true; // the rows are in the band read before
    // Level 0 left in the cache entry (core/mip_texture.h) comes in bands of whole tiles, as many
    // as the budget's rows (at most 8 MiB, even when the budget is unbounded: finish()), and
    // is uploaded from the band over as many frames as the budget takes.
    const std::uint64_t tile = kMipCacheTileSide;
    const std::uint64_t cap = std::max<std::uint64_t>((std::uint64_t(8) << 20) / rowBytes, tile);
    const int rows =
        int(std::min<std::uint64_t>(std::clamp(fit / tile * tile, tile, cap / tile * tile),
                                    std::uint64_t(l.height - e.uploadRow)));
    e.band.resize(size_t(rowBytes) * size_t(rows));
    std::string why;
    if (!readMipCacheRows(e.data->finestInCache, *e.data, 0, e.uploadRow, rows, e.band.data(),
                          &why)) {
        // The entry went (a cache cleaned meanwhile) or broke: load the file again, this time
        // with level 0 in memory; the coarse levels keep drawing meanwhile.
        Problem p{Problem::Severity::Warning, e.file.string(), std::string(),
                  "texture cache entry " + e.data->finestInCache.string() + " could not be read (" +
                      why + "); loading the file again"};
        e.problems.push_back(p);
        m_problems.items.push_back(std::move(p));
        e.data.reset();
        e.uploadLevel = -1;
        e.bandRows = 0;
        std::vector<std::uint8_t>().swap(e.band);
        startLoad(e, /*leaveFinestInCache=*/false);
        return false;
    }
    e.bandRow = e.uploadRow;
    e.bandRows = rows;
    m_stats.streamedBytes += rowBytes * std::uint64_t(rows);
    return true;
}

std::uint64_t TextureSet::upload(Entry& e, std::uint64_t budget, bool& becameVisible) {
    if (e.storage && !takeStorage(e, /*wait=*/!m_async))
        return 0; // the frame draws on meanwhile: the parameter value, or nothing new
    std::uint64_t spent = 0;
    const GLenum type = e.format == MipFormat::Rgba16F ? GL_HALF_FLOAT : GL_UNSIGNED_BYTE;
    const std::uint64_t bpp = std::uint64_t(mipBytesPerPixel(e.format));
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    while (e.data && e.uploadLevel >= 0 && spent < budget) {
        const MipLevel& l = e.data->levels[size_t(e.uploadLevel)];
        const std::uint64_t rowBytes = std::uint64_t(l.width) * bpp;
        // Whole rows within the budget; one row past it only when nothing fitted yet (a row
        // wider than the budget still makes progress).
        std::uint64_t fit = (budget - spent) / rowBytes;
        if (fit == 0 && spent > 0)
            break;
        int rows = int(std::clamp<std::uint64_t>(fit, 1, std::uint64_t(l.height - e.uploadRow)));
        const std::uint8_t* pixels = l.bytes.data() + std::uint64_t(e.uploadRow) * rowBytes;
        if (l.bytes.empty() && !e.data->finestInCache.empty()) {
            if (!readBand(e, l, rowBytes, fit))
                break;
            rows = std::min(rows, e.bandRow + e.bandRows - e.uploadRow);
            pixels = e.band.data() + std::uint64_t(e.uploadRow - e.bandRow) * rowBytes;
        }
        // Row 0 (the image's top) goes to t = 0, matching glTF's UV space (v = 0 at the top).
        glTextureSubImage2D(e.texture, e.uploadLevel, 0, e.uploadRow, l.width, rows, GL_RGBA, type,
                            pixels);
        spent += rowBytes * std::uint64_t(rows);
        e.bytesDone += rowBytes * std::uint64_t(rows);
        e.uploadRow += rows;
        if (e.uploadRow < l.height)
            continue;
        // A level is complete: sampling may reach down to it (levels finest..max are all there).
        if (e.finest < 0 || e.uploadLevel < e.finest) {
            becameVisible = becameVisible || e.finest < 0;
            e.finest = e.uploadLevel;
            glTextureParameteri(e.texture, GL_TEXTURE_BASE_LEVEL, e.finest);
        }
        // Its CPU copy goes now, unless someone else still reads the levels (the loader writing
        // the cache entry): the peak stays near one copy of the chain, CPU and GPU together.
        if (e.data.use_count() == 1)
            std::vector<std::uint8_t>().swap(e.data->levels[size_t(e.uploadLevel)].bytes);
        --e.uploadLevel;
        e.uploadRow = 0;
    }
    if (e.uploadLevel < 0) {
        e.data.reset(); // every level is on the GPU: the CPU copy goes
        e.bandRows = 0;
        std::vector<std::uint8_t>().swap(e.band);
    }
    return spent;
}

bool TextureSet::takeStorage(Entry& e, bool wait) {
    std::string error;
    unsigned texture = 0;
    const auto state = wait ? TextureStorageThread::wait(*e.storage, texture, &error)
                            : TextureStorageThread::take(*e.storage, texture, &error);
    if (state == TextureStorageThread::State::Waiting)
        return false;
    if (state == TextureStorageThread::State::Failed) {
        // The worker's context could not be made: this thread allocates, as without one.
        std::fprintf(stderr, "velvet: texture storage made on the drawing thread: %s\n",
                     error.c_str());
        texture = createSlotTexture(e.storage->request());
        m_storageThread.reset(); // every later request would fail the same way
    } else
        ++m_stats.storageOffThread;
    e.texture = texture;
    e.storage.reset();
    return true;
}

} // namespace velvet::render

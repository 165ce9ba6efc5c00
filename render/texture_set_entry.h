#pragma once
/// @file texture_set_entry.h
/// TextureSet's record of one GL texture, shared by texture_set.cpp (slots, loads, binding) and
/// texture_set_upload.cpp (storage and upload). Private to render/.

#include "core/diagnostics.h"
#include "core/image.h"
#include "core/mip_texture.h"
#include "core/texture_cache.h"
#include "core/texture_loader.h"
#include "render/texture_set.h"
#include "render/texture_storage_thread.h"

#include <cstdint>
#include <filesystem>
#include <glm/vec4.hpp>
#include <memory>
#include <string>
#include <vector>

namespace velvet::render {

/// One GL texture: a (file, colour space, usage), shared by every slot that names it.
struct TextureSet::Entry {
    std::filesystem::path file;
    std::string colorSpace;
    TextureUsage usage = TextureUsage::Color;
    TextureFileStamp stamp;
    std::shared_ptr<TextureJob> job;  ///< the load in flight
    std::shared_ptr<MipTexture> data; ///< levels still to upload (each freed once uploaded)
    std::vector<std::uint8_t> band;   ///< rows of level 0 read from the cache entry (streamed)
    int bandRow = 0, bandRows = 0;    ///< which rows band holds
    int uploadLevel = -1;             ///< level being uploaded (coarsest first), -1 none
    int uploadRow = 0;                ///< rows of it done
    unsigned texture = 0; ///< GL name; 0 while none (or its storage is still being made)
    std::shared_ptr<PendingTextureStorage> storage; ///< texture's storage being made off-thread
    int width = 0, height = 0, levels = 0;
    MipFormat format = MipFormat::Rgba8;
    int finest = -1; ///< finest level complete on the GPU; -1 none
    glm::vec4 mean{1.0f};
    Image meanLevel;               ///< linear level <= 256 px: atlas-region means
    std::uint64_t generation = 0;  ///< new levels taken (slots recompute region, mean)
    std::vector<Problem> problems; ///< of the last load
    std::uint64_t bytesTotal = 0, bytesDone = 0;
};
} // namespace velvet::render

#pragma once
/// @file texture_progress.h
/// How far the material's textures are on their way to the GPU (render/texture_set.h), for
/// hosts: the editor's status bar, tests and `velvet bench`.

#include <cstdint>

namespace velvet::render {

/// Where the slots' textures stand (the editor's status bar).
struct TextureLoadProgress {
    int loading = 0;       ///< textures not yet complete on the GPU (loading or uploading)
    int total = 0;         ///< textures in use
    double fraction = 1.0; ///< of the bytes to upload, done (1 when nothing is loading)
};

/// What the uploads cost the frames (tests, bench): per poll() that uploaded anything.
struct TextureUploadStats {
    int frames = 0;                    ///< polls that uploaded at least one row
    std::uint64_t bytes = 0;           ///< uploaded in all
    std::uint64_t worstFrameBytes = 0; ///< the most one poll uploaded
    double worstFrameMs = 0;           ///< the longest one poll spent uploading (wall clock)
    int proxyFrames = 0;               ///< polls after which a texture showed only coarse levels
    /// Of `bytes`, those read from the on-disk cache entry band by band as they were uploaded
    /// (a large level 0 in asynchronous mode: core/mip_texture.h, leaveFinestInCache).
    std::uint64_t streamedBytes = 0;
    /// Textures whose storage was made on the storage thread (TextureSet::setStorageContext).
    int storageOffThread = 0;
};

} // namespace velvet::render

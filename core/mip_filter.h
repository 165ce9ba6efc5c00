#pragma once
/// @file mip_filter.h
/// One step of a mip chain: a level halved (each side rounded down, at least 1, as OpenGL 4.5
/// section 8.14.3 sizes levels) with a separable Blackman-Harris filter, streamed a row at a
/// time so that an 8-bit 4096² map never needs a float copy of itself (issue 16: peak memory).
/// The filter is OpenImageIO's "blackman-harris" as ImageBufAlgo::resize applies it when
/// shrinking (width 3 destination pixels, i.e. 6 source pixels at a 2x reduction, normalised
/// weights, edges clamped), written separably: O(taps) instead of O(taps²) per pixel.

#include <functional>

namespace velvet {

/// Fills @p rgba (4 floats a pixel, the source level's width) with source row @p y (0 at the
/// top), in the space the filter should average in (scene-linear for colour).
using MipRowLoader = std::function<void(int y, float* rgba)>;
/// Receives destination row @p y (4 floats a pixel, the destination width).
using MipRowStorer = std::function<void(int y, const float* rgba)>;

/// Halves a @p width x @p height level read through @p load into @p store. Every output value
/// is clamped to [@p lo[c], @p hi[c]], the source level's range per channel, so the filter's
/// negative lobes never ring data (roughness, masks) outside the values the level holds, nor a
/// colour below 0. Each row is stored once; each source row is loaded once (a few twice when
/// @p threads is 2: then @p load and @p store are called from two threads at once, for distinct
/// rows, and must allow that).
void halveLevel(int width, int height, const MipRowLoader& load, const MipRowStorer& store,
                const float lo[4], const float hi[4], int threads = 1);

} // namespace velvet

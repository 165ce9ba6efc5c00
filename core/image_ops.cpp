#include "core/image_ops.h"

#include "core/image.h"
#include "core/image_codec.h"
#include "core/mip_filter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace velvet {
namespace {

const char* filterName(ResizeFilter filter) {
    switch (filter) {
    case ResizeFilter::Box:
        return "box";
    case ResizeFilter::Triangle:
        return "triangle";
    case ResizeFilter::Mitchell:
        return "mitchell";
    case ResizeFilter::BlackmanHarris:
        return "blackman-harris";
    case ResizeFilter::Lanczos3:
        return "lanczos3";
    }
    return "blackman-harris";
}

bool setError(std::string* error, const std::string& what) {
    if (error)
        *error = what;
    return false;
}

bool consistent(const Image& image) {
    return !image.empty() && image.channels >= 1 && image.channels <= 4 &&
           image.pixels.size() == size_t(image.width) * image.height * image.channels;
}

} // namespace

Image resize(const Image& image, int width, int height, std::string* error, ResizeFilter filter) {
    if (!consistent(image))
        return setError(error, "resize: empty or inconsistent source image"), Image();
    if (width < 1 || height < 1)
        return setError(error, "resize: bad target size " + std::to_string(width) + "x" +
                                   std::to_string(height)),
               Image();
    if (width == image.width && height == image.height)
        return image;

    const int channels = image.channels;
    std::string why;
    const codec::ImageCodec* imageCodec = codec::imageCodec(&why); // ImageBufAlgo::resize
    if (!imageCodec)
        return setError(error, "resize: " + why), Image();
    Image out(width, height, channels);
    if (!imageCodec->resize(image, out, filterName(filter), error))
        return Image();

    // Clamp to the source's range per channel: no ringing outside the data's own values.
    float lo[4], hi[4];
    std::fill_n(lo, 4, std::numeric_limits<float>::max());
    std::fill_n(hi, 4, std::numeric_limits<float>::lowest());
    for (size_t i = 0; i < image.pixels.size(); ++i) {
        const int c = int(i % channels);
        lo[c] = std::min(lo[c], image.pixels[i]);
        hi[c] = std::max(hi[c], image.pixels[i]);
    }
    for (size_t i = 0; i < out.pixels.size(); ++i) {
        const int c = int(i % channels);
        out.pixels[i] = std::clamp(out.pixels[i], lo[c], hi[c]);
    }
    return out;
}

void ImageMean::add(const Image& image) {
    if (m_count == 0 || image.width != m_sum.width || image.height != m_sum.height ||
        image.channels != m_sum.channels || image.pixels.size() != m_sum.pixels.size()) {
        m_sum = image;
        m_count = 1;
        return;
    }
    for (size_t i = 0; i < image.pixels.size(); ++i)
        m_sum.pixels[i] += image.pixels[i];
    ++m_count;
}

void ImageMean::clear() {
    m_sum = Image();
    m_count = 0;
}

Image ImageMean::mean() const {
    ImageMean copy = *this;
    return copy.takeMean();
}

Image ImageMean::takeMean() {
    Image out = std::move(m_sum);
    if (m_count > 1) {
        const float scale = 1.0f / float(m_count);
        for (float& v : out.pixels)
            v *= scale;
    }
    clear();
    return out;
}

Image boxDownsample(Image image, int factor) {
    if (factor < 1 || !consistent(image) || image.width % factor || image.height % factor)
        return {};
    if (factor == 1)
        return image; // moved out: the parameter is ours
    Image out(image.width / factor, image.height / factor, image.channels);
    const float weight = 1.0f / float(factor * factor);
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x) {
            float* o = out.at(x, y);
            for (int sy = 0; sy < factor; ++sy)
                for (int sx = 0; sx < factor; ++sx) {
                    const float* p = image.at(x * factor + sx, y * factor + sy);
                    for (int c = 0; c < image.channels; ++c)
                        o[c] += p[c];
                }
            for (int c = 0; c < image.channels; ++c)
                o[c] *= weight;
        }
    return out;
}

int mipLevelCount(int width, int height) {
    int levels = 1;
    for (int side = std::max(width, height); side > 1; side /= 2)
        ++levels;
    return levels;
}

std::vector<Image> mipChain(const Image& image, std::string* error, ResizeFilter filter) {
    std::vector<Image> chain;
    if (!consistent(image))
        return setError(error, "mip chain: empty or inconsistent source image"), chain;
    const int levels = mipLevelCount(image.width, image.height);
    chain.reserve(size_t(levels));
    chain.push_back(image);
    for (int level = 1; level < levels; ++level) {
        const Image& above = chain.back();
        const int width = std::max(1, above.width / 2), height = std::max(1, above.height / 2);
        if (filter != ResizeFilter::BlackmanHarris) {
            Image next = resize(above, width, height, error, filter);
            if (next.empty())
                return {};
            chain.push_back(std::move(next));
            continue;
        }
        // Blackman-Harris, separable and streamed (core/mip_filter.h): the filter the GPU
        // texture path uses too, so a slot's levels equal these.
        const int channels = above.channels;
        float lo[4], hi[4];
        std::fill_n(lo, 4, std::numeric_limits<float>::max());
        std::fill_n(hi, 4, std::numeric_limits<float>::lowest());
        for (size_t i = 0; i < above.pixels.size(); ++i) {
            const int c = int(i % channels);
            lo[c] = std::min(lo[c], above.pixels[i]);
            hi[c] = std::max(hi[c], above.pixels[i]);
        }
        for (int c = channels; c < 4; ++c)
            lo[c] = std::numeric_limits<float>::lowest(), hi[c] = std::numeric_limits<float>::max();
        Image next(width, height, channels);
        halveLevel(
            above.width, above.height,
            [&](int y, float* rgba) {
                const float* p = above.at(0, y);
                for (int x = 0; x < above.width; ++x, p += channels, rgba += 4)
                    for (int c = 0; c < 4; ++c)
                        rgba[c] = c < channels ? p[c] : 1.0f;
            },
            [&](int y, const float* rgba) {
                float* p = next.at(0, y);
                for (int x = 0; x < width; ++x, p += channels, rgba += 4)
                    for (int c = 0; c < channels; ++c)
                        p[c] = rgba[c];
            },
            lo, hi);
        chain.push_back(std::move(next));
    }
    return chain;
}

bool fitToLimit(Image& image, int maxSide, std::string* warning, const std::string& fileName) {
    if (maxSide < 1 || image.empty() || (image.width <= maxSide && image.height <= maxSide))
        return false;
    const double scale = double(maxSide) / std::max(image.width, image.height);
    const int width = std::clamp(int(std::lround(image.width * scale)), 1, maxSide);
    const int height = std::clamp(int(std::lround(image.height * scale)), 1, maxSide);
    std::string error;
    Image smaller = resize(image, width, height, &error);
    if (smaller.empty()) {
        if (warning)
            *warning = (fileName.empty() ? std::string() : fileName + ": ") +
                       "cannot downscale to the texture limit: " + error;
        return false;
    }
    if (warning)
        *warning = (fileName.empty() ? std::string("texture") : fileName) + ": " +
                   std::to_string(image.width) + "x" + std::to_string(image.height) +
                   " is larger than the GPU limit of " + std::to_string(maxSide) +
                   " pixels a side; downscaled to " + std::to_string(width) + "x" +
                   std::to_string(height);
    image = std::move(smaller);
    return true;
}

} // namespace velvet

#include "core/atlas_packing.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <numeric>

namespace velvet {
namespace {

bool setError(std::string* error, const std::string& what) {
    if (error)
        *error = what;
    return false;
}

std::string sizeText(int w, int h) {
    return std::to_string(w) + "x" + std::to_string(h);
}

/// Skyline bottom-left bin (Jylänki 2010, "Skyline-BL"): the top edge of what is placed so far
/// as a list of horizontal segments; a rectangle goes where its bottom edge ends lowest (here
/// "lowest" is the smallest y, as rows go down), ties to the narrowest segment.
class Skyline {
public:
    Skyline(int width, int height) : m_width(width), m_height(height) {
        m_nodes.push_back({0, 0, width});
    }

    bool insert(int w, int h, int& outX, int& outY) {
        int bestBottom = INT_MAX, bestWidth = INT_MAX, bestIndex = -1, bestY = 0;
        for (size_t i = 0; i < m_nodes.size(); ++i) {
            const int y = fit(i, w, h);
            if (y < 0)
                continue;
            if (y + h < bestBottom || (y + h == bestBottom && m_nodes[i].width < bestWidth)) {
                bestBottom = y + h;
                bestWidth = m_nodes[i].width;
                bestIndex = int(i);
                bestY = y;
            }
        }
        if (bestIndex < 0)
            return false;
        outX = m_nodes[size_t(bestIndex)].x;
        outY = bestY;
        add(size_t(bestIndex), outX, bestY + h, w);
        m_usedWidth = std::max(m_usedWidth, outX + w);
        m_usedHeight = std::max(m_usedHeight, bestY + h);
        return true;
    }
    int usedWidth() const { return m_usedWidth; }
    int usedHeight() const { return m_usedHeight; }

private:
    struct Node {
        int x, y, width;
    };

    /// The y at which a w x h rectangle fits with its left edge at node i, or -1.
    int fit(size_t i, int w, int h) const {
        if (m_nodes[i].x + w > m_width)
            return -1;
        int y = m_nodes[i].y;
        for (int left = w; left > 0; ++i) {
            y = std::max(y, m_nodes[i].y);
            if (y + h > m_height)
                return -1;
            left -= m_nodes[i].width;
        }
        return y;
    }

    void add(size_t index, int x, int y, int width) {
        m_nodes.insert(m_nodes.begin() + std::ptrdiff_t(index), Node{x, y, width});
        // Cut the segments the new one covers.
        for (size_t i = index + 1; i < m_nodes.size();) {
            const Node& prev = m_nodes[i - 1];
            Node& n = m_nodes[i];
            const int shrink = prev.x + prev.width - n.x;
            if (shrink <= 0)
                break;
            n.x += shrink;
            n.width -= shrink;
            if (n.width > 0)
                break;
            m_nodes.erase(m_nodes.begin() + std::ptrdiff_t(i));
        }
        // Merge neighbours at the same height.
        for (size_t i = 0; i + 1 < m_nodes.size();) {
            if (m_nodes[i].y == m_nodes[i + 1].y) {
                m_nodes[i].width += m_nodes[i + 1].width;
                m_nodes.erase(m_nodes.begin() + std::ptrdiff_t(i + 1));
            } else {
                ++i;
            }
        }
    }

    int m_width, m_height;
    int m_usedWidth = 0, m_usedHeight = 0;
    std::vector<Node> m_nodes;
};

/// Packs padded sizes, in @p order, into a bin of at most @p w x @p h. Fills @p regions (input
/// order, unpadded) and the used extent; false if they do not all fit.
bool tryPack(std::span<const AtlasItemSize> sizes, const std::vector<size_t>& order, int padding,
             int w, int h, std::vector<AtlasRegion>& regions, int& usedW, int& usedH) {
    Skyline bin(w, h);
    regions.assign(sizes.size(), AtlasRegion{});
    for (size_t i : order) {
        int x = 0, y = 0;
        if (!bin.insert(sizes[i].width + 2 * padding, sizes[i].height + 2 * padding, x, y))
            return false;
        regions[i] = {x + padding, y + padding, sizes[i].width, sizes[i].height};
    }
    usedW = bin.usedWidth();
    usedH = bin.usedHeight();
    return true;
}

int nextPowerOfTwo(int v) {
    int p = 1;
    while (p < v && p < (1 << 30))
        p <<= 1;
    return p;
}

/// Value of channel @p c of pixel (x, y) for an atlas of @p channels channels.
float channelFor(const Image& image, int x, int y, int c, int channels) {
    if (image.channels == channels)
        return image.at(x, y)[c];
    const glm::vec4 p = image.rgba(x, y);
    if (channels == 2) // grey + alpha
        return c == 0 ? p.r : p.a;
    return p[c];
}

} // namespace

bool planAtlas(std::span<const AtlasItemSize> sizes, const AtlasOptions& options, AtlasLayout& out,
               std::string* error) {
    if (sizes.empty())
        return setError(error, "atlas: no images to pack");
    if (options.padding < 0 || options.maxWidth < 1 || options.maxHeight < 1)
        return setError(error, "atlas: bad options (padding " + std::to_string(options.padding) +
                                   ", maximum " + sizeText(options.maxWidth, options.maxHeight) +
                                   ")");
    const int pad2 = 2 * options.padding;
    std::uint64_t area = 0;
    int widest = 0, tallest = 0;
    for (size_t i = 0; i < sizes.size(); ++i) {
        const AtlasItemSize& s = sizes[i];
        if (s.width < 1 || s.height < 1)
            return setError(error, "atlas: image " + std::to_string(i + 1) + " is empty (" +
                                       sizeText(s.width, s.height) + ")");
        if (s.width + pad2 > options.maxWidth || s.height + pad2 > options.maxHeight)
            return setError(error, "atlas: image " + std::to_string(i + 1) + " (" +
                                       sizeText(s.width, s.height) + " with " +
                                       std::to_string(options.padding) +
                                       " texels padding) is larger than the maximum atlas size " +
                                       sizeText(options.maxWidth, options.maxHeight));
        area += std::uint64_t(s.width + pad2) * std::uint64_t(s.height + pad2);
        widest = std::max(widest, s.width + pad2);
        tallest = std::max(tallest, s.height + pad2);
    }

    // Tallest first (then widest): shelves of similar height waste least (Jylänki 2010).
    std::vector<size_t> order(sizes.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        if (sizes[a].height != sizes[b].height)
            return sizes[a].height > sizes[b].height;
        return sizes[a].width > sizes[b].width;
    });

    struct Candidate {
        int width, height;
    };
    std::vector<Candidate> candidates;
    if (options.powerOfTwo) {
        for (int w = nextPowerOfTwo(widest); w <= options.maxWidth && w > 0; w <<= 1)
            for (int h = nextPowerOfTwo(tallest); h <= options.maxHeight && h > 0; h <<= 1)
                if (std::uint64_t(w) * std::uint64_t(h) >= area)
                    candidates.push_back({w, h});
    } else {
        // Widths from the square root of the area up to the limit; the height is what is used.
        const int from = std::max(widest, int(std::ceil(std::sqrt(double(area)))));
        for (double w = from; w < options.maxWidth; w = std::ceil(w * 1.125))
            candidates.push_back({int(w), options.maxHeight});
        candidates.push_back({options.maxWidth, options.maxHeight});
        for (int w = widest; w < from; w = int(std::ceil(w * 1.25)))
            candidates.push_back({w, options.maxHeight});
    }
    // Smallest area first; between equals the squarer, then the wider.
    std::stable_sort(candidates.begin(), candidates.end(), [](Candidate a, Candidate b) {
        const auto areaA = std::uint64_t(a.width) * a.height;
        const auto areaB = std::uint64_t(b.width) * b.height;
        if (areaA != areaB)
            return areaA < areaB;
        const int skewA = std::abs(a.width - a.height), skewB = std::abs(b.width - b.height);
        if (skewA != skewB)
            return skewA < skewB;
        return a.width > b.width;
    });

    AtlasLayout best;
    std::uint64_t bestArea = UINT64_MAX;
    std::vector<AtlasRegion> regions;
    for (const Candidate& c : candidates) {
        int usedW = 0, usedH = 0;
        if (!tryPack(sizes, order, options.padding, c.width, c.height, regions, usedW, usedH))
            continue;
        if (options.powerOfTwo) { // sorted by area: the first that fits is the smallest
            best = {c.width, c.height, regions};
            bestArea = 0;
            break;
        }
        // Squarest first (the longest side, which bounds what a GPU must accept), then area.
        const std::uint64_t score = (std::uint64_t(std::max(usedW, usedH)) << 32) |
                                    (std::uint64_t(usedW) * std::uint64_t(usedH));
        if (score < bestArea) {
            bestArea = score;
            best = {usedW, usedH, regions};
        }
    }
    if (bestArea == UINT64_MAX)
        return setError(error, "atlas: " + std::to_string(sizes.size()) + " images (" +
                                   std::to_string(area) + " texels with " +
                                   std::to_string(options.padding) +
                                   " texels padding each side) do not fit in " +
                                   sizeText(options.maxWidth, options.maxHeight) +
                                   (options.powerOfTwo ? " (power-of-two sides)" : ""));
    out = std::move(best);
    return true;
}

bool packAtlas(std::span<const Image> images, const AtlasOptions& options, Image& atlas,
               AtlasLayout& layout, std::string* error) {
    std::vector<AtlasItemSize> sizes;
    sizes.reserve(images.size());
    int maxChannels = 0;
    bool mixed = false, alpha = false;
    for (size_t i = 0; i < images.size(); ++i) {
        const Image& img = images[i];
        if (img.empty() || img.channels < 1 || img.channels > 4 ||
            img.pixels.size() != size_t(img.width) * img.height * img.channels)
            return setError(error,
                            "atlas: image " + std::to_string(i + 1) + " is empty or inconsistent");
        sizes.push_back({img.width, img.height});
        mixed = mixed || (maxChannels != 0 && img.channels != maxChannels);
        maxChannels = std::max(maxChannels, img.channels);
        alpha = alpha || img.channels == 2 || img.channels == 4;
    }
    AtlasLayout plan;
    if (!planAtlas(sizes, options, plan, error))
        return false;
    int channels = maxChannels;
    if (mixed)
        channels = maxChannels <= 2 ? 2 : alpha ? 4 : 3;

    Image out(plan.width, plan.height, channels);
    const int p = options.padding;
    for (size_t i = 0; i < images.size(); ++i) {
        const Image& img = images[i];
        const AtlasRegion& r = plan.regions[i];
        // The padded rectangle; texels outside the image repeat its nearest edge texel.
        for (int y = -p; y < r.height + p; ++y) {
            const int sy = std::clamp(y, 0, img.height - 1);
            for (int x = -p; x < r.width + p; ++x) {
                const int sx = std::clamp(x, 0, img.width - 1);
                float* o = out.at(r.x + x, r.y + y);
                for (int c = 0; c < channels; ++c)
                    o[c] = channelFor(img, sx, sy, c, channels);
            }
        }
    }
    atlas = std::move(out);
    layout = std::move(plan);
    return true;
}

Image extractRegion(const Image& atlas, const AtlasRegion& region) {
    if (region.width < 1 || region.height < 1 || region.x < 0 || region.y < 0 ||
        region.x + region.width > atlas.width || region.y + region.height > atlas.height)
        return {};
    Image out(region.width, region.height, atlas.channels);
    for (int y = 0; y < region.height; ++y)
        std::copy_n(atlas.at(region.x, region.y + y), size_t(region.width) * atlas.channels,
                    out.at(0, y));
    return out;
}

glm::vec4 regionMean(const Image& level, const AtlasRegion& r, int width, int height) {
    const Image& m = level;
    const double sx = double(m.width) / width, sy = double(m.height) / height;
    const int x0 = std::clamp(int(std::floor(r.x * sx)), 0, m.width - 1);
    const int y0 = std::clamp(int(std::floor(r.y * sy)), 0, m.height - 1);
    const int x1 = std::clamp(int(std::ceil((r.x + r.width) * sx)), x0 + 1, m.width);
    const int y1 = std::clamp(int(std::ceil((r.y + r.height) * sy)), y0 + 1, m.height);
    glm::dvec4 sum(0.0);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x)
            sum += glm::dvec4(m.rgba(x, y));
    return glm::vec4(sum / double((x1 - x0) * (y1 - y0)));
}

} // namespace velvet

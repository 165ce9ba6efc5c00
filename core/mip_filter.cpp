#include "core/mip_filter.h"

#include <algorithm>
#include <cmath>
#include <thread>
#include <vector>

namespace velvet {
namespace {

/// Blackman-Harris window on [-1, 1] (Harris 1978, the 4-term minimum: a0..a3 as OpenImageIO's
/// FilterBlackmanHarris1D uses them), 0 outside.
float blackmanHarris(float x) {
    if (x <= -1.0f || x >= 1.0f)
        return 0.0f;
    const double t = 2.0 * M_PI * (0.5 + 0.5 * double(x)); // [0, 2 pi] across the support
    return float(0.35875 - 0.48829 * std::cos(t) + 0.14128 * std::cos(2.0 * t) -
                 0.01168 * std::cos(3.0 * t));
}

/// Taps of one output sample: the first source index and normalised weights.
struct Taps {
    int first = 0;
    std::vector<float> weights;
};

/// Weights for each of @p dstSize outputs from @p srcSize inputs, as ImageBufAlgo::resize
/// places them: output pixel centre d + 0.5 maps to source (d + 0.5) * ratio, the filter's
/// radius is 1.5 destination pixels (1.5 * ratio source pixels); indices outside clamp to the
/// edge (their weight adds to the edge pixel).
std::vector<Taps> tapsFor(int srcSize, int dstSize) {
    std::vector<Taps> out(static_cast<size_t>(dstSize));
    const double ratio = double(srcSize) / double(dstSize);
    const double radius = 1.5 * std::max(ratio, 1.0);
    for (int d = 0; d < dstSize; ++d) {
        const double centre = (d + 0.5) * ratio; // in source pixel-edge coordinates
        const int lo = int(std::floor(centre - radius));
        const int hi = int(std::ceil(centre + radius));
        Taps& t = out[size_t(d)];
        t.first = std::clamp(lo, 0, srcSize - 1);
        const int last = std::clamp(hi, 0, srcSize - 1);
        t.weights.assign(size_t(last - t.first + 1), 0.0f);
        double sum = 0.0;
        std::vector<double> w(size_t(last - t.first + 1), 0.0);
        for (int i = lo; i <= hi; ++i) {
            const double x = (i + 0.5 - centre) / radius; // source pixel centre
            const double v = blackmanHarris(float(x));
            if (v <= 0.0)
                continue;
            w[size_t(std::clamp(i, 0, srcSize - 1) - t.first)] += v;
            sum += v;
        }
        for (size_t k = 0; k < w.size(); ++k)
            t.weights[k] = float(sum > 0.0 ? w[k] / sum : (k == 0 ? 1.0 : 0.0));
    }
    return out;
}

/// Output rows [y0, y1) of the halved level.
void halveRows(int width, int height, int dstW, const std::vector<Taps>& columns,
               const std::vector<Taps>& rows, int y0, int y1, const MipRowLoader& load,
               const MipRowStorer& store, const float lo[4], const float hi[4]) {
    // Horizontally filtered source rows, kept while an output row's support may need them
    // (ring indexed by source row).
    int ringSize = 1;
    for (int y = y0; y < y1; ++y)
        ringSize = std::max(ringSize, int(rows[size_t(y)].weights.size()) + 2);
    std::vector<std::vector<float>> ring(size_t(ringSize), std::vector<float>(size_t(dstW) * 4));
    std::vector<int> ringRow(size_t(ringSize), -1);
    std::vector<float> src(size_t(width) * 4);
    std::vector<float> out(size_t(dstW) * 4);
    auto filtered = [&](int sy) -> const float* {
        const size_t slot = size_t(sy % ringSize);
        if (ringRow[slot] != sy) {
            load(sy, src.data());
            float* h = ring[slot].data();
            for (int dx = 0; dx < dstW; ++dx) {
                const Taps& t = columns[size_t(dx)];
                float acc[4] = {0, 0, 0, 0};
                const float* s = src.data() + size_t(t.first) * 4;
                for (float w : t.weights) {
                    acc[0] += w * s[0], acc[1] += w * s[1], acc[2] += w * s[2], acc[3] += w * s[3];
                    s += 4;
                }
                std::copy(acc, acc + 4, h + size_t(dx) * 4);
            }
            ringRow[slot] = sy;
        }
        return ring[slot].data();
    };
    (void)height;
    for (int y = y0; y < y1; ++y) {
        const Taps& t = rows[size_t(y)];
        std::fill(out.begin(), out.end(), 0.0f);
        for (size_t k = 0; k < t.weights.size(); ++k) {
            const float w = t.weights[k];
            const float* h = filtered(t.first + int(k));
            for (size_t i = 0; i < out.size(); ++i)
                out[i] += w * h[i];
        }
        for (size_t i = 0; i < out.size(); ++i)
            out[i] = std::clamp(out[i], lo[i & 3], hi[i & 3]);
        store(y, out.data());
    }
}

} // namespace

void halveLevel(int width, int height, const MipRowLoader& load, const MipRowStorer& store,
                const float lo[4], const float hi[4], int threads) {
    const int dstW = std::max(1, width / 2), dstH = std::max(1, height / 2);
    const std::vector<Taps> columns = tapsFor(width, dstW), rows = tapsFor(height, dstH);
    if (threads < 2 || dstH < 64) {
        halveRows(width, height, dstW, columns, rows, 0, dstH, load, store, lo, hi);
        return;
    }
    // Two halves of the output rows, one on a second thread (the storer takes distinct rows).
    const int mid = dstH / 2;
    std::thread worker(
        [&] { halveRows(width, height, dstW, columns, rows, mid, dstH, load, store, lo, hi); });
    halveRows(width, height, dstW, columns, rows, 0, mid, load, store, lo, hi);
    worker.join();
}

} // namespace velvet

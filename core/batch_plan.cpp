#include "core/batch_plan.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace velvet {
namespace {

bool parseInt(std::string_view text, int& v) {
    if (text.empty())
        return false;
    auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    return ec == std::errc() && ptr == text.data() + text.size();
}

} // namespace

std::optional<Shard> parseShard(std::string_view text) {
    const size_t slash = text.find('/');
    if (slash == std::string_view::npos)
        return std::nullopt;
    Shard s;
    if (!parseInt(text.substr(0, slash), s.index) || !parseInt(text.substr(slash + 1), s.count))
        return std::nullopt;
    if (s.count < 1 || s.count > 100000 || s.index < 0 || s.index >= s.count)
        return std::nullopt;
    return s;
}

std::vector<std::string> shardInputs(std::vector<std::string> inputs, Shard shard) {
    std::sort(inputs.begin(), inputs.end());
    inputs.erase(std::unique(inputs.begin(), inputs.end()), inputs.end());
    std::vector<std::string> out;
    for (size_t i = 0; i < inputs.size(); ++i)
        if (int(i % size_t(shard.count)) == shard.index)
            out.push_back(std::move(inputs[i]));
    return out;
}

std::string formatDuration(double seconds) {
    const long total = std::max(0L, long(std::ceil(seconds)));
    const long h = total / 3600, m = (total / 60) % 60, s = total % 60;
    char text[32];
    if (h > 0)
        std::snprintf(text, sizeof text, "%ld:%02ld:%02ld", h, m, s);
    else
        std::snprintf(text, sizeof text, "%ld:%02ld", m, s);
    return text;
}

std::optional<double> estimateRemaining(int done, int total, double elapsed) {
    if (done >= total)
        return 0.0;
    if (done <= 0)
        return std::nullopt;
    // Throughput so far (inputs per second, all workers together) times what is left.
    return elapsed / double(done) * double(total - done);
}

} // namespace velvet

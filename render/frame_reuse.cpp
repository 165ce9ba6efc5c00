#include "render/frame_reuse.h"

namespace velvet::render {

FrameKey& FrameKey::add(const std::string& text) {
    add(text.size());
    const auto* p = reinterpret_cast<const std::byte*>(text.data());
    m_bytes.insert(m_bytes.end(), p, p + text.size());
    return *this;
}

bool FrameReuse::reuse(FrameKey key) {
    const bool same = m_valid && key == m_key;
    m_key = std::move(key);
    m_valid = true;
    m_reused += same ? 1 : 0;
    return same;
}

} // namespace velvet::render

#include "render/background_reuse.h"

namespace velvet::render {

BackgroundKey& BackgroundKey::add(const std::string& text) {
    add(text.size());
    const auto* p = reinterpret_cast<const std::byte*>(text.data());
    m_bytes.insert(m_bytes.end(), p, p + text.size());
    return *this;
}

bool BackgroundReuse::reuse(BackgroundKey key) {
    const bool same = m_valid && key == m_key;
    m_key = std::move(key);
    m_valid = true;
    m_reused += same ? 1 : 0;
    return same;
}

} // namespace velvet::render

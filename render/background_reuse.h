#pragma once
// Whether a display-only frame may keep the last frame's background pixels (issue 16).
//
// The inline display path (FrameSettings::displayOnly) draws the background and the surfaces
// straight into one display framebuffer that persists between frames. The surfaces' pass is
// depth-tested against this frame's G-buffer, so it writes the mesh's pixels only; every other
// pixel still holds what the background pass wrote last frame. When nothing the background or
// the display step reads has changed and the mesh covers the same pixels — a material value edit
// (a slider dragged), the editor's most common frame — the background pass (a cube lookup and
// the display step for ~75 % of a preview's pixels) can be skipped: the pixels are already right.
//
// The key holds everything those pixels depend on, bytewise: the frame block (camera, viewport,
// environment, background, exposure, lights), the IBL block (the bake's state, the blurred
// level; the time only when the background or the display step reads it), the framebuffer and
// its format, the programs and the display step's source key. What the key cannot see — the
// coverage through a cut-out texture, the scene's structure, the colour management, the shaders
// on disk — invalidates the reuse from the outside (Renderer::update with anything but
// ScenePart::MaterialValues, a texture upload, a split frame, a frame off the inline path).
#include <cstddef>
#include <string>
#include <type_traits>
#include <vector>

namespace velvet::render {

/// The bytes the background pixels of an inline frame depend on (see the header).
class BackgroundKey {
public:
    // Room for the frame and IBL blocks and the rest at once (and no false -Wstringop-overflow
    // from GCC 12 on inserting into an empty vector).
    BackgroundKey() { m_bytes.reserve(2048); }
    template <typename T>
    BackgroundKey& add(const T& value) {
        static_assert(std::is_trivially_copyable_v<T>);
        const auto* p = reinterpret_cast<const std::byte*>(&value);
        m_bytes.insert(m_bytes.end(), p, p + sizeof(T));
        return *this;
    }
    BackgroundKey& add(const std::string& text);
    bool operator==(const BackgroundKey&) const = default;

private:
    std::vector<std::byte> m_bytes;
};

/// The last inline frame's key, and whether its background pixels may be kept.
class BackgroundReuse {
public:
    /// Something the key cannot see changed (the next inline frame draws the background).
    void invalidate() { m_valid = false; }
    /// Whether this frame, with @p key, may keep the background the last frame drew; remembers
    /// @p key for the next frame either way.
    bool reuse(BackgroundKey key);
    /// Frames that kept the background since the renderer started (tests, bench).
    int reusedFrames() const { return m_reused; }

private:
    BackgroundKey m_key;
    bool m_valid = false;
    int m_reused = 0;
};

} // namespace velvet::render

#pragma once
// Whether a frame may keep what a pass drew last frame, by a key of the bytes that result depends
// on (FrameKey) and the last frame's key (FrameReuse). Two passes use it: the inline display
// path's background (below, issue 16) and the screen-space occlusion (render/ao_pass.h), kept
// while the depth and normals it reads and the camera are as they were.
//
// The background: whether a display-only frame may keep the last frame's background pixels.
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

/// The bytes a kept result depends on (see the header).
class FrameKey {
public:
    // Room for the frame and IBL blocks and the rest at once (and no false -Wstringop-overflow
    // from GCC 12 on inserting into an empty vector).
    FrameKey() { m_bytes.reserve(2048); }
    template <typename T>
    FrameKey& add(const T& value) {
        static_assert(std::is_trivially_copyable_v<T>);
        const auto* p = reinterpret_cast<const std::byte*>(&value);
        m_bytes.insert(m_bytes.end(), p, p + sizeof(T));
        return *this;
    }
    FrameKey& add(const std::string& text);
    bool operator==(const FrameKey&) const = default;

private:
    std::vector<std::byte> m_bytes;
};

/// The last frame's key, and whether its result may be kept.
class FrameReuse {
public:
    /// Something the key cannot see changed (the next frame draws the result again).
    void invalidate() { m_valid = false; }
    /// Whether this frame, with @p key, may keep the result the last frame drew; remembers
    /// @p key for the next frame either way.
    bool reuse(FrameKey key);
    /// Frames that kept the result since the renderer started (tests, bench).
    int reusedFrames() const { return m_reused; }

private:
    FrameKey m_key;
    bool m_valid = false;
    int m_reused = 0;
};

} // namespace velvet::render

#pragma once
/// @file scene_fields.h
/// The scene's fields as tables (internal to core): key, kind, range, description and where the
/// value lives. The scene reader, writer and JSON Schema are all generated from these tables, as
/// the material's are from the parameter metadata.

#include "core/json_read.h"
#include "core/scene.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <span>
#include <string>
#include <string_view>

namespace velvet {

/// The largest scene-linear radiance the renderer stores: the half-float maximum (its HDR buffer
/// and environment maps are RGBA16F). Bounds colours and radiance multipliers (scene_fields.cpp).
inline constexpr double kMaxSceneRadiance = 65504.0;

enum class FieldKind {
    Number, ///< float in `range`
    Vec2,   ///< two floats, each in `range`
    Vec3,   ///< three floats, each in `range`
    Bool,
    Text,   ///< a free string
    Path,   ///< a file path: relative to the document, missing files are warnings
    Choice, ///< one of `choices`
};

/// A field of struct S. Exactly one accessor matching `kind` is set.
template <class S>
struct Field {
    std::string_view key;
    FieldKind kind = FieldKind::Number;
    NumberRange range;
    std::span<const std::string_view> choices{};
    std::string_view description;
    float S::*number = nullptr;
    glm::vec2 S::*vec2 = nullptr;
    glm::vec3 S::*vec3 = nullptr;
    bool S::*flag = nullptr;
    std::string S::*text = nullptr;
    int (*getChoice)(const S&) = nullptr;
    void (*setChoice)(S&, int) = nullptr;
    /// Whether the field matters for this value (e.g. cone angles for spot lights only). Fields
    /// that do not matter are written only when they differ from the default, so nothing is lost
    /// and files stay short. nullptr: always written.
    bool (*relevant)(const S&) = nullptr;
    bool required = false;
};

std::span<const Field<Camera>> cameraFields();
std::span<const Field<Light>> lightFields();
std::span<const Field<Environment>> environmentFields();
std::span<const Field<MeshRef>> meshFields();

} // namespace velvet

#pragma once
/// @file param_meta.h
/// Parameter metadata: the single description of every material parameter from which property
/// panels, serializers, JSON Schemas and validation are generated (DESIGN.md, "Parameters").

#include <glm/vec3.hpp>
#include <span>
#include <string_view>

namespace velvet {

/// What kind of value a parameter holds.
enum class ParamType {
    Float,  ///< a scalar with a hard range
    Color,  ///< an RGB triple, each channel with the same range
    Choice, ///< one of a fixed list of names (stored as an index)
};

/// How the numbers of a colour parameter are to be read. Colours are always *stored* scene-linear
/// (Linear Rec.709); `Linear` tells pickers to show display-encoded values and store linear ones.
enum class ColorSpace {
    None,   ///< not a colour
    Linear, ///< scene-linear Rec.709 (the working space)
};

/// Metadata of one parameter. All strings are static; tables of these live in .cpp files.
struct ParamMeta {
    std::string_view id;    ///< JSON path inside the document, e.g. "lobes.base.roughness"
    std::string_view label; ///< shown to the artist, e.g. "Roughness"
    std::string_view group; ///< panel group, e.g. "Base", "Clearcoat", "Sheen", "BRDF"
    ParamType type = ParamType::Float;
    float min = 0.0f; ///< hard minimum (each channel for colours, first index for choices)
    float max = 1.0f; ///< hard maximum (each channel for colours, last index for choices)
    glm::vec3 defaultValue{0.0f}; ///< x holds the scalar or the choice index
    std::string_view unit;        ///< "" when unitless, else e.g. "nits", "°"
    ColorSpace colorSpace = ColorSpace::None;
    std::string_view tooltip;                    ///< one sentence, shown on hover and in docs
    std::span<const std::string_view> choices{}; ///< names of a Choice parameter, in index order
    float softMax = 0.0f; ///< slider end when smaller than max (0: same as max)
};

/// @name Builders of the metadata tables
/// The one way the tables (core/material.cpp's parameters, the post-effect catalogue, the graph
/// nodes' inputs shown as parameters) fill a ParamMeta, so a field added here reaches them all.
/// @{
/// A scalar in [@p min, @p max] (the slider ends at @p softMax when that is smaller than max).
constexpr ParamMeta floatParam(std::string_view id, std::string_view label, std::string_view group,
                               float min, float max, float def, std::string_view unit,
                               std::string_view tooltip, float softMax = 0.0f) {
    ParamMeta m{};
    m.id = id;
    m.label = label;
    m.group = group;
    m.type = ParamType::Float;
    m.min = min;
    m.max = max;
    m.defaultValue = glm::vec3(def);
    m.unit = unit;
    m.tooltip = tooltip;
    m.softMax = softMax;
    return m;
}
/// A scene-linear RGB colour, each channel in [@p min, @p max].
constexpr ParamMeta colorParam(std::string_view id, std::string_view label, std::string_view group,
                               float min, float max, glm::vec3 def, std::string_view tooltip) {
    ParamMeta m{};
    m.id = id;
    m.label = label;
    m.group = group;
    m.type = ParamType::Color;
    m.min = min;
    m.max = max;
    m.defaultValue = def;
    m.colorSpace = ColorSpace::Linear;
    m.tooltip = tooltip;
    return m;
}
/// One of @p names (static storage), stored as its index; @p def is the default index.
constexpr ParamMeta choiceParam(std::string_view id, std::string_view label, std::string_view group,
                                std::span<const std::string_view> names, int def,
                                std::string_view tooltip) {
    ParamMeta m{};
    m.id = id;
    m.label = label;
    m.group = group;
    m.type = ParamType::Choice;
    m.min = 0.0f;
    m.max = float(names.size() - 1);
    m.defaultValue = glm::vec3(float(def));
    m.tooltip = tooltip;
    m.choices = names;
    return m;
}
/// @}
/// The value rules of an edit, one place for every editor (the material's setValue, the post
/// chain's setEffectParam, the property panel through them): each channel clamped to
/// [min, max] (a non-finite one takes the default's x), a choice rounded to the nearest index.
/// Loaders do not use it: a file value out of range is an error, never silently clamped.
glm::vec3 constrainParamValue(const ParamMeta& meta, glm::vec3 value);

} // namespace velvet

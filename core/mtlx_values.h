#pragma once
/// @file mtlx_values.h
/// MaterialX values as Velvet's, with no XML in sight (internal to core/mtlx_import.cpp, which
/// reads the document with pugixml, and core/mtlx_export.cpp): number lists, the colour space a
/// texture slot gets, image placement (the image node's uvtiling / uvoffset and a place2d node's
/// scale / rotate / offset / pivot) as a Velvet UV transform and back, and the Velvet graph node
/// each MaterialX standard node stands for. docs/interchange.md, "From MaterialX 1.39".

#include "core/material.h"

#include <glm/vec2.hpp>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace velvet::mtlx {

/// "0.5, 1, 2" -> {0.5, 1, 2}. Throws std::exception when an item is not a number.
std::vector<float> parseNumbers(const std::string& text);

/// A constant input's value @p text as @p count numbers into @p out (one number is splat for 3):
/// empty, else what is wrong ("is not a number list", "is not finite", "has 2 components,
/// expected 3").
std::string constantValue(const std::string& text, size_t count, std::vector<float>& out);

/// @p v (1 or 3 numbers) into parameter @p id of @p material; a warning (@p where: "line L,
/// column C: shader.input") says when it lies outside Velvet's range (and is clamped).
void setParam(Material& material, ParamId id, const std::vector<float>& v, const std::string& where,
              const std::string& valueText, std::vector<std::string>& warnings);

/// Whether an alpha / opacity input (@p name) holds the value that changes nothing (alpha_mode
/// 0, opacity 1, any alpha_cutoff); a @p connected one never does (Velvet's cut-out comes from
/// the base colour image).
bool isDefaultAlpha(const std::string& name, const std::string& valueText, bool connected);

/// What the shader's inputs leave to the end: the base weight multiplies the base colour
/// (warned when a graph drives it: @p baseDriven), the open_pbr / standard_surface anisotropy
/// @p mxAniso (< 0: none) becomes a strength at the material's roughness, and gltf_pbr's
/// sheen_color (weight x colour, as glTF's) is split into Velvet's weight and colour.
void finishMaterial(Material& m, const std::string& shader, float baseWeight, float mxAniso,
                    bool baseDriven, bool sheenDriven, std::vector<std::string>& warnings);

/// The colour space a slot's TextureRef names for an image node of @p type colour ("color3",
/// "color4": @p colourType) or data, whose file input says @p mxColorSpace ("" when it says
/// none) and whose file has extension @p fileExtension: nullopt for the slot's own default.
/// MaterialX converts colour types only, so a data image in a colour slot is "Raw".
std::optional<std::string> slotColorSpace(const std::string& mxColorSpace, bool colourType,
                                          TextureSlot slot, const std::string& fileExtension);

/// A place2d node's constant inputs (MaterialX Specification 1.39, "Geometric nodes"):
/// out = R(rotate) ((texcoord - pivot) / scale) - offset + pivot for operationorder 0 ("SRT"),
/// R((texcoord - pivot) - offset) / scale + pivot for 1 ("TRS"); R is rotate2d's matrix
/// (cos a, sin a; -sin a, cos a) for a degrees (NG_place2d_vector2 in the standard library).
struct Place2d {
    glm::vec2 pivot{0.0f};
    glm::vec2 scale{1.0f};
    float rotate = 0.0f; ///< degrees
    glm::vec2 offset{0.0f};
    int operationOrder = 0;
};

/// An image's placement in MaterialX: texcoord -> optional place2d -> the image node's
/// uv * uvtiling + uvoffset, in MaterialX's UV space (v up from the bottom row).
struct MtlxPlacement {
    glm::vec2 tiling{1.0f};
    glm::vec2 offset{0.0f};
    std::optional<Place2d> place;
};

/// Velvet's UV transform (texture_ref.h: uv' = R(rotation) (scale uv) + offset, v down from the
/// top row) as a MaterialX placement. Without a rotation the image node's inputs carry it (as
/// before); with one, a place2d (scale 1 / scale, rotate = rotation: the v flip between the two
/// UV spaces turns Velvet's counter-clockwise R into rotate2d's sense) and the image's uvoffset.
MtlxPlacement mtlxPlacement(glm::vec2 scale, glm::vec2 offset, float rotationDegrees);

/// The inverse: the UV transform a MaterialX placement makes in Velvet's UV space. False when
/// the composite cannot be one (a shear: a non-uniform scale after a rotation, or a mirror); @p
/// out then holds the nearest scale and rotation.
bool velvetPlacement(const MtlxPlacement& placement, UvTransform& out);

/// The Velvet graph node type a MaterialX standard node category stands for, and the MaterialX
/// input names that differ from the Velvet node's port names.
struct GraphCounterpart {
    std::string velvetType;
    std::map<std::string, std::string> ports;
};
/// Null when @p category has no counterpart (constant, extract and convert are read apart).
const GraphCounterpart* graphCounterpart(std::string_view category);

} // namespace velvet::mtlx

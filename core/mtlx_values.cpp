// MaterialX values as Velvet's. References: the MaterialX Specification v1.39 ("Texture nodes":
// image's uvtiling / uvoffset; "Geometric nodes": place2d; "Color Spaces"), and the standard
// library's NG_place2d_vector2 and mx_rotate_vector2 (libraries/stdlib), which fix place2d's
// order and rotate2d's sense.
#include "core/mtlx_values.h"

#include "core/mtlx_shader_inputs.h"

#include <algorithm>
#include <cmath>
#include <glm/mat2x2.hpp>
#include <glm/trigonometric.hpp>
#include <sstream>

namespace velvet::mtlx {

std::vector<float> parseNumbers(const std::string& text) {
    std::vector<float> out;
    std::string item;
    std::stringstream in(text);
    while (std::getline(in, item, ','))
        out.push_back(std::stof(item));
    return out;
}

std::string constantValue(const std::string& text, size_t count, std::vector<float>& out) {
    try {
        out = parseNumbers(text);
    } catch (const std::exception&) {
        return "is not a number list";
    }
    for (float f : out)
        if (!std::isfinite(f))
            return "is not finite";
    if (out.size() == 1 && count == 3)
        out.assign(3, out[0]);
    if (out.size() != count)
        return "has " + std::to_string(out.size()) + " components, expected " +
               std::to_string(count);
    return {};
}

void setParam(Material& material, ParamId id, const std::vector<float>& v, const std::string& where,
              const std::string& valueText, std::vector<std::string>& warnings) {
    const ParamMeta& meta = paramMeta(id);
    bool clamped = false;
    for (float f : v)
        clamped |= f < meta.min || f > meta.max;
    if (clamped)
        warnings.push_back(where + " = \"" + valueText + "\" lies outside Velvet's range of " +
                           std::string(meta.id) + "; clamped");
    if (meta.type == ParamType::Color)
        material.setColor(id, glm::vec3(v[0], v[1], v[2]));
    else
        material.setScalar(id, v[0]);
}

bool isDefaultAlpha(const std::string& name, const std::string& v, bool connected) {
    if (connected)
        return false; // a cut-out from the base colour image: see the warning
    if (name == "alpha_mode")
        return v == "0";
    if (name == "alpha_cutoff")
        return true; // with alpha_mode 0 it does nothing
    return v == "1" || v == "1, 1, 1" || v == "1,1,1";
}

void finishMaterial(Material& m, const std::string& shader, float baseWeight, float mxAniso,
                    bool baseDriven, bool sheenDriven, std::vector<std::string>& warnings) {
    using P = ParamId;
    if (mxAniso >= 0.0f) // needs the roughness (mtlx_shader_inputs.h)
        m.setScalar(P::AnisotropyStrength,
                    mtlxAnisotropyToStrength(mxAniso, m.scalar(P::Roughness)));
    if (baseWeight != 1.0f) {
        if (baseDriven)
            warnings.push_back(shader + ".base = " + std::to_string(baseWeight) +
                               " not applied to the graph-driven base colour");
        else
            m.setColor(P::BaseColor, m.color(P::BaseColor) * baseWeight);
    }
    if (shader == "gltf_pbr") { // sheen_color carries weight x colour, as glTF's
        const glm::vec3 c = m.color(P::SheenColor);
        const float w = std::max({c.r, c.g, c.b});
        if (!m.texture(TextureSlot::SheenColor).empty() || sheenDriven) {
            m.setScalar(P::SheenWeight, 1.0f);
        } else {
            m.setScalar(P::SheenWeight, w);
            m.setColor(P::SheenColor, w > 0.0f ? c / w : glm::vec3(1.0f));
        }
    }
}

std::optional<std::string> slotColorSpace(const std::string& mxColorSpace, bool colourType,
                                          TextureSlot slot, const std::string& fileExtension) {
    const bool hdrFile = fileExtension == ".exr" || fileExtension == ".hdr";
    if (colourType && !mxColorSpace.empty()) {
        const std::string v = velvetColorSpace(mxColorSpace);
        // The slot's own default already is sRGB texture for colour slots (PNG, JPEG).
        if (v == "sRGB texture" && textureSlotMeta(slot).isColor && !hdrFile)
            return std::nullopt;
        return v;
    }
    if (!colourType && textureSlotMeta(slot).isColor)
        return std::string("Raw"); // MaterialX converts colour types only
    return std::nullopt;
}

namespace {

/// rotate2d's matrix for @p degrees (mx_rotate_vector2: (c x + s y, -s x + c y)), column-major.
glm::mat2 rotate2d(float degrees) {
    const float r = glm::radians(degrees);
    return glm::mat2(std::cos(r), -std::sin(r), std::sin(r), std::cos(r));
}

} // namespace

MtlxPlacement mtlxPlacement(glm::vec2 scale, glm::vec2 offset, float rotationDegrees) {
    MtlxPlacement p;
    if (rotationDegrees == 0.0f) {
        // uv * uvtiling + uvoffset in MaterialX's UV space (v_mx = 1 - v): the offset becomes
        // (offset.u, 1 - scale.v - offset.v).
        p.tiling = scale;
        p.offset = glm::vec2(offset.x, 1.0f - scale.y - offset.y);
        return p;
    }
    // Velvet samples s = R(t) S u + o with v down; with F(u, v) = (u, 1 - v) on both sides,
    // s_mx = F(R(t) S F(u_mx) + o) = R(-t) S u_mx + c, c = (o.u - s.v sin t, 1 - o.v - s.v cos t).
    // rotate2d(t) is R(-t), so a place2d (scale 1 / S, rotate t) followed by uvoffset c is it.
    const float r = glm::radians(rotationDegrees);
    Place2d place;
    place.scale = glm::vec2(1.0f) / scale;
    place.rotate = rotationDegrees;
    p.place = place;
    p.tiling = glm::vec2(1.0f);
    p.offset = glm::vec2(offset.x - scale.y * std::sin(r), 1.0f - offset.y - scale.y * std::cos(r));
    return p;
}

bool velvetPlacement(const MtlxPlacement& placement, UvTransform& out) {
    out = UvTransform{};
    const glm::vec2 t = placement.tiling, u = placement.offset;
    if (!placement.place) { // the image node alone: the inverse of mtlxPlacement's first case
        out.scale = t;
        out.offset = glm::vec2(u.x, 1.0f - t.y - u.y);
        return true;
    }
    // The whole chain as s = A x + b in MaterialX's UV space (NG_place2d_vector2), ...
    const Place2d& p = *placement.place;
    const glm::mat2 d(1.0f / p.scale.x, 0.0f, 0.0f, 1.0f / p.scale.y);
    const glm::mat2 rot = rotate2d(p.rotate);
    glm::mat2 a;
    glm::vec2 b;
    if (p.operationOrder == 1) { // TRS
        a = d * rot;
        b = -(d * rot * (p.pivot + p.offset)) + p.pivot;
    } else { // SRT
        a = rot * d;
        b = -(rot * d * p.pivot) - p.offset + p.pivot;
    }
    const glm::mat2 tiling(t.x, 0.0f, 0.0f, t.y);
    a = tiling * a;
    b = tiling * b + u;
    // ... then in Velvet's (v flipped on both sides): M = J A J, o = J A e + J b + e, J =
    // diag(1, -1), e = (0, 1); M = R(t) S when M's columns are perpendicular.
    const glm::mat2 j(1.0f, 0.0f, 0.0f, -1.0f);
    const glm::vec2 e(0.0f, 1.0f);
    const glm::mat2 m = j * a * j;
    const glm::vec2 o = j * a * e + j * b + e;
    const float angle = std::atan2(m[0][1], m[0][0]);
    const float c = std::cos(angle), s = std::sin(angle);
    out.rotation = glm::degrees(angle);
    out.scale = glm::vec2(std::hypot(m[0][0], m[0][1]), -m[1][0] * s + m[1][1] * c);
    out.offset = o;
    const float shear = m[1][0] * c + m[1][1] * s;
    const bool finite = std::isfinite(out.scale.x) && std::isfinite(out.scale.y) &&
                        std::isfinite(o.x) && std::isfinite(o.y);
    return finite && std::abs(shear) <= 1e-4f * std::max(1.0f, std::abs(out.scale.y));
}

const GraphCounterpart* graphCounterpart(std::string_view category) {
    static const std::map<std::string, GraphCounterpart, std::less<>> table{
        {"multiply", {"math.multiply", {{"in1", "a"}, {"in2", "b"}}}},
        {"add", {"math.add", {{"in1", "a"}, {"in2", "b"}}}},
        {"mix", {"math.mix", {{"bg", "a"}, {"fg", "b"}, {"mix", "factor"}}}},
        {"clamp", {"math.clamp", {{"in", "value"}, {"low", "min"}, {"high", "max"}}}},
        {"power", {"math.power", {{"in1", "value"}, {"in2", "exponent"}}}},
        {"normalmap", {"normal.map", {{"in", "color"}, {"scale", "strength"}}}},
        {"combine3", {"channel.combine", {{"in1", "r"}, {"in2", "g"}, {"in3", "b"}}}},
        {"separate3", {"channel.split", {{"in", "color"}}}},
        {"texcoord", {"input.uv", {}}},
        {"image", {"texture.image", {{"texcoord", "uv"}}}},
        {"tiledimage", {"texture.image", {{"texcoord", "uv"}}}},
    };
    const auto it = table.find(category);
    return it == table.end() ? nullptr : &it->second;
}

} // namespace velvet::mtlx

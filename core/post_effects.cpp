// The post-effect catalogue: one table entry per effect type; parameters and their ranges come
// from the seed documents (000: bloom, tone mapping, pixelation, night vision; 001: gaussian blur,
// vignette; 002: motion blur, toon; 004: bloom, fake DoF, pointillism, paintbrush, vaporwave) and
// from the engines artists compare against (Unity's post-processing stack, Filament).
#include "core/post_effects.h"

#include "core/json_read.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>

namespace velvet {
namespace {

// The catalogue's parameters, all in the "Effect" group, through core/param_meta.h's builders.
constexpr ParamMeta scalar(std::string_view id, std::string_view label, float min, float max,
                           float def, std::string_view unit, std::string_view tooltip) {
    return floatParam(id, label, "Effect", min, max, def, unit, tooltip);
}

constexpr ParamMeta colour(std::string_view id, std::string_view label, float min, float max,
                           glm::vec3 def, std::string_view tooltip) {
    return colorParam(id, label, "Effect", min, max, def, tooltip);
}

constexpr ParamMeta choice(std::string_view id, std::string_view label,
                           std::span<const std::string_view> names, int def,
                           std::string_view tooltip) {
    return choiceParam(id, label, "Effect", names, def, tooltip);
}

constexpr std::array<std::string_view, 2> kOffOn{"off", "on"};
constexpr std::array<std::string_view, 7> kToneMappers{
    "pbr-neutral", "aces", "reinhard", "filmic", "agx", "linear", "display"};

const std::array kBloom{
    scalar("threshold", "Threshold", 0, 64, 1.0f, "",
           "Brightness (max channel, scene-linear) above which pixels bloom."),
    scalar("knee", "Soft knee", 0, 1, 0.5f, "",
           "Width of the soft transition around the threshold, as a fraction of it."),
    scalar("radius", "Radius", 1, 8, 5, "mip levels",
           "How far the glow spreads: the number of half-resolution levels it goes down."),
    scalar("intensity", "Intensity", 0, 8, 0.3f, "", "Strength of the added glow."),
    colour("tint", "Tint", 0, 4, glm::vec3(1.0f), "Colour the glow is multiplied by."),
};
const std::array kToneMap{
    scalar("exposure", "Exposure", -16, 16, 0.0f, "EV", "Stops of exposure before the curve."),
    choice("operator", "Operator", kToneMappers, 0,
           "Tone curve; \"display\" uses the OpenColorIO display/view transform."),
};
const std::array kBlur{
    scalar("sigma", "Sigma", 0.1f, 32, 2.0f, "px", "Standard deviation of the gaussian."),
    scalar("radius", "Radius", 1, 64, 6, "px", "Taps on each side of the centre."),
};
const std::array kVignette{
    scalar("centerX", "Center X", 0, 1, 0.5f, "", "Horizontal centre, 0 left, 1 right."),
    scalar("centerY", "Center Y", 0, 1, 0.5f, "", "Vertical centre, 0 bottom, 1 top."),
    scalar("roundness", "Roundness", 0, 1, 1.0f, "", "1 round, 0 almost square."),
    scalar("intensity", "Intensity", 0, 1, 0.35f, "",
           "How much the corners are darkened (0.35: corners keep 65 %)."),
    scalar("smoothness", "Smoothness", 0.01f, 1, 0.6f, "", "Width of the falloff."),
    scalar("blend", "Blend", 0, 1, 0.0f, "", "0 darkens, 1 replaces the border by the colour."),
    colour("color", "Colour", 0, 1, glm::vec3(0.0f), "Colour of the border."),
};
const std::array kPixelate{
    scalar("cellSize", "Cell size", 1, 128, 8, "px", "Side of the square cells."),
};
const std::array kNightVision{
    colour("weights", "Green weights", 0, 4, glm::vec3(0.1f, 1.0f, 0.2f),
           "Luminance is multiplied by these channel weights (seed 000: more weight to green)."),
    scalar("grain", "Grain", 0, 1, 0.15f, "", "Amount of animated noise."),
    scalar("vignetting", "Vignetting", 0, 1, 0.6f, "", "Darkening towards the border."),
};
const std::array kMotionBlur{
    scalar("samples", "Samples", 2, 32, 8, "", "Taps along the motion vector."),
    scalar("strength", "Strength", 0, 4, 1.0f, "", "Scale of the per-pixel motion vector."),
    scalar("frameBlend", "Frame blending", 0, 0.9f, 0.0f, "",
           "Weight of the previous frame's image blended in (Unity post-processing v1 frame "
           "blending); 0 keeps no previous frame."),
};
const std::array kToon{
    scalar("bands", "Bands", 2, 16, 3, "", "Number of luminance bands (seed 002: levels)."),
    scalar("lightIntensity", "Light intensity", 0.01f, 20, 1.0f, "",
           "Luminance scale before banding (seed 002: lightIntensity)."),
    choice("outline", "Outline", kOffOn, 1, "Dark lines at depth and normal discontinuities."),
    scalar("outlineThreshold", "Outline threshold", 0.001f, 1, 0.2f, "",
           "Edge strength above which the outline is drawn."),
    colour("outlineColor", "Outline colour", 0, 1, glm::vec3(0.0f), "Colour of the outline."),
};
const std::array kDof{
    scalar("focalDistance", "Focal distance", 0.01f, 1000, 3.0f, "m",
           "Distance from the camera that is in focus."),
    scalar("focalRange", "Focal range", 0, 100, 0.5f, "m",
           "Depth around the focal distance that stays sharp."),
    scalar("maxBlur", "Max blur", 0, 32, 6.0f, "px", "Blur radius far from the focal plane."),
};
const std::array kPointillism{
    scalar("cellSize", "Cell size", 2, 64, 6, "px", "Spacing of the dots."),
    scalar("dotScale", "Dot scale", 0, 2, 1.0f, "",
           "Dot radius scale; darker cells get larger dots."),
    colour("paperColor", "Paper colour", 0, 1, glm::vec3(0.95f, 0.93f, 0.86f),
           "Colour between the dots."),
};
const std::array kPaintbrush{
    scalar("brushScale", "Brush scale", 2, 64, 8, "px", "Size of one stroke."),
    scalar("noiseAmount", "Noise amount", 0, 1, 0.3f, "", "Roughness of the stroke edges."),
    scalar("noiseFrequency", "Noise frequency", 0.1f, 16, 2.0f, "",
           "Frequency of the curl noise that orients the strokes (higher: less coherent)."),
    scalar("period", "Change period", 0.1f, 120, 4.0f, "s",
           "Strokes change every this many seconds, with a smooth transition."),
};
const std::array kVaporwave{
    scalar("desaturation", "Desaturation", 0, 1, 0.6f, "", "How much colour is removed."),
    colour("tint", "Tint", 0, 1, glm::vec3(0.62f, 0.25f, 0.85f), "The purple blended in."),
    scalar("tintAmount", "Tint amount", 0, 1, 0.45f, "", "How much of the tint is blended in."),
    scalar("checkerSize", "Checker size", 0, 128, 16, "px",
           "Checker squares replacing the far background (0: off)."),
    scalar("aberration", "Aberration", 0, 32, 3, "px",
           "Horizontal shift of the green channel, larger towards the left and right edges."),
    scalar("staticAmount", "Static", 0, 1, 0.08f, "", "TV static noise."),
    scalar("scanlines", "Scanlines", 0, 1, 0.25f, "", "Darkening of every other line pair."),
};
const std::array kColorGrading{
    scalar("exposure", "Exposure", -16, 16, 0.0f, "EV", "Stops of exposure."),
    scalar("contrast", "Contrast", 0, 3, 1.0f, "", "Contrast around 18 % grey."),
    scalar("saturation", "Saturation", 0, 3, 1.0f, "", "0 grey, 1 unchanged."),
    scalar("temperature", "Temperature", -1, 1, 0.0f, "", "White balance: blue (-) to amber (+)."),
    scalar("tint", "Tint", -1, 1, 0.0f, "", "White balance: green (-) to magenta (+)."),
    colour("lift", "Lift", -1, 1, glm::vec3(0.0f), "Offset of the shadows."),
    colour("gamma", "Gamma", 0.1f, 4, glm::vec3(1.0f), "Power of the midtones."),
    colour("gain", "Gain", 0, 4, glm::vec3(1.0f), "Scale of the highlights."),
};
const std::array kFilmGrain{
    scalar("intensity", "Intensity", 0, 1, 0.1f, "", "Amount of grain."),
    scalar("size", "Size", 1, 8, 1.5f, "px", "Size of a grain."),
};
const std::array kChromaticAberration{
    scalar("amount", "Amount", 0, 32, 2.0f, "px", "Red/blue split at the corners."),
};
const std::array kSharpen{
    scalar("amount", "Amount", 0, 4, 0.5f, "", "Unsharp-mask strength."),
};
const std::array kFxaa{
    scalar("edgeThreshold", "Edge threshold", 0.02f, 0.5f, 0.125f, "",
           "Minimum local contrast treated as an edge."),
    scalar("subpixel", "Subpixel", 0, 1, 0.75f, "", "Amount of subpixel aliasing removed."),
};

const std::array<EffectMeta, 17> kCatalogue{{
    {"bloom", "Bloom",
     "Soft-knee bright pass, half-resolution mip down/up-sample chain, added to the image.",
     PostStage::PrePass, kReadsColor, false, kBloom},
    {"motion_blur", "Motion blur",
     "Camera motion blur from depth and the previous view-projection (seed 002), optionally "
     "blended with the previous frame.",
     PostStage::Hdr, kReadsColor | kReadsDepth | kReadsCameraMotion | kReadsPreviousFrame, false,
     kMotionBlur},
    {"depth_of_field", "Depth of field",
     "Circle of confusion from the focal distance and range sets the blur radius: sharp, half and "
     "full maxBlur interpolated.",
     PostStage::Hdr, kReadsColor | kReadsDepth, false, kDof},
    {"toon", "Toon", "Luminance bands and an outline from depth and normal edges (seed 002).",
     PostStage::Hdr, kReadsColor | kReadsDepth | kReadsNormals, true, kToon},
    {"color_grading", "Colour grading",
     "Exposure, contrast, saturation, white balance, lift/gamma/gain.", PostStage::Hdr, kReadsColor,
     true, kColorGrading},
    {"paintbrush", "Paintbrush",
     "Curl-noise pre-pass orients elliptic strokes coloured from the image (seed 004).",
     PostStage::Paint, kReadsColor | kReadsTime, false, kPaintbrush},
    {"tonemap", "Tone mapping", "Exposure and a tone curve, or the OCIO display transform.",
     PostStage::ToneMap, kReadsColor, true, kToneMap},
    {"gaussian_blur", "Gaussian blur", "Separable gaussian, weights from G(x) (seed 001).",
     PostStage::Any, kReadsColor, false, kBlur},
    {"pixelate", "Pixelation", "Square cells of one colour (seed 000).", PostStage::Any,
     kReadsColor, false, kPixelate},
    {"chromatic_aberration", "Chromatic aberration", "Radial red/blue channel split.",
     PostStage::Any, kReadsColor, false, kChromaticAberration},
    {"vignette", "Vignette", "Darkens or tints the border (seed 001's six controls).",
     PostStage::Ldr, kReadsColor, true, kVignette},
    {"night_vision", "Night vision", "Green-weighted luminance, grain and vignetting (seed 000).",
     PostStage::Ldr, kReadsColor | kReadsTime, true, kNightVision},
    {"pointillism", "Pointillism", "Dots sized by darkness on paper (seed 004).", PostStage::Ldr,
     kReadsColor, false, kPointillism},
    {"vaporwave", "Vaporwave",
     "Desaturated purple tint, checker background, aberration, static, scanlines (seed 004).",
     PostStage::Ldr, kReadsColor | kReadsDepth | kReadsTime, false, kVaporwave},
    {"film_grain", "Film grain", "Animated luminance noise.", PostStage::Ldr,
     kReadsColor | kReadsTime, true, kFilmGrain},
    {"sharpen", "Sharpen", "Unsharp mask from the four neighbours.", PostStage::Ldr, kReadsColor,
     false, kSharpen},
    {"fxaa", "FXAA", "Fast approximate anti-aliasing (Lottes 2009).", PostStage::Ldr, kReadsColor,
     false, kFxaa},
}};

std::vector<std::string_view> catalogueTypes() {
    std::vector<std::string_view> names;
    for (const EffectMeta& m : kCatalogue)
        names.push_back(m.type);
    return names;
}

std::string effectLabel(const PostChain& chain, size_t i) {
    return "\"" + chain.effects[i].type + "\" (effects[" + std::to_string(i) + "])";
}

} // namespace

EffectId newEffectId() {
    static std::atomic<EffectId> next{1};
    return next.fetch_add(1, std::memory_order_relaxed);
}

long findEffectIndex(const PostChain& chain, EffectId id) {
    for (size_t i = 0; i < chain.effects.size(); ++i)
        if (chain.effects[i].id == id)
            return long(i);
    return -1;
}

std::vector<float> effectParamComponents(const ParamMeta& param, glm::vec3 value) {
    const glm::vec3 v = constrainParamValue(param, value);
    std::vector<float> out;
    for (int k = 0; k < paramComponents(param); ++k)
        out.push_back(v[k]);
    return out;
}

bool setEffectParam(PostChain& chain, EffectId id, std::string_view param, glm::vec3 value) {
    const long index = findEffectIndex(chain, id);
    if (index < 0)
        return false;
    EffectInstance& effect = chain.effects[size_t(index)];
    const EffectMeta* meta = findPostEffect(effect.type);
    const ParamMeta* p = meta ? findEffectParam(*meta, param) : nullptr;
    if (!p)
        return false;
    effect.params[std::string(param)] = effectParamComponents(*p, value);
    return true;
}

std::span<const EffectMeta> postEffectCatalogue() {
    return kCatalogue;
}

const EffectMeta* findPostEffect(std::string_view type) {
    for (const EffectMeta& m : kCatalogue)
        if (m.type == type)
            return &m;
    return nullptr;
}

int toneMapOperatorIndex(std::string_view name) {
    const EffectMeta* tonemap = findPostEffect("tonemap");
    const ParamMeta* op = tonemap ? findEffectParam(*tonemap, "operator") : nullptr;
    if (!op)
        return -1;
    for (size_t i = 0; i < op->choices.size(); ++i)
        if (op->choices[i] == name)
            return int(i);
    return -1;
}

const ParamMeta* findEffectParam(const EffectMeta& meta, std::string_view id) {
    for (const ParamMeta& p : meta.params)
        if (p.id == id)
            return &p;
    return nullptr;
}

int paramComponents(const ParamMeta& p) {
    return p.type == ParamType::Color ? 3 : 1;
}

std::string_view postStageName(PostStage stage) {
    switch (stage) {
    case PostStage::PrePass:
        return "pre-pass";
    case PostStage::Hdr:
        return "HDR";
    case PostStage::Paint:
        return "paint";
    case PostStage::ToneMap:
        return "tone mapping";
    case PostStage::Ldr:
        return "LDR";
    case PostStage::Any:
        return "any";
    }
    return "?";
}

std::string describeReads(unsigned reads) {
    static constexpr std::pair<unsigned, std::string_view> kNames[] = {
        {kReadsColor, "colour"},
        {kReadsDepth, "depth"},
        {kReadsNormals, "normals"},
        {kReadsPreviousFrame, "previous frame"},
        {kReadsCameraMotion, "camera motion"},
        {kReadsTime, "time"}};
    std::string out;
    for (const auto& [bit, name] : kNames)
        if (reads & bit)
            out += (out.empty() ? "" : ", ") + std::string(name);
    return out;
}

EffectInstance makeEffect(std::string_view type) {
    EffectInstance e;
    const EffectMeta* meta = findPostEffect(type);
    if (!meta)
        return e;
    e.type = std::string(type);
    for (const ParamMeta& p : meta->params) {
        std::vector<float> v;
        for (int k = 0; k < paramComponents(p); ++k)
            v.push_back(p.defaultValue[k]);
        e.params[std::string(p.id)] = std::move(v);
    }
    return e;
}

glm::vec3 effectValue(const EffectInstance& effect, const ParamMeta& param) {
    const auto it = effect.params.find(std::string(param.id));
    if (it == effect.params.end() || it->second.empty())
        return param.defaultValue;
    glm::vec3 v = param.defaultValue;
    const int n = paramComponents(param);
    for (int k = 0; k < n; ++k)
        v[k] = it->second[std::min<size_t>(size_t(k), it->second.size() - 1)];
    return v;
}

float effectFloat(const EffectInstance& effect, std::string_view id) {
    if (const EffectMeta* meta = findPostEffect(effect.type))
        if (const ParamMeta* p = findEffectParam(*meta, id))
            return effectValue(effect, *p).x;
    return 0.0f;
}

bool postChainReadsTime(const PostChain& chain) {
    return std::any_of(chain.effects.begin(), chain.effects.end(), [](const EffectInstance& e) {
        const EffectMeta* meta = findPostEffect(e.type);
        return e.enabled && meta && (meta->reads & kReadsTime);
    });
}

bool setEffectEnabled(PostChain& chain, size_t index, bool enabled) {
    if (index >= chain.effects.size())
        return false;
    chain.effects[index].enabled = enabled;
    return true;
}

bool moveEffect(PostChain& chain, size_t from, size_t to) {
    auto& e = chain.effects;
    if (from >= e.size() || to >= e.size())
        return false;
    if (from < to)
        std::rotate(e.begin() + long(from), e.begin() + long(from) + 1, e.begin() + long(to) + 1);
    else if (to < from)
        std::rotate(e.begin() + long(to), e.begin() + long(from), e.begin() + long(from) + 1);
    return true;
}

bool duplicateEffect(PostChain& chain, size_t index) {
    if (index >= chain.effects.size())
        return false;
    EffectInstance copy = chain.effects[index];
    copy.id = newEffectId();
    chain.effects.insert(chain.effects.begin() + long(index) + 1, copy);
    return true;
}

bool removeEffect(PostChain& chain, size_t index) {
    if (index >= chain.effects.size())
        return false;
    chain.effects.erase(chain.effects.begin() + long(index));
    return true;
}

std::vector<ChainIssue> checkStageOrder(const PostChain& chain) {
    std::vector<ChainIssue> issues;
    long toneMap = -1;
    // The latest-stage constrained effect seen so far: an effect of an earlier stage after it is
    // out of order.
    long latest = -1;
    for (size_t i = 0; i < chain.effects.size(); ++i) {
        const EffectMeta* meta = findPostEffect(chain.effects[i].type);
        if (!meta || meta->stage == PostStage::Any)
            continue;
        if (meta->stage == PostStage::ToneMap) {
            if (toneMap >= 0)
                issues.push_back(
                    {i, effectLabel(chain, i) + ": the chain already tone maps at " +
                            effectLabel(chain, size_t(toneMap)) +
                            "; a second tone mapping would compress display values again"});
            else
                toneMap = long(i);
        }
        if (latest >= 0) {
            const EffectMeta* prev = findPostEffect(chain.effects[size_t(latest)].type);
            if (meta->stage < prev->stage) {
                std::string why;
                switch (meta->stage) {
                case PostStage::PrePass:
                    why = "a pre-pass reads the lit image before HDR effects change it";
                    break;
                case PostStage::Hdr:
                case PostStage::Paint:
                    why = "it works on scene-linear HDR colour, before tone mapping";
                    break;
                case PostStage::ToneMap:
                    why = "LDR effects expect display values, which tone mapping produces";
                    break;
                default:
                    break;
                }
                issues.push_back(
                    {i, effectLabel(chain, i) + " is a " + std::string(postStageName(meta->stage)) +
                            " effect and must come before " + effectLabel(chain, size_t(latest)) +
                            " (" + std::string(postStageName(prev->stage)) + "): " + why +
                            " (order: pre-passes, HDR effects, paintbrush, tone "
                            "mapping, LDR effects)"});
                continue; // keep comparing later effects with the stage that was out of place
            }
        }
        latest = long(i);
    }
    return issues;
}

std::vector<ChainIssue> checkEffectParams(const PostChain& chain) {
    std::vector<ChainIssue> issues;
    const std::vector<std::string_view> types = catalogueTypes();
    for (size_t i = 0; i < chain.effects.size(); ++i) {
        const EffectInstance& e = chain.effects[i];
        const EffectMeta* meta = findPostEffect(e.type);
        if (!meta) {
            issues.push_back({i, "unknown effect type \"" + e.type + "\"" +
                                     didYouMean(e.type, types) + "; known: " + listNames(types)});
            continue;
        }
        for (const auto& [id, values] : e.params) {
            const ParamMeta* p = findEffectParam(*meta, id);
            if (!p) {
                std::vector<std::string_view> ids;
                for (const ParamMeta& q : meta->params)
                    ids.push_back(q.id);
                issues.push_back({i, "\"" + std::string(meta->type) + "\" has no parameter \"" +
                                         id + "\"" + didYouMean(id, ids)});
                continue;
            }
            if (int(values.size()) != paramComponents(*p)) {
                issues.push_back({i, "\"" + id + "\" expects " +
                                         std::to_string(paramComponents(*p)) + " number(s), got " +
                                         std::to_string(values.size())});
                continue;
            }
            for (float v : values)
                if (!(v >= p->min && v <= p->max)) {
                    issues.push_back({i, "\"" + id + "\" expects " +
                                             closedRange(p->min, p->max).describe() + ", got " +
                                             formatNumber(v)});
                    break;
                }
        }
    }
    return issues;
}

std::string postEffectCatalogueMarkdown() {
    auto number = [](float v) { return formatNumber(double(v)); };
    auto value = [&](const ParamMeta& p, glm::vec3 v) {
        if (p.type == ParamType::Choice)
            return "`" + std::string(p.choices[size_t(std::lround(v.x))]) + "`";
        if (p.type == ParamType::Color)
            return "(" + number(v.x) + ", " + number(v.y) + ", " + number(v.z) + ")";
        return number(v.x);
    };
    std::string s;
    for (const EffectMeta& m : kCatalogue) {
        s += "### " + std::string(m.label) + " (`" + std::string(m.type) + "`)\n\n";
        s += std::string(m.description) + "\n\n";
        s += "Stage: " + std::string(postStageName(m.stage)) +
             ". Reads: " + describeReads(m.reads) + ". " +
             (m.pointwise ? "Pointwise: fused with neighbouring pointwise effects into one pass."
                          : "Own pass(es).") +
             "\n\n";
        s += "| Parameter | Label | Range | Default | Unit | Description |\n"
             "|---|---|---|---|---|---|\n";
        for (const ParamMeta& p : m.params) {
            std::string range;
            if (p.type == ParamType::Choice) {
                for (std::string_view c : p.choices) {
                    range.append(range.empty() ? "`" : ", `");
                    range.append(c);
                    range.append("`");
                }
            } else {
                range = "[" + number(p.min) + ", " + number(p.max) + "]" +
                        (p.type == ParamType::Color ? " per channel" : "");
            }
            s += "| `" + std::string(p.id) + "` | " + std::string(p.label) + " | " + range + " | " +
                 value(p, p.defaultValue) + " | " + std::string(p.unit) + " | " +
                 std::string(p.tooltip) + " |\n";
        }
        s += "\n";
    }
    return s;
}

PostChain defaultPostChain() {
    PostChain c;
    c.effects = {makeEffect("bloom"), makeEffect("tonemap"), makeEffect("vignette"),
                 makeEffect("fxaa")};
    c.effects[1].params["operator"] = {1.0f}; // ACES fitted
    return c;
}

} // namespace velvet

#include "core/scene_fields.h"

#include <array>

namespace velvet {
namespace {

template <class S>
Field<S> number(std::string_view key, float S::*m, NumberRange r, std::string_view d) {
    Field<S> f;
    f.key = key;
    f.kind = FieldKind::Number;
    f.range = r;
    f.number = m;
    f.description = d;
    return f;
}

template <class S>
Field<S> vec3(std::string_view key, glm::vec3 S::*m, NumberRange r, std::string_view d) {
    Field<S> f;
    f.key = key;
    f.kind = FieldKind::Vec3;
    f.range = r;
    f.vec3 = m;
    f.description = d;
    return f;
}

template <class S>
Field<S> vec2(std::string_view key, glm::vec2 S::*m, NumberRange r, std::string_view d) {
    Field<S> f;
    f.key = key;
    f.kind = FieldKind::Vec2;
    f.range = r;
    f.vec2 = m;
    f.description = d;
    return f;
}

template <class S>
Field<S> flag(std::string_view key, bool S::*m, std::string_view d) {
    Field<S> f;
    f.key = key;
    f.kind = FieldKind::Bool;
    f.flag = m;
    f.description = d;
    return f;
}

template <class S>
Field<S> text(std::string_view key, FieldKind kind, std::string S::*m, std::string_view d) {
    Field<S> f;
    f.key = key;
    f.kind = kind;
    f.text = m;
    f.description = d;
    return f;
}

template <class S>
Field<S> choice(std::string_view key, std::span<const std::string_view> names, int (*get)(const S&),
                void (*set)(S&, int), std::string_view d) {
    Field<S> f;
    f.key = key;
    f.kind = FieldKind::Choice;
    f.choices = names;
    f.getChoice = get;
    f.setChoice = set;
    f.description = d;
    return f;
}

template <class S>
Field<S> onlyWhen(Field<S> f, bool (*relevant)(const S&)) {
    f.relevant = relevant;
    return f;
}

// Every physical quantity is bounded by what the renderer can carry (docs/file-formats.md,
// "Bounds"): it computes in 32-bit floats and stores scene-linear radiance in half floats
// (RGBA16F HDR buffer and environment maps, largest finite value 65504; IEEE 754-2008 binary16).
// Lengths and positions stay within a million metres and above a tenth of a millimetre, where
// float32 still resolves the preview mesh (spacing 0.06 m at 1e6) and a squared length neither
// overflows nor flushes to zero; angles that wrap stay within 100 000 degrees (float32 spacing
// 1/128 degree there; the editor wraps them into (-360, 360) anyway).
const NumberRange kPosition = closedRange(-1e6, 1e6);
const NumberRange kLength = closedRange(1e-4, 1e6);
const NumberRange kWrappingAngle = closedRange(-1e5, 1e5);
// Scene-linear colours and multipliers of radiance: at most the half-float maximum, so a colour
// the HDR buffer cannot hold is refused where it is typed rather than rendered as infinity.
const NumberRange kRadiance = closedRange(0, kMaxSceneRadiance);
// Photometric intensities: lux, candela, nits or a multiplier. The sun gives about 1.2e5 lux;
// 1e6 times a colour of 65504 still multiplies to a finite float32 in every light equation.
const NumberRange kIntensity = closedRange(0, 1e6);
const NumberRange kCone = closedRange(0, 90);

bool isSpot(const Light& l) {
    return l.type == LightType::Spot;
}
bool isArea(const Light& l) {
    return l.type == LightType::Area;
}
bool hasPosition(const Light& l) {
    return l.type == LightType::Point || l.type == LightType::Spot || l.type == LightType::Area;
}
bool hasDirection(const Light& l) {
    return l.type == LightType::Directional || l.type == LightType::Spot ||
           l.type == LightType::Area;
}
bool castsShadows(const Light& l) {
    return l.type != LightType::Ambient;
}
bool isDirectional(const Light& l) {
    return l.type == LightType::Directional;
}
bool isPointOrSpot(const Light& l) {
    return l.type == LightType::Point || l.type == LightType::Spot;
}
bool never(const Light&) {
    return false;
}

// Angles that wrap (yaw, environment rotation) take any value within kWrappingAngle: an orbiting
// camera may have turned several times, and refusing its saved state would lose the user's work.
const std::array<Field<Camera>, 9> kCamera{
    vec3("target", &Camera::target, kPosition, "Point the camera orbits and looks at, in metres."),
    number("yaw", &Camera::yawDeg, kWrappingAngle,
           "Rotation about +Y in degrees; 0 looks down -Z."),
    number("pitch", &Camera::pitchDeg, closedRange(-90, 90),
           "Elevation in degrees; positive looks down on the target."),
    number("distance", &Camera::distance, kLength, "Distance from the target in metres."),
    number("fovY", &Camera::fovYDeg, NumberRange{1, 179, true, true},
           "Vertical field of view in degrees (perspective)."),
    number("near", &Camera::nearPlane, kLength, "Near clip distance in metres."),
    number("far", &Camera::farPlane, kLength,
           "Far clip distance in metres; must be greater than near."),
    flag("orthographic", &Camera::orthographic, "Orthographic instead of perspective projection."),
    number("orthoHeight", &Camera::orthoHeight, kLength,
           "Visible height in metres (orthographic)."),
};

const std::array<Field<Light>, 14> kLight = [] {
    auto typeField = choice<Light>(
        "type", lightTypeNames(), [](const Light& l) { return static_cast<int>(l.type); },
        [](Light& l, int i) { l.type = static_cast<LightType>(i); },
        "Directional (lux), point and spot (candela), area (nits), ambient (multiplier).");
    typeField.required = true;
    return std::array<Field<Light>, 14>{
        typeField,
        onlyWhen(text("name", FieldKind::Text, &Light::name, "Shown in the light list."), never),
        vec3("color", &Light::color, kRadiance, "Scene-linear Rec.709 colour."),
        number("intensity", &Light::intensity, kIntensity,
               "Lux (directional), candela (point, spot), nits (area), multiplier (ambient)."),
        onlyWhen(vec3("position", &Light::position, kPosition, "Position in metres."), hasPosition),
        onlyWhen(vec3("direction", &Light::direction, kPosition,
                      "The way the light travels (need not be normalised, must not be zero)."),
                 hasDirection),
        onlyWhen(number("range", &Light::range, kLength, "Influence radius in metres."),
                 hasPosition),
        onlyWhen(number("innerCone", &Light::innerConeDeg, kCone,
                        "Half-angle in degrees of full intensity; at most outerCone."),
                 isSpot),
        onlyWhen(number("outerCone", &Light::outerConeDeg, kCone,
                        "Half-angle in degrees beyond which the spot is dark."),
                 isSpot),
        onlyWhen(choice<Light>(
                     "shape", areaShapeNames(),
                     [](const Light& l) { return static_cast<int>(l.shape); },
                     [](Light& l, int i) { l.shape = static_cast<AreaShape>(i); },
                     "Shape of an area light."),
                 isArea),
        onlyWhen(vec2("size", &Light::size, kLength,
                      "Area light: radius (sphere, first number) or width and height in metres."),
                 isArea),
        onlyWhen(flag("castShadows", &Light::castShadows,
                      "Casts shadows from the preview mesh (the strongest few lights do; "
                      "docs/shadows.md)."),
                 castsShadows),
        onlyWhen(number("sourceAngle", &Light::sourceAngleDeg, closedRange(0, 20),
                        "Directional: angular diameter of the source in degrees (soft shadows)."),
                 isDirectional),
        onlyWhen(number("sourceRadius", &Light::sourceRadius, closedRange(0, 10),
                        "Point and spot: radius of the source in metres (soft shadows)."),
                 isPointOrSpot),
    };
}();

bool hasPlainGround(const Environment& e) {
    return e.ground == GroundMode::Plain;
}

const std::array<Field<Environment>, 11> kEnvironment{
    onlyWhen(
        text("hdri", FieldKind::Path, &Environment::hdri,
             "Equirectangular HDR or EXR image; empty for a uniform colour."),
        +[](const Environment& e) { return !e.hdri.empty(); }),
    onlyWhen(
        vec3("color", &Environment::color, kRadiance,
             "Uniform scene-linear radiance when there is no HDRI."),
        +[](const Environment& e) { return e.hdri.empty(); }),
    number("intensity", &Environment::intensity, kRadiance,
           "Multiplier on the environment's radiance."),
    number("rotation", &Environment::rotationDeg, kWrappingAngle, "Rotation about +Y in degrees."),
    choice<Environment>(
        "background", backgroundModeNames(),
        [](const Environment& e) { return static_cast<int>(e.background); },
        [](Environment& e, int i) { e.background = static_cast<BackgroundMode>(i); },
        "What is seen behind the mesh."),
    onlyWhen(
        vec3("backgroundColor", &Environment::backgroundColor, kRadiance,
             "Scene-linear colour of the solid-color background."),
        +[](const Environment& e) { return e.background == BackgroundMode::SolidColor; }),
    choice<Environment>(
        "ground", groundModeNames(),
        [](const Environment& e) { return static_cast<int>(e.ground); },
        [](Environment& e, int i) { e.ground = static_cast<GroundMode>(i); },
        "A floor under the mesh at its lowest point: off, a shadow catcher (the background shows "
        "through, darkened by shadows and occlusion) or a plain material."),
    onlyWhen(vec3("groundColor", &Environment::groundColor, closedRange(0, 1),
                  "Scene-linear albedo of the plain ground."),
             hasPlainGround),
    onlyWhen(number("groundRoughness", &Environment::groundRoughness, closedRange(0, 1),
                    "Perceptual roughness of the plain ground."),
             hasPlainGround),
    flag("ambientOcclusion", &Environment::ambientOcclusion,
         "Screen-space ambient occlusion (GTAO) on the environment's light."),
    number("occlusionRadius", &Environment::occlusionRadius, closedRange(0.01, 10),
           "World-space radius of the ambient occlusion search in metres."),
};

const std::array<Field<MeshRef>, 2> kMesh{
    choice<MeshRef>(
        "kind", previewMeshKindNames(), [](const MeshRef& m) { return static_cast<int>(m.kind); },
        [](MeshRef& m, int i) { m.kind = static_cast<PreviewMeshKind>(i); },
        "Built-in preview mesh, or custom to load `file`."),
    onlyWhen(
        text("file", FieldKind::Path, &MeshRef::file,
             "Mesh file for kind custom (OBJ, FBX, glTF, … through Assimp)."),
        +[](const MeshRef& m) { return m.kind == PreviewMeshKind::Custom; }),
};

} // namespace

std::span<const Field<Camera>> cameraFields() {
    return kCamera;
}
std::span<const Field<Light>> lightFields() {
    return kLight;
}
std::span<const Field<Environment>> environmentFields() {
    return kEnvironment;
}
std::span<const Field<MeshRef>> meshFields() {
    return kMesh;
}

} // namespace velvet

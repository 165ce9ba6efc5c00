// The environment: equirectangular radiance (mip-mapped) and its SH9 irradiance.
#include "common_math.glsl"
#include "common_frame.glsl"

layout(binding = BINDING_ENVIRONMENT_TEX) uniform sampler2D uEnvironment;

// Direction of equirect coordinates (u, v), v = 0 at +Y, u = 0.5 looking down -Z.
// Must match velvet::equirectDirection() in core/spherical_harmonics.cpp.
vec3 equirectDirection(vec2 uv) {
    float phi = (uv.x - 0.5) * 2.0 * PI;
    float theta = uv.y * PI;
    return vec3(sin(theta) * sin(phi), cos(theta), -sin(theta) * cos(phi));
}
vec2 equirectUv(vec3 d) {
    return vec2(0.5 + atan(d.x, -d.z) / (2.0 * PI), acos(clamp(d.y, -1.0, 1.0)) / PI);
}

// World direction -> environment direction (the environment is rotated about +Y).
vec3 toEnvironment(vec3 d) {
    float c = frame.envParams.x, s = frame.envParams.y;
    return vec3(c * d.x - s * d.z, d.y, s * d.x + c * d.z);
}

// Radiance arriving from world direction d, blurred to mip level lod; intensity applied.
vec3 environmentRadiance(vec3 d, float lod) {
    vec2 uv = equirectUv(toEnvironment(d));
    return textureLod(uEnvironment, uv, lod).rgb * frame.envParams.z + frame.ambientRadiance.rgb;
}

// Ramamoorthi & Hanrahan 2001, "An Efficient Representation for Irradiance Environment Maps"
// E(n) / pi, so that a uniform radiance L gives L. Mirrors evalIrradianceOverPi() in
// core/spherical_harmonics.cpp; frame.envSh already carries the intensity.
vec3 irradianceOverPi(vec3 nWorld) {
    vec3 n = toEnvironment(nWorld);
    vec3 e = frame.envSh[0].rgb * 0.282095;
    e += (2.0 / 3.0) * 0.488603 * (frame.envSh[1].rgb * n.y + frame.envSh[2].rgb * n.z +
                                   frame.envSh[3].rgb * n.x);
    e += 0.25 * (frame.envSh[4].rgb * (1.092548 * n.x * n.y) +
                 frame.envSh[5].rgb * (1.092548 * n.y * n.z) +
                 frame.envSh[6].rgb * (0.315392 * (3.0 * n.z * n.z - 1.0)) +
                 frame.envSh[7].rgb * (1.092548 * n.x * n.z) +
                 frame.envSh[8].rgb * (0.546274 * (n.x * n.x - n.y * n.y)));
    return max(e, vec3(0.0)) + frame.ambientRadiance.rgb;
}

// Mip level whose texel footprint roughly matches a GGX lobe of width alpha (an approximation:
// the renderer issue replaces this with a GGX-prefiltered cubemap).
float specularLod(float perceptualRoughness) {
    float alpha = perceptualRoughness * perceptualRoughness;
    return clamp(log2(max(alpha * frame.post.z / PI, 1e-6)), 0.0, frame.envParams.w);
}

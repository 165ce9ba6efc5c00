// Ambient occlusion turned into the light that still arrives: the screen-space occlusion of the
// environment's light with the light its cavities' walls bounce back (lighting.frag), and the
// light the part of a reflection's lobe that the mesh hides brings from the mesh itself
// (meshReflection, below; the occlusion is mesh_visibility.glsl's).
#include "common_math.glsl"

// Jimenez et al. 2016, "Practical Real-Time Strategies for Accurate Indirect Occlusion"
// (section 5, eq. 10): the light that bounces between the occluding parts of the surface,
// fitted against ray-traced multiple bounces, per albedo: a cavity's walls light its floor. The
// fit reaches 1.0005 at full visibility: held to 1, so an open point keeps exactly its light.
// (It goes to 0 at no visibility whatever the albedo, so for the specular occlusion, whose
// closed lobes see the mesh rather than a cavity's floor, meshReflection replaced it: a white
// metal's closed lobes stay white in a white furnace.)
vec3 multiBounceOcclusion(float visibility, vec3 albedo) {
    vec3 a = 2.0404 * albedo - 0.3324;
    vec3 b = -4.7951 * albedo + 0.6417;
    vec3 c = 2.7552 * albedo + 0.6903;
    float x = visibility;
    return min(max(vec3(x), ((x * a + b) * x + c) * x), vec3(1.0));
}

// The light a reflection brings from the part of the surface the occlusion hides (lighting.frag):
// that part reflects its surroundings with the surface's own @p albedo (its directional albedo:
// diffuse and specular, what a white furnace reads), and hides part of them in turn. Taking the
// hidden part to see a share s of its sky, each bounce keeps albedo x s of the light and passes
// albedo x (1 - s) on, a geometric series: surroundings x albedo s / (1 - albedo (1 - s)), exactly
// the surroundings for albedo 1 (a white furnace stays white however often the light bounces)
// and little for a dark surface. s = MESH_REFLECTION_OPEN_SHARE, the mean open share of the
// shader ball's vertices (render/mesh_visibility.h); @p surroundings the irradiance over pi
// about the normal.
const float MESH_REFLECTION_OPEN_SHARE = 0.5;
vec3 meshReflection(vec3 surroundings, vec3 albedo) {
    vec3 a = min(albedo, vec3(1.0));
    return surroundings * a * MESH_REFLECTION_OPEN_SHARE /
           max(1.0 - a * (1.0 - MESH_REFLECTION_OPEN_SHARE), vec3(1e-4));
}

// Ambient occlusion turned into the light that still arrives: shared by the mesh's own visibility
// (mesh_visibility.glsl, the specular occlusion) and the screen-space occlusion of the
// environment's light (lighting.frag).
#include "common_math.glsl"

// Jimenez et al. 2016, "Practical Real-Time Strategies for Accurate Indirect Occlusion"
// (section 5, eq. 10): the light that bounces between the occluding parts of the surface,
// fitted against ray-traced multiple bounces, per albedo. They apply it to specular occlusion
// with F0 as the albedo: what a reflection meets of the mesh reflects the environment too; on the
// screen-space occlusion the albedo is the base colour: a cavity's walls light its floor. The fit
// reaches 1.0005 at full visibility: held to 1, so an open point keeps exactly its light.
vec3 multiBounceOcclusion(float visibility, vec3 albedo) {
    vec3 a = 2.0404 * albedo - 0.3324;
    vec3 b = -4.7951 * albedo + 0.6417;
    vec3 c = 2.7552 * albedo + 0.6903;
    float x = visibility;
    return min(max(vec3(x), ((x * a + b) * x + c) * x), vec3(1.0));
}

// Debug views: the ids (DEBUG_FINAL .. DEBUG_CLEARCOAT_ONLY, render::DebugView's numbers) and
// isLightView() / isLobeView() are generated into render_interface.glsl (render/renderer.h
// documents what each view shows). Raw values go to the linear image; debugDisplay() maps them
// for the display image.
#include "common_math.glsl"
#include "common_frame.glsl"


// Heat map for lights per pixel: black at 0, then blue, cyan, green, yellow, red at 32 and above.
vec3 heatMap(float count) {
    if (count <= 0.0)
        return vec3(0.0);
    float t = clamp(count / 32.0, 0.0, 1.0) * 4.0;
    vec3 c = t < 1.0   ? mix(vec3(0.0, 0.0, 1.0), vec3(0.0, 1.0, 1.0), t)
             : t < 2.0 ? mix(vec3(0.0, 1.0, 1.0), vec3(0.0, 1.0, 0.0), t - 1.0)
             : t < 3.0 ? mix(vec3(0.0, 1.0, 0.0), vec3(1.0, 1.0, 0.0), t - 2.0)
                       : mix(vec3(1.0, 1.0, 0.0), vec3(1.0, 0.0, 0.0), t - 3.0);
    return c;
}

// Display mapping of the views above (display_output.frag); false for the views it leaves alone.
// Colour-like views come back display-linear with @p encode set: the caller encodes them with
// the display's OCIO encoding (displayEncode), as the final view; the false-colour maps (heat
// map, material id hues) are already display values.
bool debugDisplay(int view, vec3 c, float exposure, out vec3 display, out bool encode) {
    encode = false;
    if (view == DEBUG_LIGHTS_PER_PIXEL) {
        display = heatMap(c.x);
    } else if (view == DEBUG_MATERIAL_ID) {
        // A distinct hue per id (golden-ratio hash); id 0 grey.
        float h = fract(c.x * 0.61803399);
        display = c.x < 0.5 ? vec3(0.25)
                            : clamp(abs(fract(h + vec3(0.0, 2.0, 1.0) / 3.0) * 6.0 - 3.0) - 1.0, 0.0, 1.0);
    } else if (view == DEBUG_SPECULAR || view == DEBUG_SHEEN || view == DEBUG_EMISSIVE) {
        display = c;
        encode = true;
    } else if (view == DEBUG_ANISOTROPY) {
        display = c * 0.5 + 0.5; // the direction as a colour, like the normal view; grey: none
    } else if (isLobeView(view)) {
        display = c * exposure / (1.0 + c * exposure); // Reinhard: comparable lobes
        encode = true;
    } else {
        return false;
    }
    return true;
}

#version 450 core
// One triangle covering the viewport; no vertex buffer (gl_VertexID 0..2).
void main() {
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
#ifdef FULLSCREEN_FAR_PLANE
    // On the far plane (window depth exactly 1.0), for a depth test against a G-buffer depth.
    gl_Position = vec4(p * 2.0 - 1.0, 1.0, 1.0);
#else
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
#endif
}

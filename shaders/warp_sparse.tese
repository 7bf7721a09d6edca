#version 410 core
// Sparse mesh, tessellation evaluation: each generated vertex is a source pixel of the patch
// (equal spacing at level uPatchSize lands exactly on pixel centres), warped like the full
// mesh's vertices.

layout(quads, equal_spacing, ccw) in;

patch in vec2 tcOrigin;
uniform int uPatchSize;

out vec3 vSourceH;
out vec3 vSourceWorld;

void main() {
    ivec2 pixel = ivec2(tcOrigin) + ivec2(round(gl_TessCoord.xy * float(uPatchSize)));
    pixel = min(pixel, ivec2(uSize));  // the last patches overhang the outer ring: fold them onto it
    WarpedPoint w = warpPixel(pixel);
    vSourceH = w.sourceH;
    vSourceWorld = w.sourceWorld;
    gl_Position = w.clip;
}

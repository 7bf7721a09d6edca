#version 410 core
// Warp, sparse mesh (seed 004 section 5.2.6): four control points per patch of
// uPatchSize x uPatchSize source pixels; every control point carries the patch's origin
// pixel, the tessellation evaluation stage places the vertices.

uniform int uPatchSize;
uniform ivec2 uPatchCount;

out vec2 vOrigin;

void main() {
    int patchIndex = gl_VertexID / 4;
    ivec2 patchCoord = ivec2(patchIndex % uPatchCount.x, patchIndex / uPatchCount.x);
    // The patch grid starts one pixel outside the image, like the full mesh's outer ring.
    vOrigin = vec2(patchCoord * uPatchSize - 1);
}

#version 410 core
// Sparse mesh, tessellation control: a patch where the patch flags pass found a depth (or
// velocity) discontinuity that this warp opens (warp_patch_flags.frag) is subdivided back to full resolution in both directions, so its
// triangles are the full mesh's, one pixel square, and the disocclusion fix (warp_fix.geom)
// finds the same sheets in it as on the full mesh. Subdividing only along the jump, as
// this shader once did, left one-pixel-wide slivers a whole patch long across it: the fix cannot
// tell those from a surface seen at a grazing angle, so the revealed background showed their
// smear. An edge is subdivided when either patch beside it is, decided alike from both
// sides, so the two tessellations meet vertex for vertex: no cracks.
// llvmpipe (Mesa 22.3, src/gallium/auxiliary/draw/draw_tess.c) indexes the vertices it
// tessellates for each run of 1024 patches with 16 bits: past 65,536 in a run, triangles join
// the wrong vertices. A dense patch has (N + 1)^2 vertices: 25 and 81 for sparse4 and sparse8
// stay far below, but 289 for sparse16 overflow once about a fifth of a run is dense (seen
// from 960x540 up). Drawing sparse16 in batches of at most 200 patches would avoid it.

layout(vertices = 4) out;

in vec2 vOrigin[];
patch out vec2 tcOrigin;

uniform sampler2D uPatchFlags;  // r: a jump between neighbouring pixels of the patch that the warp opens
uniform int uPatchSize;
uniform ivec2 uPatchCount;

bool dense(ivec2 patchCoord) {
    if (any(lessThan(patchCoord, ivec2(0))) || any(greaterThanEqual(patchCoord, uPatchCount))) return false;
    return texelFetch(uPatchFlags, patchCoord, 0).r > 0.5;
}

void main() {
    if (gl_InvocationID == 0) {
        // The patch's coordinate from its origin, not from gl_PrimitiveID: llvmpipe restarts
        // gl_PrimitiveID every 1024 patches of a draw, so every patch after the first 1024 read
        // another patch's flags (sparse8 draws 47,107 for 1920x1080 with its guard band).
        ivec2 p = (ivec2(vOrigin[0]) + 1) / uPatchSize;
        bool self = dense(p);
        float full = float(uPatchSize);
        gl_TessLevelInner[0] = self ? full : 1.0;                               // along x (u)
        gl_TessLevelInner[1] = self ? full : 1.0;                               // along y (v)
        gl_TessLevelOuter[0] = self || dense(p + ivec2(-1, 0)) ? full : 1.0;   // edge u = 0, runs along y
        gl_TessLevelOuter[1] = self || dense(p + ivec2(0, -1)) ? full : 1.0;   // edge v = 0, runs along x
        gl_TessLevelOuter[2] = self || dense(p + ivec2(1, 0)) ? full : 1.0;    // edge u = 1
        gl_TessLevelOuter[3] = self || dense(p + ivec2(0, 1)) ? full : 1.0;    // edge v = 1
        tcOrigin = vOrigin[0];
    }
    gl_out[gl_InvocationID].gl_Position = vec4(0.0);
}

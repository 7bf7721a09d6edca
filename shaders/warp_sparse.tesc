#version 410 core
// Sparse mesh, tessellation control: subdivide a patch back to full resolution only where
// the depth map has discontinuities -- along x where horizontal neighbours differ, along y
// where vertical ones do (the patch flags pass found them). An edge shared with a neighbour
// takes the same level from both sides (this patch's or the neighbour's flag in the edge's
// direction), so the two tessellations meet vertex for vertex: no cracks.

layout(vertices = 4) out;

in vec2 vOrigin[];
patch out vec2 tcOrigin;

uniform sampler2D uPatchFlags;  // r: discontinuity between horizontal neighbours, g: vertical
uniform int uPatchSize;
uniform ivec2 uPatchCount;

vec2 flagsAt(ivec2 p) {
    if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, uPatchCount))) return vec2(0.0);
    return texelFetch(uPatchFlags, p, 0).rg;
}

void main() {
    if (gl_InvocationID == 0) {
        ivec2 p = ivec2(gl_PrimitiveID % uPatchCount.x, gl_PrimitiveID / uPatchCount.x);
        vec2 self = flagsAt(p);
        vec2 left = flagsAt(p + ivec2(-1, 0)), right = flagsAt(p + ivec2(1, 0));
        vec2 below = flagsAt(p + ivec2(0, -1)), above = flagsAt(p + ivec2(0, 1));
        float full = float(uPatchSize);
        gl_TessLevelInner[0] = self.r > 0.5 ? full : 1.0;                  // along x (u)
        gl_TessLevelInner[1] = self.g > 0.5 ? full : 1.0;                  // along y (v)
        gl_TessLevelOuter[0] = max(self.g, left.g) > 0.5 ? full : 1.0;    // edge u = 0, runs along y
        gl_TessLevelOuter[1] = max(self.r, below.r) > 0.5 ? full : 1.0;   // edge v = 0, runs along x
        gl_TessLevelOuter[2] = max(self.g, right.g) > 0.5 ? full : 1.0;   // edge u = 1
        gl_TessLevelOuter[3] = max(self.r, above.r) > 0.5 ? full : 1.0;   // edge v = 1
        tcOrigin = vOrigin[0];
    }
    gl_out[gl_InvocationID].gl_Position = vec4(0.0);
}

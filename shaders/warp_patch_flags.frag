#version 410 core
// One fragment per sparse-mesh patch: must it be drawn at full density in this warp (r)?
// Only where the source depth (or velocity) jumps between horizontal or vertical neighbours
// inside the patch, and only where the warp moves neighbouring pixels of the patch apart.
// Linear eye depths are compared relative to the nearer one, so a wall far away and a crate
// close by are judged alike; a velocity jump counts too, or a moving object resting against a
// static one at the same depth would be stretched across their boundary. A jump whose two
// sides move together (the identity warp, a camera turn, anything far enough for parallax to
// stay under a quarter pixel) is mapped exactly enough by the patch's two triangles, and no
// full-mesh triangle there would open for the disocclusion fix either (below): it needs no
// triangles of its own. That keeps the sparse meshes sparse: at 1920x1080 the jumps of a
// moving sphere and of the hallway's edges alone made sparse8 draw 524k triangles.
// Needs warp_common.glsl (the warp's uniforms and warpPixel) before it.

uniform vec2 uTargetSize;  // display pixels
uniform int uPatchSize;
uniform float uNear;
uniform float uFar;
uniform float uDepthThreshold;     // relative
uniform float uVelocityThreshold;  // m/s

layout(location = 0) out vec4 outFlags;

const int kMaxPatchSize = 16;  // warp-sparse16's, the largest the registry makes

float linearDepth(float d) {
    float ndc = 2.0 * d - 1.0;
    return 2.0 * uNear * uFar / (uFar + uNear - ndc * (uFar - uNear));
}

bool jump(float za, vec3 va, float zb, vec3 vb) {
    return abs(za - zb) > uDepthThreshold * min(za, zb) || distance(va, vb) > uVelocityThreshold;
}

// The fix recolours a sheet only if it opens: its longest side grows by more than half a pixel
// (kOpensPx in warp_fix.geom). Where every pair of horizontal or vertical neighbours moves
// apart by at most a quarter pixel, a diagonal pair moves by at most half one, so no full-mesh
// triangle in the patch opens and the fix would change nothing there.
const float kMovesApartPx = 0.25;

// Where a source pixel lands in the display, in display pixels, as the mesh places it (the
// guard band's constant offset cancels in the differences below). False behind the eye.
bool landing(ivec2 pixel, out vec2 at) {
    vec4 clip = warpPixel(pixel).clip;
    at = clip.xy / clip.w * 0.5 * uTargetSize;
    return clip.w > 0.0;
}

// The patch's (N + 1) x (N + 1) vertices, row by row, each against its left neighbour and the
// one below it: does any pair move apart in this warp? A vertex behind the eye counts as
// moving apart, as the fix treats a sheet reaching there as open.
bool movesApart(ivec2 origin) {
    vec2 below[kMaxPatchSize + 1];
    for (int j = 0; j <= uPatchSize; ++j) {
        vec2 left = vec2(0.0);
        for (int i = 0; i <= uPatchSize; ++i) {
            vec2 at;
            // The last patches overhang the outer ring; the evaluation stage folds them onto it.
            ivec2 pixel = min(origin + ivec2(i, j), ivec2(uSize));
            if (!landing(pixel, at)) return true;
            vec2 moved = at - vec2(pixel);
            if (i > 0 && distance(moved, left) > kMovesApartPx) return true;
            if (j > 0 && distance(moved, below[i]) > kMovesApartPx) return true;
            left = moved;
            below[i] = moved;
        }
    }
    return false;
}

void main() {
    // The patch's (N + 1) x (N + 1) pixels, its vertices, from one before its origin: every
    // pair of horizontal or vertical neighbours among them. Pairs on a shared edge row or
    // column count for both patches beside it, as either patch's triangles may span them.
    // Each pixel is read once, row by row, against its left neighbour and the one below it
    // (kept from the previous row): the pass reads a quarter of what testing each pair
    // afresh would.
    ivec2 origin = ivec2(gl_FragCoord.xy) * uPatchSize - 1;
    ivec2 last = ivec2(uSize) - 1;
    float zBelow[kMaxPatchSize + 1];
    vec3 vBelow[kMaxPatchSize + 1];
    bool discontinuity = false;
    for (int j = 0; j <= uPatchSize && !discontinuity; ++j) {
        float zLeft = 0.0;
        vec3 vLeft = vec3(0.0);
        for (int i = 0; i <= uPatchSize && !discontinuity; ++i) {
            ivec2 p = clamp(origin + ivec2(i, j), ivec2(0), last);
            float z = linearDepth(texelFetch(uSourceDepth, p, 0).r);
            vec3 v = texelFetch(uSourceVelocity, p, 0).xyz;
            discontinuity = (i > 0 && jump(zLeft, vLeft, z, v)) || (j > 0 && jump(zBelow[i], vBelow[i], z, v));
            zLeft = z;
            vLeft = v;
            zBelow[i] = z;
            vBelow[i] = v;
        }
    }
    outFlags = vec4(discontinuity && movesApart(origin) ? 1.0 : 0.0, 0.0, 0.0, 1.0);
}

#version 410 core
// One fragment per sparse-mesh patch: does the source depth (or velocity) jump between
// horizontal or vertical neighbours anywhere inside the patch (r)? Linear eye depths are
// compared relative to the nearer one, so a wall far away and a crate close by are judged
// alike; a velocity jump counts too, or a moving object resting against a static one at the
// same depth would be stretched across their boundary.

uniform sampler2D uSourceDepth;
uniform sampler2D uSourceVelocity;
uniform vec2 uSize;
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
    outFlags = vec4(discontinuity ? 1.0 : 0.0, 0.0, 0.0, 1.0);
}

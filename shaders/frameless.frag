#version 410 core
// Adaptive frameless sampling: the displayed pixel from the deep buffer by the adaptive
// space-time filter (seed 002, section 5.1). Its support is sized as if reconstructing a regular
// sampling at the cell's sample density, and its shape set so that colour changes as much across
// its spatial extent S as across its temporal extent T (S * dC/ds = T * dC/dt, section 4.1): a
// sharp, older-sample-using filter where the scene is still, a blurred but current one where it
// moves. Weights: Gaussian in distance (sigma S), exponential in the sample's age (scale T).

uniform sampler2D uDeep;    // rgb colour, a: when made (s), < 0: none
uniform sampler2D uStats;   // per cell (frameless_stats.frag)
uniform usampler2D uIds;    // this frame's geometry pass: the ids shown
uniform int uCell;
uniform float uTime;
uniform float uRefreshHz;   // display frames per second
uniform float uFreshPerPixel;  // samples per pixel per frame over the whole frame (the budget)
uniform usampler2D uCounts;    // per cell: samples placed this frame

layout(location = 0) out vec4 outColour;
layout(location = 1) out uint outId;
layout(location = 2) out vec4 outCorrespondence;

const int kRadius = 2;  // a 5 x 5 gather: S is kept within it

void main() {
    ivec2 size = textureSize(uDeep, 0);
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 cell = p / uCell;
    vec4 stats = texelFetch(uStats, cell, 0);
    // Samples per pixel per second in this cell, from what the controller placed there.
    float density = max(float(texelFetch(uCounts, cell, 0).r) / float(uCell * uCell), 0.25 * uFreshPerPixel) *
                    uRefreshHz;
    float gs = max(stats.y, 1e-3), gt = max(stats.z, 1e-3);
    // S^2 T density = 2 (two samples expected in the filter's volume), T = S gs / gt.
    float s = clamp(pow(2.0 * gt / (gs * density), 1.0 / 3.0), 0.5, float(kRadius));
    float t = clamp(s * gs / gt, 1.0 / uRefreshHz, 0.25);

    vec3 sum = vec3(0.0);
    float weight = 0.0;
    float nearest = 1e9;
    vec3 nearestColour = vec3(0.0);
    for (int dy = -kRadius; dy <= kRadius; ++dy)
        for (int dx = -kRadius; dx <= kRadius; ++dx) {
            ivec2 q = p + ivec2(dx, dy);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
            vec4 sample_ = texelFetch(uDeep, q, 0);
            if (sample_.a < 0.0) continue;
            float d2 = float(dx * dx + dy * dy);
            float age = max(uTime - sample_.a, 0.0);
            float w = exp(-0.5 * d2 / (s * s)) * exp(-age / t);
            sum += w * sample_.rgb;
            weight += w;
            if (d2 < nearest) {
                nearest = d2;
                nearestColour = sample_.rgb;
            }
        }
    vec3 colour = weight > 1e-8 ? sum / weight : nearestColour;
    outColour = vec4(clamp(colour, 0.0, 1.0), 1.0);
    outId = texelFetch(uIds, p, 0).r;
    outCorrespondence = vec4(uintBitsToFloat(0x7fc00000u));
}

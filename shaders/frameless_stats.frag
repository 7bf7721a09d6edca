#version 410 core
// Adaptive frameless sampling: one controller cell's statistics from the deep buffer (seed 002,
// sections 4, 4.1 and 6.1), read back by the controller to place the next frame's samples and
// used by the reconstruction to size its filters.
//   x: colour variation, the age-weighted variance of the samples' luminance, weights e^(-3.47 a)
//   y: spatial gradient, the mean absolute luminance difference of neighbouring samples per pixel
//   z: temporal gradient, luminance per second, age-weighted mean of the samples' crosshairs
//   w: the share of the cell's pixels holding no sample (the undersampling term)

uniform sampler2D uDeep;    // rgb colour, a: when made (s), < 0: none
uniform sampler2D uChange;  // r: temporal gradient
uniform int uCell;          // pixels per cell side
uniform float uTime;

layout(location = 0) out vec4 outStats;

float luma(vec3 c) {
    return dot(c, vec3(0.299, 0.587, 0.114));
}

void main() {
    ivec2 size = textureSize(uDeep, 0);
    ivec2 origin = ivec2(gl_FragCoord.xy) * uCell;
    float w = 0.0, mean = 0.0, meanSquare = 0.0, temporal = 0.0, spatial = 0.0;
    int pairs = 0, empty = 0, pixels = 0;
    for (int y = 0; y < uCell; ++y)
        for (int x = 0; x < uCell; ++x) {
            ivec2 p = origin + ivec2(x, y);
            if (p.x >= size.x || p.y >= size.y) continue;
            ++pixels;
            vec4 s = texelFetch(uDeep, p, 0);
            if (s.a < 0.0) {
                ++empty;
                continue;
            }
            float l = luma(s.rgb);
            float weight = exp(-3.47 * max(uTime - s.a, 0.0));
            w += weight;
            mean += weight * l;
            meanSquare += weight * l * l;
            temporal += weight * texelFetch(uChange, p, 0).r;
            for (int k = 0; k < 2; ++k) {
                ivec2 q = p + (k == 0 ? ivec2(1, 0) : ivec2(0, 1));
                if (q.x >= size.x || q.y >= size.y) continue;
                vec4 n = texelFetch(uDeep, q, 0);
                if (n.a < 0.0) continue;
                spatial += abs(luma(n.rgb) - l);
                ++pairs;
            }
        }
    float variance = w > 0.0 ? max(meanSquare / w - (mean / w) * (mean / w), 0.0) : 0.0;
    outStats = vec4(variance, pairs > 0 ? spatial / float(pairs) : 0.0, w > 0.0 ? temporal / w : 0.0,
                    pixels > 0 ? float(empty) / float(pixels) : 1.0);
}

#version 410 core
// One fragment per sparse-mesh patch: does the source depth (or velocity) jump between
// horizontal neighbours (r) or vertical neighbours (g) anywhere inside the patch? Linear eye
// depths are compared relative to the nearer one, so a wall far away and a crate close by
// are judged alike; a velocity jump counts too, or a moving object resting against a static
// one at the same depth would be stretched across their boundary.

uniform sampler2D uSourceDepth;
uniform sampler2D uSourceVelocity;
uniform vec2 uSize;
uniform int uPatchSize;
uniform float uNear;
uniform float uFar;
uniform float uDepthThreshold;     // relative
uniform float uVelocityThreshold;  // m/s

layout(location = 0) out vec4 outFlags;

float linearDepth(float d) {
    float ndc = 2.0 * d - 1.0;
    return 2.0 * uNear * uFar / (uFar + uNear - ndc * (uFar - uNear));
}

bool jump(ivec2 a, ivec2 b) {
    ivec2 hi = ivec2(uSize) - 1;
    a = clamp(a, ivec2(0), hi);
    b = clamp(b, ivec2(0), hi);
    float za = linearDepth(texelFetch(uSourceDepth, a, 0).r);
    float zb = linearDepth(texelFetch(uSourceDepth, b, 0).r);
    if (abs(za - zb) > uDepthThreshold * min(za, zb)) return true;
    vec3 va = texelFetch(uSourceVelocity, a, 0).xyz, vb = texelFetch(uSourceVelocity, b, 0).xyz;
    return distance(va, vb) > uVelocityThreshold;
}

void main() {
    ivec2 origin = ivec2(gl_FragCoord.xy) * uPatchSize - 1;
    bool horizontal = false, vertical = false;
    for (int j = 0; j <= uPatchSize; ++j) {
        for (int i = 0; i < uPatchSize; ++i) {
            horizontal = horizontal || jump(origin + ivec2(i, j), origin + ivec2(i + 1, j));
            vertical = vertical || jump(origin + ivec2(j, i), origin + ivec2(j, i + 1));
        }
    }
    outFlags = vec4(horizontal ? 1.0 : 0.0, vertical ? 1.0 : 0.0, 0.0, 1.0);
}

#version 410 core
// Scene-assisted reprojection, fragment stage: the surface point's exact position in each
// I-frame; it is visible there when the depth stored at that pixel is its own (view depths
// within a relative tolerance). Visible in both: blend by alpha; in one: that one; in neither:
// closest-on-miss, the I-frame whose stored surface is nearer (the paper's choice).

in vec4 vClip0;
in vec4 vClip1;

uniform int uSky;
uniform uint uObjectId;
uniform sampler2D uColour0;
uniform sampler2D uColour1;
uniform sampler2D uDepth0;       // window depth, 1 = far plane
uniform sampler2D uDepth1;
uniform vec2 uSize;
uniform float uAlpha;
uniform float uNear;
uniform float uFar;
uniform float uDepthTolerance;   // relative
uniform mat4 uInverseViewProjection;
uniform mat4 uViewProjection0;
uniform mat4 uViewProjection1;

layout(location = 0) out vec4 outColour;
layout(location = 1) out uint outId;
layout(location = 2) out vec4 outCorrespondence;

ivec2 texel(vec2 q) { return clamp(ivec2(floor(q)), ivec2(0), ivec2(uSize) - 1); }
bool inside(vec2 q) { return all(greaterThanEqual(q, vec2(0.0))) && all(lessThan(q, uSize)); }
float viewDepth(float windowDepth) {
    float ndc = windowDepth * 2.0 - 1.0;
    return 2.0 * uNear * uFar / (uFar + uNear - ndc * (uFar - uNear));
}
vec2 pixelOf(vec4 clip) { return (clip.xy / clip.w * 0.5 + 0.5) * uSize; }

void main() {
    vec4 c0 = vClip0, c1 = vClip1;
    if (uSky != 0) {
        vec2 ndc = gl_FragCoord.xy / uSize * 2.0 - 1.0;
        vec4 a = uInverseViewProjection * vec4(ndc, -1.0, 1.0);
        vec4 b = uInverseViewProjection * vec4(ndc, 1.0, 1.0);
        vec3 direction = b.xyz / b.w - a.xyz / a.w;
        c0 = uViewProjection0 * vec4(direction, 0.0);
        c1 = uViewProjection1 * vec4(direction, 0.0);
    }
    // Behind an I-frame's camera there is no position in it: put it far outside the image.
    vec2 q0 = c0.w > 1e-6 ? pixelOf(c0) : vec2(-1e6);
    vec2 q1 = c1.w > 1e-6 ? pixelOf(c1) : vec2(-1e6);
    float stored0 = viewDepth(texelFetch(uDepth0, texel(q0), 0).r);
    float stored1 = viewDepth(texelFetch(uDepth1, texel(q1), 0).r);
    bool visible0, visible1;
    if (uSky != 0) {
        visible0 = inside(q0) && texelFetch(uDepth0, texel(q0), 0).r >= 1.0;
        visible1 = inside(q1) && texelFetch(uDepth1, texel(q1), 0).r >= 1.0;
    } else {
        visible0 = inside(q0) && abs(stored0 - c0.w) < uDepthTolerance * c0.w;
        visible1 = inside(q1) && abs(stored1 - c1.w) < uDepthTolerance * c1.w;
    }
    float w1 = visible0 && visible1 ? uAlpha : (visible1 ? 1.0 : (visible0 ? 0.0 : (stored1 < stored0 ? 1.0 : 0.0)));
    vec3 colour0 = texture(uColour0, clamp(q0, vec2(0.5), uSize - 0.5) / uSize).rgb;
    vec3 colour1 = texture(uColour1, clamp(q1, vec2(0.5), uSize - 0.5) / uSize).rgb;
    outColour = vec4(mix(colour0, colour1, w1), 1.0);
    outId = uObjectId;
    // The exact correspondence, top-down, into both I-frames.
    outCorrespondence = vec4(q0.x, uSize.y - q0.y, q1.x, uSize.y - q1.y);
}

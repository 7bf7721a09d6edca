#version 410 core
// Adaptive frameless sampling, emulated by a rasteriser (seed 002, Dayal et al. 2005): the deep
// buffer's update at one displayed frame. Each pixel keeps its newest sample (a deep buffer of
// depth 1): a sample shaded this frame where the controller placed one, otherwise the sample it
// held, reprojected to the current view (section 6) and dropped where the surface it shows is
// no longer the one seen there -- the occlusion test of section 6.1, made with the geometry
// pass's depth and ids instead of a ray cast to the eye. Rows are GL's (bottom-up).

uniform sampler2D uDepth;          // this frame's geometry pass
uniform usampler2D uIds;
uniform sampler2D uVelocity;       // world-space m/s
uniform sampler2D uShaded;         // this frame's samples, shaded where uMask says
uniform usampler2D uMask;
uniform sampler2D uPreviousDeep;   // rgb: the sample's colour, a: when it was made (s), < 0: none
uniform sampler2D uPreviousChange; // r: its pixel's temporal gradient, luminance per second
uniform sampler2D uPreviousDepth;  // the previous frame's geometry pass
uniform usampler2D uPreviousIds;

uniform mat4 uInverseViewProjection;
uniform mat4 uPreviousViewProjection;
uniform float uTime;               // the displayed instant, s
uniform float uDt;                 // since the previous frame, s
uniform float uNear;
uniform float uFar;
uniform int uHaveHistory;
uniform float uDepthTolerance;

layout(location = 0) out vec4 outDeep;
layout(location = 1) out vec4 outChange;

float linearDepth(float d) {
    float ndc = 2.0 * d - 1.0;
    return 2.0 * uNear * uFar / (uFar + uNear - ndc * (uFar - uNear));
}

float luma(vec3 c) {
    return dot(c, vec3(0.299, 0.587, 0.114));
}

void main() {
    ivec2 size = textureSize(uDepth, 0);
    ivec2 p = ivec2(gl_FragCoord.xy);
    float depth = texelFetch(uDepth, p, 0).r;
    uint id = texelFetch(uIds, p, 0).r;

    // The sample this pixel held, reprojected: nearest texel, kept only if it shows this surface.
    vec4 held = vec4(0.0, 0.0, 0.0, -1.0);
    float change = 0.0;
    if (uHaveHistory != 0) {
        vec2 ndc = (vec2(p) + 0.5) / vec2(size) * 2.0 - 1.0;
        vec4 world = uInverseViewProjection * vec4(ndc, 2.0 * depth - 1.0, 1.0);
        vec3 point = world.xyz / world.w - texelFetch(uVelocity, p, 0).xyz * uDt;
        vec4 clip = uPreviousViewProjection * vec4(point, 1.0);
        ivec2 t = ivec2(floor((clip.xy / clip.w * 0.5 + 0.5) * vec2(size)));
        if (clip.w > 0.0 && all(greaterThanEqual(t, ivec2(0))) && all(lessThan(t, size)) &&
            texelFetch(uPreviousIds, t, 0).r == id) {
            float previous = linearDepth(texelFetch(uPreviousDepth, t, 0).r);
            if (abs(previous - clip.w) <= uDepthTolerance * min(previous, clip.w)) {
                held = texelFetch(uPreviousDeep, t, 0);
                change = texelFetch(uPreviousChange, t, 0).r;
            }
        }
    }
    if (texelFetch(uMask, p, 0).r != 0u) {
        vec3 fresh = texelFetch(uShaded, p, 0).rgb;
        // The crosshair's temporal gradient (section 4.1): against the sample it replaces.
        if (held.a >= 0.0 && uTime > held.a) change = abs(luma(fresh) - luma(held.rgb)) / (uTime - held.a);
        outDeep = vec4(fresh, uTime);
    } else {
        outDeep = held;
    }
    outChange = vec4(change, 0.0, 0.0, 0.0);
}

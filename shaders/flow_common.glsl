// Flow fields of bidirectional reprojection (seed 000 eq. 1-2), shared by the conventional
// pass (which writes the backward flow of an I-frame as it renders it, into a fourth render
// target) and the flow-only pass of renderer/upconvert/bireproj.cpp. The vertex stage hands
// over the fragment's surface point in the other instant's clip space and both view depths.
// Output (GL window pixels, y up; metres of view depth):
//   xy = where the surface point is at the other instant minus where it is now,
//   z  = its view depth there minus here, w = its view depth here.
// Sky pixels are directions: only the camera's rotation moves them; their depth is the far
// plane. A point behind the other camera has no position there: flow 0, so every value stays
// finite (the B-frame search then reports a large error for it, or finds another point).

uniform vec2 uFlowSize;
uniform float uFlowFar;
uniform mat4 uFlowInverseViewProjection;
uniform mat4 uFlowOtherViewProjection;

vec4 flowOf(vec2 here, vec4 otherClip, float viewDepth, float otherViewDepth, bool sky) {
    vec4 other = otherClip;
    float depthChange = otherViewDepth - viewDepth;
    float depth = viewDepth;
    if (sky) {
        vec2 ndc = here / uFlowSize * 2.0 - 1.0;
        vec4 a = uFlowInverseViewProjection * vec4(ndc, -1.0, 1.0);
        vec4 b = uFlowInverseViewProjection * vec4(ndc, 1.0, 1.0);
        vec3 direction = b.xyz / b.w - a.xyz / a.w;
        other = uFlowOtherViewProjection * vec4(direction, 0.0);
        depthChange = 0.0;
        depth = uFlowFar;
    }
    vec2 flow = vec2(0.0);
    if (other.w > 1e-6) flow = (other.xy / other.w * 0.5 + 0.5) * uFlowSize - here;
    return vec4(flow, depthChange, depth);
}

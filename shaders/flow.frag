#version 410 core
// Flow fields, fragment stage. Output (GL window pixels, y up; metres of view depth):
//   xy = where this pixel's surface point is at the other instant minus where it is now,
//   z  = its view depth there minus here, w = its view depth here.
// Sky pixels are directions: only the camera's rotation moves them; their depth is the far
// plane. A point behind the other camera has no position there: flow 0, so every value stays
// finite (the B-frame search then reports a large error for it, or finds another point).

in vec4 vOtherClip;
in float vViewDepth;
in float vOtherViewDepth;

uniform int uSky;
uniform uint uObjectId;
uniform vec2 uSize;
uniform float uFar;
uniform mat4 uInverseViewProjection;
uniform mat4 uOtherViewProjection;

layout(location = 1) out uint outId;
layout(location = 2) out vec4 outFlow;

void main() {
    vec2 here = gl_FragCoord.xy;
    vec4 other = vOtherClip;
    float depthChange = vOtherViewDepth - vViewDepth;
    float depth = vViewDepth;
    if (uSky != 0) {
        vec2 ndc = here / uSize * 2.0 - 1.0;
        vec4 a = uInverseViewProjection * vec4(ndc, -1.0, 1.0);
        vec4 b = uInverseViewProjection * vec4(ndc, 1.0, 1.0);
        vec3 direction = b.xyz / b.w - a.xyz / a.w;
        other = uOtherViewProjection * vec4(direction, 0.0);
        depthChange = 0.0;
        depth = uFar;
    }
    vec2 flow = vec2(0.0);
    if (other.w > 1e-6) flow = (other.xy / other.w * 0.5 + 0.5) * uSize - here;
    outId = uObjectId;
    outFlow = vec4(flow, depthChange, depth);
}

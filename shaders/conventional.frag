#version 410 core
// Conventional renderer, fragment stage: Phong shading plus the G-buffer's id and world-space
// velocity (seed 004 section 5.2.3). A rigid body's surface point p moves with
// v + omega x (p - centre), so rotating objects get the right per-fragment velocity.

in vec3 vWorldPosition;
in vec3 vNormal;
in vec3 vDiffuse;
in vec4 vSpecular;
in vec4 vOtherClip;
in float vViewDepth;
in float vOtherViewDepth;

uniform int uSky;

uniform uint uObjectId;
uniform vec3 uLinearVelocity;
uniform vec3 uAngularVelocity;
uniform vec3 uCentre;
uniform vec3 uEye;
uniform vec3 uTint;
uniform int uPanelPattern;
uniform int uLampCount;
uniform int uShadingCost;
uniform int uGeometryOnly;  // a G-buffer pass: ids, velocity and depth, no lighting
// Shade only the pixels this mask marks (adaptive frameless sampling's samples); the rest are
// discarded before any shading, depth included.
uniform int uMasked;
uniform usampler2D uSampleMask;
uniform vec3 uLampPosition[MAX_LAMPS];
uniform vec3 uLampColour[MAX_LAMPS];

layout(location = 0) out vec4 outColour;
layout(location = 1) out uint outId;
layout(location = 2) out vec4 outVelocity;
layout(location = 3) out vec4 outFlow;  // only stored when a fourth target is bound (see flow_common.glsl)

// Thin dark seams every 2 m on the hangar's surfaces: high-frequency detail that a warp
// must carry correctly, and that makes its errors show in PSNR / SSIM.
float panelSeams(vec3 p, vec3 n) {
    vec3 a = abs(n);
    vec2 uv = a.x > a.y && a.x > a.z ? p.zy : (a.y > a.z ? p.xz : p.xy);
    vec2 f = abs(fract(uv * 0.5) - 0.5);
    float seam = step(0.47, max(f.x, f.y));
    return 1.0 - 0.35 * seam;
}

// The bench's shading-cost knob: uShadingCost iterations of a hash per fragment, standing in
// for the expensive shading of a real game. Its result tints the surface by at most 2% so the
// compiler cannot drop the loop; at 0 (the default) it does nothing.
float costlyDetail(vec3 p, int iterations) {
    vec3 q = p;
    float sum = 0.0;
    for (int i = 0; i < iterations; ++i) {
        q = fract(q * 1.6180339 + vec3(0.1031, 0.1030, 0.0973));
        sum += dot(q, q.yzx + 19.19);
    }
    return fract(sum);
}

void main() {
    if (uMasked != 0 && texelFetch(uSampleMask, ivec2(gl_FragCoord.xy), 0).r == 0u) discard;
    outFlow = flowOf(gl_FragCoord.xy, vOtherClip, vViewDepth, vOtherViewDepth, uSky != 0);
    if (uSky != 0) {
        outColour = vec4(SKY_COLOUR, 1.0);  // the clear colour, from conventional.cpp
        outId = 0u;
        outVelocity = vec4(0.0);
        return;
    }
    if (uGeometryOnly != 0) {
        outColour = vec4(0.0, 0.0, 0.0, 1.0);
        outId = uObjectId;
        outVelocity = vec4(uLinearVelocity + cross(uAngularVelocity, vWorldPosition - uCentre), 0.0);
        return;
    }
    vec3 n = normalize(vNormal);
    vec3 toEye = normalize(uEye - vWorldPosition);
    // Two-sided: a face seen from behind is lit as if it faced the viewer.
    if (dot(n, toEye) < 0.0) n = -n;
    vec3 kd = vDiffuse * uTint;
    if (uPanelPattern != 0) kd *= panelSeams(vWorldPosition, n);
    if (uShadingCost > 0) kd *= 1.0 + 0.02 * (costlyDetail(vWorldPosition, uShadingCost) - 0.5);

    vec3 colour = 0.12 * kd;  // ambient: the hangar is never pitch black
    for (int i = 0; i < uLampCount; ++i) {
        vec3 toLamp = uLampPosition[i] - vWorldPosition;
        float d2 = dot(toLamp, toLamp);
        vec3 l = toLamp * inversesqrt(d2);
        float attenuation = 1.0 / (1.0 + 0.02 * d2);
        float diffuse = max(dot(n, l), 0.0);
        vec3 r = reflect(-l, n);
        float specular = diffuse > 0.0 ? pow(max(dot(r, toEye), 0.0), vSpecular.a) : 0.0;
        colour += attenuation * uLampColour[i] * (kd * diffuse + vSpecular.rgb * specular);
    }
    outColour = vec4(clamp(colour, 0.0, 1.0), 1.0);
    outId = uObjectId;
    outVelocity = vec4(uLinearVelocity + cross(uAngularVelocity, vWorldPosition - uCentre), 0.0);
}

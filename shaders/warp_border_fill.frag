#version 410 core
// Warp, border fill: drawn before the mesh, without writing depth, so the mesh replaces it
// wherever it lands and it shows only where no warped source pixel does -- content that was
// off-screen in the source after a turn. Each display pixel's view ray is reprojected as a
// direction (a point at infinity) into the source view and its coordinate clamped to the
// source's edge pixel centres: exact for a pure rotation while the ray stays inside the source
// view, and the nearest source edge beyond it, never black. A ray pointing behind the source
// eye still leaves through the edge on its own side (its lateral direction decides).
// Its correspondence is NaN: a clamped edge pixel is a fill, not the surface that is there.

uniform sampler2D uSourceColour;
uniform usampler2D uSourceIds;
uniform mat4 uTargetInverseViewProjection;
uniform mat4 uSourceViewProjection;
uniform vec3 uTargetEye;
uniform vec2 uSourceSize;  // pixels; larger than the display's when sources have a guard band
uniform vec2 uTargetSize;  // the displayed frame's pixels

layout(location = 0) out vec4 outColour;
layout(location = 1) out uint outId;
layout(location = 2) out vec4 outCorrespondence;

void main() {
    vec2 ndc = gl_FragCoord.xy / uTargetSize * 2.0 - 1.0;
    vec4 far = uTargetInverseViewProjection * vec4(ndc, 1.0, 1.0);
    vec3 direction = far.xyz / far.w - uTargetEye;
    vec4 h = uSourceViewProjection * vec4(direction, 0.0);
    vec2 source = (h.xy / max(h.w, 1e-6) * 0.5 + 0.5) * uSourceSize;  // bottom-up pixel coordinates
    source = clamp(source, vec2(0.5), uSourceSize - 0.5);
    outColour = texture(uSourceColour, source / uSourceSize);
    outId = texelFetch(uSourceIds, ivec2(floor(source)), 0).r;
    float none = uintBitsToFloat(0x7fc00000u);
    outCorrespondence = vec4(none);
}

// Where a warp shows what no warped source pixel covers -- content that was off-screen in the
// source after a turn: each display pixel's view ray is reprojected as a direction (a point at
// infinity) into the source view and its coordinate clamped to the source's edge pixel centres.
// Exact for a pure rotation while the ray stays inside the source view, and the nearest source
// edge beyond it, never black. A ray pointing behind the source eye still leaves through the
// edge on its own side (its lateral direction decides). Shared by the mesh warps' border fill
// and warp-splat's resolve.

uniform mat4 uTargetInverseViewProjection;
uniform mat4 uSourceViewProjection;
uniform vec3 uTargetEye;
uniform vec2 uSourceSize;  // pixels; larger than the display's when sources have a guard band
uniform vec2 uTargetSize;  // the displayed frame's pixels

// The source coordinate (bottom-up pixels, centres at +0.5) in the direction of display pixel
// `fragCoord`'s view ray, before clamping: outside [0.5, size - 0.5] the ray left the source view.
vec2 borderRayCoordinate(vec2 fragCoord) {
    vec2 ndc = fragCoord / uTargetSize * 2.0 - 1.0;
    vec4 far = uTargetInverseViewProjection * vec4(ndc, 1.0, 1.0);
    vec3 direction = far.xyz / far.w - uTargetEye;
    vec4 h = uSourceViewProjection * vec4(direction, 0.0);
    return (h.xy / max(h.w, 1e-6) * 0.5 + 0.5) * uSourceSize;
}

vec2 borderSourceCoordinate(vec2 fragCoord) {
    return clamp(borderRayCoordinate(fragCoord), vec2(0.5), uSourceSize - 0.5);
}

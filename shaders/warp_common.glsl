// Warp extrapolation, shared by the full-mesh vertex stage and the sparse mesh's tessellation
// evaluation stage (seed 004 eq. 5-11): a source pixel's depth is unprojected with the source
// camera's inverse matrices, moved by its stored world velocity times dt, and projected with
// the current camera.

uniform sampler2D uSourceDepth;     // window-space depth, 1 = far plane
uniform sampler2D uSourceVelocity;  // world-space velocity (xyz)
uniform mat4 uSourceInverseViewProjection;
uniform mat4 uSourceViewProjection;
uniform mat4 uTargetViewProjection;
uniform vec3 uSourceEye;
uniform vec2 uSize;       // source size in pixels (the display's plus any guard band)
uniform float uDt;        // display time - source time, seconds
uniform float uSkyDistance;  // far-plane pixels are placed this far from the source eye

struct WarpedPoint {
    vec4 clip;          // position in the current view
    vec3 sourceWorld;   // surface point at source time (for disocclusion classification)
    vec3 sourceH;       // source pixel coordinate (bottom-up, centres at +0.5) times source w, and w
};

// `pixel` is a source pixel index; it may lie one outside the image (the mesh's outer ring,
// so the warped mesh covers the whole border): depth and velocity come from the nearest pixel.
WarpedPoint warpPixel(ivec2 pixel) {
    ivec2 texel = clamp(pixel, ivec2(0), ivec2(uSize) - 1);
    float depth = texelFetch(uSourceDepth, texel, 0).r;
    vec2 centre = vec2(pixel) + 0.5;
    vec2 ndc = centre / uSize * 2.0 - 1.0;
    vec4 world = uSourceInverseViewProjection * vec4(ndc, 2.0 * depth - 1.0, 1.0);
    vec3 p = world.xyz / world.w;
    vec3 velocity = vec3(0.0);
    if (depth >= 1.0) {
        // Sky: no surface, a direction. Put it at a fixed distance inside the far plane so
        // turning the camera moves it like the distant background it is, with no NaN and no
        // clipping against the far plane.
        p = uSourceEye + normalize(p - uSourceEye) * uSkyDistance;
    } else {
        velocity = texelFetch(uSourceVelocity, texel, 0).xyz;
    }
    WarpedPoint w;
    w.sourceWorld = p;
    w.clip = uTargetViewProjection * vec4(p + velocity * uDt, 1.0);  // eq. 11 then eq. 8
    // Interpolating (x w, y w, w) and dividing per fragment maps source coordinates exactly
    // through the perspective of both views, even across large sparse-mesh triangles.
    float sourceW = (uSourceViewProjection * vec4(p, 1.0)).w;
    w.sourceH = vec3(centre * sourceW, sourceW);
    return w;
}

#version 430 core
// warp-splat, passes 1b and 1c: each cell of the warped grid (warp_splat_common.glsl) covers
// the display pixel centres inside its two triangles -- a source pixel's footprint, so a
// stretch leaves no crack -- with no mesh, no rasteriser, a few memory operations per pixel.
// Pass 1b (uWinnerPass 0) keeps each pixel's nearest depth with atomicMin; pass 1c
// (uWinnerPass 1) repeats the same arithmetic and, where its depth is the kept one, keeps the
// smallest triangle index with atomicMin. Both are minima, so the result is the same
// whatever order the invocations run in: the nearest surface, ties to the lower index. One
// program serves both passes so that their depths are computed by the same code, bit for bit.
//
// A triangle that is a disocclusion sheet (the fix's rule, warp_fix.geom: nearly parallel to
// the source view ray, spanning a depth jump, and opening in the display) is not splatted:
// the resolve fills its pixels from the background side.

layout(local_size_x = 16, local_size_y = 16) in;

uniform bool uWinnerPass;
uniform ivec2 uTargetPixels;
uniform float uGrazingCosine;
uniform float uSheetDepthRatio;
// A triangle spanning more display pixels than this on a side is one that the near plane or a
// grazing view has stretched beyond any surface's footprint; left as a hole, it is filled.
uniform int uMaxSpan;

// As warp_fix.geom: a sheet must open by half a pixel beyond its source extent (the cell's
// diagonal) in the display before it is one. Only then are its surface points needed, so they
// are unprojected again here (warp_common.glsl) rather than stored for every vertex.
const float kOpensPx = 0.5;
const float kSourceExtent = 1.41421356;

bool isSheet(vec3 v[3], ivec2 g[3]) {
    float targetExtent = max(max(distance(v[0].xy, v[1].xy), distance(v[1].xy, v[2].xy)), distance(v[2].xy, v[0].xy));
    if (targetExtent <= kSourceExtent + kOpensPx) return false;
    vec3 a = warpPixel(g[0] - 1).sourceWorld, b = warpPixel(g[1] - 1).sourceWorld, c = warpPixel(g[2] - 1).sourceWorld;
    vec3 normal = cross(b - a, c - a);
    vec3 ray = (a + b + c) / 3.0 - uSourceEye;
    float lengths = length(normal) * length(ray);
    if (!(lengths > 0.0 && abs(dot(normal, ray)) < uGrazingCosine * lengths)) return false;
    float d0 = distance(a, uSourceEye), d1 = distance(b, uSourceEye), d2 = distance(c, uSourceEye);
    float near = min(min(d0, d1), d2), far = max(max(d0, d1), d2);
    return far > uSheetDepthRatio * near;
}

struct Triangle {
    vec3 v[3];  // display x, y and window depth of the corners
    float area;  // edgeFunction of the corners; 0 = not splatted
};

Triangle prepare(vec4 r0, vec4 r1, vec4 r2, ivec2 g0, ivec2 g1, ivec2 g2) {
    Triangle t;
    t.v = vec3[3](r0.xyz, r1.xyz, r2.xyz);
    t.area = 0.0;
    if (r0.w <= 0.0 || r1.w <= 0.0 || r2.w <= 0.0) return t;  // a corner behind the display eye
    if (isSheet(t.v, ivec2[3](g0, g1, g2))) return t;
    t.area = edgeFunction(t.v[0].xy, t.v[1].xy, t.v[2].xy);
    return t;
}

void cover(Triangle t, uint index, vec2 p, int pixel) {
    if (t.area == 0.0) return;
    vec3 b = barycentric(t.v[0].xy, t.v[1].xy, t.v[2].xy, t.area, p);
    if (min(min(b.x, b.y), b.z) < -kInsideTolerance) return;
    float depth = b.x * t.v[0].z + b.y * t.v[1].z + b.z * t.v[2].z;
    if (!(depth >= 0.0 && depth <= 1.0)) return;  // beyond the near or far plane
    uint bits = floatBitsToUint(depth);
    if (!uWinnerPass)
        atomicMin(depths[pixel], bits);
    else if (depths[pixel] == bits)
        atomicMin(winners[pixel], index);
}

void main() {
    ivec2 c = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(c, uCells))) return;
    // The cell's two triangles (splatTriangle's), their corners read once.
    ivec2 g00 = c, g10 = c + ivec2(1, 0), g01 = c + ivec2(0, 1), g11 = c + ivec2(1, 1);
    vec4 r00 = gridVertex(g00), r10 = gridVertex(g10), r01 = gridVertex(g01), r11 = gridVertex(g11);
    uint first = 2u * uint(c.y * uCells.x + c.x);
    Triangle upper = prepare(r01, r00, r11, g01, g00, g11);
    Triangle lower = prepare(r00, r11, r10, g00, g11, g10);
    if (upper.area == 0.0 && lower.area == 0.0) return;
    vec2 size = vec2(uTargetPixels);
    vec2 lo = clamp(min(min(r00.xy, r10.xy), min(r01.xy, r11.xy)), vec2(-1.0), size + 1.0);
    vec2 hi = clamp(max(max(r00.xy, r10.xy), max(r01.xy, r11.xy)), vec2(-1.0), size + 1.0);
    ivec2 lowest = max(ivec2(ceil(lo - 0.5)), ivec2(0));
    ivec2 highest = min(ivec2(floor(hi - 0.5)), uTargetPixels - 1);
    if (any(greaterThan(highest - lowest, ivec2(uMaxSpan)))) return;
    for (int y = lowest.y; y <= highest.y; ++y)
        for (int x = lowest.x; x <= highest.x; ++x) {
            vec2 p = vec2(x, y) + 0.5;
            int pixel = y * uTargetPixels.x + x;
            cover(upper, first, p, pixel);
            cover(lower, first + 1u, p, pixel);
        }
}

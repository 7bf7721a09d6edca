#version 430 core
// warp-splat, pass 1a: every source pixel of the grid (guard band and outer ring included)
// warped to the displayed instant with the mesh warps' own equations (warp_common.glsl,
// seed 004 eq. 6-11), stored for the splat and the resolve (warp_splat_common.glsl).

layout(local_size_x = 16, local_size_y = 16) in;

uniform vec2 uTargetSize;

void main() {
    ivec2 g = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThan(g, uCells))) return;
    WarpedPoint p = warpPixel(g - 1);
    vec4 vertex = vec4(0.0, 0.0, 0.0, -1.0);
    if (p.clip.w > 1e-6) {
        vec3 ndc = p.clip.xyz / p.clip.w;
        // The unprojected point, projected back into the source, misses its pixel centre by the
        // float rounding of the two matrices (a thousandth of a pixel and more where depth is
        // compressed); the same rounding moves its display position, so it is taken off there
        // too. A warp with nothing to do then puts every centre exactly on its own.
        vec4 back = uSourceViewProjection * vec4(p.sourceWorld, 1.0);
        vec2 centre = vec2(g - 1) + 0.5;
        vec2 roundTrip = (back.xy / back.w * 0.5 + 0.5) * uSize - centre;
        vertex = vec4((ndc.xy * 0.5 + 0.5) * uTargetSize - roundTrip, ndc.z * 0.5 + 0.5, p.sourceH.z / p.clip.w);
    }
    vertices[g.y * (uCells.x + 1) + g.x] = vertex;
}

// warp-splat, shared by its passes: the warped source grid as the vertex pass stores it, the
// per-display-pixel depth and winner the splat keeps, and the triangles between neighbouring
// source pixel centres -- the full-density mesh of the mesh warps, split along the same
// diagonal, but rasterised by the splat itself. Shader storage buffers rather than images:
// llvmpipe reads and writes them as plain memory.
//
// The grid has one vertex per source pixel plus an outer ring, (size + 2)^2, vertex g being
// source pixel g - 1. Each vertex holds its display position (window pixels, y up), window
// depth, and k = source clip w / display clip w, which interpolates a source coordinate
// perspective-correctly (k < 0: behind the display eye, shown nowhere). Cell c joins vertices
// c .. c + (1, 1); its two triangles are numbered 2 * (c.y * cells.x + c.x) + (0 or 1).

layout(std430, binding = 0) buffer Vertices { vec4 vertices[]; };
layout(std430, binding = 1) buffer Depths { uint depths[]; };  // floatBitsToUint(window depth); kNoWinner = none
layout(std430, binding = 2) buffer Winners { uint winners[]; };  // triangle index; kNoWinner = none

uniform ivec2 uCells;  // source size + 1; the grid is one wider and taller

const uint kNoWinner = 0xFFFFFFFFu;

vec4 gridVertex(ivec2 g) { return vertices[g.y * (uCells.x + 1) + g.x]; }

struct SplatTriangle {
    ivec2 g[3];  // grid vertices
};

// The triangles of the full mesh's row strips: (x, y + 1), (x, y), (x + 1, y + 1), then
// (x, y), (x + 1, y + 1), (x + 1, y) -- both split along the diagonal (x, y) - (x + 1, y + 1).
SplatTriangle splatTriangle(uint index) {
    int cell = int(index >> 1u);
    ivec2 c = ivec2(cell % uCells.x, cell / uCells.x);
    SplatTriangle t;
    if ((index & 1u) == 0u) {
        t.g[0] = c + ivec2(0, 1);
        t.g[1] = c;
        t.g[2] = c + ivec2(1, 1);
    } else {
        t.g[0] = c;
        t.g[1] = c + ivec2(1, 1);
        t.g[2] = c + ivec2(1, 0);
    }
    return t;
}

float edgeFunction(vec2 a, vec2 b, vec2 p) { return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x); }

// Screen-space barycentric coordinates of p in (a, b, c); `area` is edgeFunction(a, b, c).
vec3 barycentric(vec2 a, vec2 b, vec2 c, float area, vec2 p) {
    float ba = edgeFunction(b, c, p) / area;
    float bb = edgeFunction(c, a, p) / area;
    return vec3(ba, bb, 1.0 - ba - bb);
}

// A pixel centre within rounding of a shared edge belongs to both triangles (the depth test
// and the winner's index then pick one), so float rounding never leaves a crack between them.
const float kInsideTolerance = 1e-4;

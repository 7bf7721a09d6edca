#version 410 core
// Warp, full-density mesh (seed 004 section 5.2.4): one vertex per source pixel plus an
// outer ring, indexed by gl_VertexID over a (width + 2) x (height + 2) grid.

out vec3 vSourceH;
out vec3 vSourceWorld;

void main() {
    int columns = int(uSize.x) + 2;
    ivec2 pixel = ivec2(gl_VertexID % columns, gl_VertexID / columns) - 1;
    WarpedPoint w = warpPixel(pixel);
    vSourceH = w.sourceH;
    vSourceWorld = w.sourceWorld;
    gl_Position = w.clip;
}

#version 410 core
// HUD quads: a rectangle given in pixels (origin bottom-left), as a two-triangle strip made
// from gl_VertexID.
uniform vec4 uRect;   // x, y, width, height in pixels
uniform vec2 uViewport;

out vec2 vUv;

void main() {
    vec2 corner = vec2(float(gl_VertexID & 1), float((gl_VertexID >> 1) & 1));
    vUv = vec2(corner.x, 1.0 - corner.y);  // text surfaces are stored top row first
    vec2 pixel = uRect.xy + corner * uRect.zw;
    gl_Position = vec4(pixel / uViewport * 2.0 - 1.0, 0.0, 1.0);
}

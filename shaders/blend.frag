#version 410 core
// Linear blend of the previous and next source frames, weighted by where the display instant
// lies between them. It knows no correspondences; the id shown is the nearer frame's.
uniform sampler2D uColourA;
uniform sampler2D uColourB;
uniform usampler2D uIdsA;
uniform usampler2D uIdsB;
uniform float uAlpha;

layout(location = 0) out vec4 outColour;
layout(location = 1) out uint outId;
layout(location = 2) out vec4 outCorrespondence;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    outColour = mix(texelFetch(uColourA, p, 0), texelFetch(uColourB, p, 0), uAlpha);
    outId = uAlpha < 0.5 ? texelFetch(uIdsA, p, 0).r : texelFetch(uIdsB, p, 0).r;
    float none = uintBitsToFloat(0x7fc00000u);
    outCorrespondence = vec4(none);
}

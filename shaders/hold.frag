#version 410 core
// Sample and hold: the displayed pixel is the source pixel at the same place, and says so in
// its correspondence (top-down pixel-centre coordinates; none into a next frame).
uniform sampler2D uColour;
uniform usampler2D uIds;
uniform int uHeight;

layout(location = 0) out vec4 outColour;
layout(location = 1) out uint outId;
layout(location = 2) out vec4 outCorrespondence;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    outColour = texelFetch(uColour, p, 0);
    outId = texelFetch(uIds, p, 0).r;
    float none = uintBitsToFloat(0x7fc00000u);  // NaN: no claim into the next frame
    outCorrespondence = vec4(gl_FragCoord.x, float(uHeight) - gl_FragCoord.y, none, none);
}

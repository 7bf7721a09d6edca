#version 410 core
// Sample and hold: the displayed pixel is the source pixel at the same place, and says so in
// its correspondence (top-down pixel-centre coordinates; none into a next frame). A source with
// a guard band shows its displayed part: the band is skipped.
uniform sampler2D uColour;
uniform usampler2D uIds;
uniform ivec2 uBand;        // guard-band pixels on each side of the source
uniform int uSourceHeight;  // the source's rows, band included

layout(location = 0) out vec4 outColour;
layout(location = 1) out uint outId;
layout(location = 2) out vec4 outCorrespondence;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy) + uBand;
    outColour = texelFetch(uColour, p, 0);
    outId = texelFetch(uIds, p, 0).r;
    float none = uintBitsToFloat(0x7fc00000u);  // NaN: no claim into the next frame
    outCorrespondence = vec4(gl_FragCoord.xy + vec2(uBand), none, none);
    outCorrespondence.y = float(uSourceHeight) - outCorrespondence.y;
}

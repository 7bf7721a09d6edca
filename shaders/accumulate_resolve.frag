#version 410 core
// Motion blur from B-frames, the displayed frame: the mean of the accumulated frames, and the
// object ids of the one nearest the middle of the exposure. A blurred pixel shows several
// surface points, so it claims no single correspondence.
uniform sampler2D uSum;
uniform usampler2D uMiddleIds;
uniform float uCount;
layout(location = 0) out vec4 outColour;
layout(location = 1) out uint outId;
layout(location = 2) out vec4 outCorrespondence;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    outColour = vec4(texelFetch(uSum, p, 0).rgb / uCount, 1.0);
    outId = texelFetch(uMiddleIds, p, 0).r;
    outCorrespondence = vec4(uintBitsToFloat(0x7fc00000u));
}

#version 410 core
// Motion blur from B-frames: adds one frame's colour into a float accumulator (additive
// blending does the sum); resolve.frag divides by the number of frames.
uniform sampler2D uColour;
layout(location = 0) out vec4 outSum;
void main() { outSum = texelFetch(uColour, ivec2(gl_FragCoord.xy), 0); }

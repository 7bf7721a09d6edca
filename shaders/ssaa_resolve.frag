#version 410 core
// Supersampling's resolve (ConventionalRenderer, ShadingOptions::supersampling): a pixel's
// colour is the box-filter mean of its uFactor x uFactor samples, rendered at uFactor times the
// size so that sample (uFactor x + i, uFactor y + j) sits at the centre of sub-pixel (i, j).
// Written into the G-buffer's colour only; depth, ids and velocity keep the pixel centre's.
uniform sampler2D uSamples;
uniform int uFactor;
layout(location = 0) out vec4 outColour;
void main() {
    ivec2 first = ivec2(gl_FragCoord.xy) * uFactor;
    vec4 sum = vec4(0.0);
    for (int j = 0; j < uFactor; ++j)
        for (int i = 0; i < uFactor; ++i) sum += texelFetch(uSamples, first + ivec2(i, j), 0);
    outColour = sum / float(uFactor * uFactor);
}

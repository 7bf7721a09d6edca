#version 410 core
// Warp, fragment stage: the displayed colour and object id are the source's at the warped
// point's source coordinate; the coordinate itself is reported for the bench.

// The source coordinate comes from the geometry stage when the disocclusion fix runs.
#ifdef WARP_GEOMETRY_STAGE
in vec3 gSourceH;
in vec3 gOwnSourceH;
in float gForeground;
// A sample exactly on a recoloured foreground corner is that foreground pixel itself (the
// rasteriser's tie rule may hand it to the sheet rather than to the foreground surface):
// it keeps its own colour, the rest of the sheet takes the background's.
#define SOURCE_H (gForeground > 0.999 ? gOwnSourceH : gSourceH)
#else
in vec3 vSourceH;
#define SOURCE_H vSourceH
#endif

uniform sampler2D uSourceColour;
uniform usampler2D uSourceIds;
uniform vec2 uSize;

layout(location = 0) out vec4 outColour;
layout(location = 1) out uint outId;
layout(location = 2) out vec4 outCorrespondence;

void main() {
    vec2 source = SOURCE_H.xy / SOURCE_H.z;  // bottom-up pixel coordinates
    outColour = texture(uSourceColour, source / uSize);
    outId = texelFetch(uSourceIds, clamp(ivec2(floor(source)), ivec2(0), ivec2(uSize) - 1), 0).r;
    float none = uintBitsToFloat(0x7fc00000u);
    outCorrespondence = vec4(source.x, uSize.y - source.y, none, none);  // top-down for the bench
}

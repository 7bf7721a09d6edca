#version 410 core
// Warp, border fill: drawn before the mesh, without writing depth, so the mesh replaces it
// wherever it lands and it shows only where no warped source pixel does (warp_border.glsl).
// Its correspondence is NaN: a clamped edge pixel is a fill, not the surface that is there.

uniform sampler2D uSourceColour;
uniform usampler2D uSourceIds;

layout(location = 0) out vec4 outColour;
layout(location = 1) out uint outId;
layout(location = 2) out vec4 outCorrespondence;

void main() {
    vec2 source = borderSourceCoordinate(gl_FragCoord.xy);  // bottom-up pixel coordinates
    outColour = texture(uSourceColour, source / uSourceSize);
    outId = texelFetch(uSourceIds, ivec2(floor(source)), 0).r;
    float none = uintBitsToFloat(0x7fc00000u);
    outCorrespondence = vec4(none);
}

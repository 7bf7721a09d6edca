#version 410 core
// Late warp by camera rotation (Kim et al., HPG 2020; NVIDIA Reflex 2 Frame Warp): the source
// frame re-projected to the displayed camera, depth ignored. Both cameras share the eye, so a
// display pixel's view ray is a direction, and a direction maps from one image to the other by
// one 3x3 homography (built in double on the CPU, rotation.cpp): exact for every static
// surface and the sky; moving objects stay where the source had them.
//
// Depth is not written, as hold.frag writes none: a depth-free method has no depth of its own
// to claim. Where the ray leaves the source image or points behind the source eye, colour and
// id are the nearest edge pixel's, as the warp's border fill (warp_border_fill.frag) does, and
// the correspondence is NaN: an edge pixel smeared outwards is not the surface that is there.

uniform sampler2D uSourceColour;
uniform usampler2D uSourceIds;
// Display window coordinates (bottom-up, pixel centres at +0.5, w = 1) to the source's, homogeneous;
// its third component is the ray's depth along the source's view axis.
uniform mat3 uDisplayToSource;
uniform vec2 uSourceSize;  // pixels, the guard band included

layout(location = 0) out vec4 outColour;
layout(location = 1) out uint outId;
layout(location = 2) out vec4 outCorrespondence;

void main() {
    vec3 h = uDisplayToSource * vec3(gl_FragCoord.xy, 1.0);
    bool inFront = h.z > 0.0;
    // A ray behind the source eye still leaves through the edge on its own side, as in the
    // border fill: its lateral direction, not its flipped projection, picks the edge.
    vec2 source = h.xy / max(h.z, 1e-6);  // bottom-up pixel coordinates
    bool inside = inFront && all(greaterThanEqual(source, vec2(0.0))) && all(lessThanEqual(source, uSourceSize));
    vec2 clamped = clamp(source, vec2(0.5), uSourceSize - 0.5);
    // Inside, the texture's own edge clamp covers the half pixel beyond the outer centres.
    outColour = texture(uSourceColour, (inside ? source : clamped) / uSourceSize);
    outId = texelFetch(uSourceIds, clamp(ivec2(floor(clamped)), ivec2(0), ivec2(uSourceSize) - 1), 0).r;
    float none = uintBitsToFloat(0x7fc00000u);  // NaN
    outCorrespondence = inside ? vec4(source.x, uSourceSize.y - source.y, none, none) : vec4(none);
}

#version 430 core
// warp-splat, pass 2: each displayed pixel from what the splat left there.
//  - A winning triangle: the source coordinate interpolated at the pixel centre as the mesh
//    warp's rasteriser would (screen-space barycentrics, perspective-correct through k), the
//    colour sampled there as warp.frag samples it, the id of the source pixel that shows it.
//  - None, where the pixel's view ray leaves the source view: the border fill of the mesh warps
//    (warp_border.glsl), correspondence NaN.
//  - None inside it: a true hole, the disocclusion fix's rule (seed 004 section 5.2.5): the
//    source coordinate of the nearest background neighbour along the motion. The splat pixels
//    on the 8 rays from the pixel (up to uHoleReach away) are the candidates; those within the
//    sheet depth ratio of the farthest are background, the rest foreground. The first
//    background pixel against the foreground's motion relative to the background gives its
//    coordinate -- the edge of the background that the moving foreground uncovered, as the
//    fix's sheet shows it -- or, where that line meets none, the nearest background candidate.
//    Never the foreground: it is nearer than the background by more than that ratio.
// The depth written is the winner's (or the background's, or the far plane for the border).

uniform sampler2D uSourceColour;
uniform usampler2D uSourceIds;
uniform int uHoleReach;
uniform float uSheetDepthRatio;
uniform float uNear;  // the display camera's planes, to compare window depths as distances
uniform float uFar;

layout(location = 0) out vec4 outColour;
layout(location = 1) out uint outId;
layout(location = 2) out vec4 outCorrespondence;

// The source coordinate (bottom-up pixels) that triangle `winner` puts at display point p.
vec2 sourceCoordinate(uint winner, vec2 p) {
    SplatTriangle t = splatTriangle(winner);
    vec4 a = gridVertex(t.g[0]), b = gridVertex(t.g[1]), c = gridVertex(t.g[2]);
    vec3 w = barycentric(a.xy, b.xy, c.xy, edgeFunction(a.xy, b.xy, c.xy), p) * vec3(a.w, b.w, c.w);
    vec2 centre0 = vec2(t.g[0]) - 0.5, centre1 = vec2(t.g[1]) - 0.5, centre2 = vec2(t.g[2]) - 0.5;
    return (w.x * centre0 + w.y * centre1 + w.z * centre2) / (w.x + w.y + w.z);
}

// How far the splat moved what display pixel q shows, in display pixels: q against its
// source coordinate (the source's band taken off, same pitch).
vec2 flowAt(ivec2 q) {
    int width = int(uTargetSize.x);
    vec2 source = sourceCoordinate(winners[q.y * width + q.x], vec2(q) + 0.5);
    return vec2(q) + 0.5 - (source - 0.5 * (uSourceSize - uTargetSize));
}

float viewDistance(float windowDepth) {
    float ndc = 2.0 * windowDepth - 1.0;
    return 2.0 * uNear * uFar / (uFar + uNear - ndc * (uFar - uNear));
}

void show(vec2 source, float depth, bool claimed) {
    outColour = texture(uSourceColour, source / uSourceSize);
    outId = texelFetch(uSourceIds, clamp(ivec2(floor(source)), ivec2(0), ivec2(uSourceSize) - 1), 0).r;
    float none = uintBitsToFloat(0x7fc00000u);
    outCorrespondence = claimed ? vec4(source.x, uSourceSize.y - source.y, none, none) : vec4(none);
    gl_FragDepth = depth;
}

const ivec2 kRays[8] = ivec2[8](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1), ivec2(1, 1), ivec2(-1, 1),
                                ivec2(1, -1), ivec2(-1, -1));

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    int width = int(uTargetSize.x);
    uint winner = winners[pixel.y * width + pixel.x];
    if (winner != kNoWinner) {
        show(sourceCoordinate(winner, gl_FragCoord.xy), uintBitsToFloat(depths[pixel.y * width + pixel.x]), true);
        return;
    }
    vec2 ray = borderRayCoordinate(gl_FragCoord.xy);
    if (any(lessThan(ray, vec2(0.5))) || any(greaterThan(ray, uSourceSize - 0.5))) {
        show(clamp(ray, vec2(0.5), uSourceSize - 0.5), 1.0, false);
        return;
    }
    ivec2 found[8];
    float distanceOf[8];
    int steps[8];
    float farthest = 0.0;
    for (int r = 0; r < 8; ++r) {
        steps[r] = 0;
        for (int s = 1; s <= uHoleReach; ++s) {
            ivec2 q = pixel + s * kRays[r];
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(uTargetSize)))) break;
            if (winners[q.y * width + q.x] != kNoWinner) {
                found[r] = q;
                steps[r] = s;
                distanceOf[r] = viewDistance(uintBitsToFloat(depths[q.y * width + q.x]));
                farthest = max(farthest, distanceOf[r]);
                break;
            }
        }
    }
    // Background: within the sheet ratio of the farthest; the rest is foreground.
    vec2 foregroundFlow = vec2(0.0), backgroundFlow = vec2(0.0);
    float foregrounds = 0.0, backgrounds = 0.0;
    int best = -1;
    float bestLength = 0.0;
    for (int r = 0; r < 8; ++r) {
        if (steps[r] == 0) continue;
        vec2 flow = flowAt(found[r]);
        if (distanceOf[r] * uSheetDepthRatio < farthest) {
            foregroundFlow += flow;
            foregrounds += 1.0;
            continue;
        }
        backgroundFlow += flow;
        backgrounds += 1.0;
        float along = float(steps[r]) * length(vec2(kRays[r]));
        if (best < 0 || along < bestLength) {
            best = r;
            bestLength = along;
        }
    }
    // The hole opened as the foreground moved against the background: the background it
    // uncovered lies behind it, against their relative motion. The fix's sheet spans that
    // motion and shows the background's edge along it; so does the first background pixel on
    // that line, where there is one (else the nearest on the 8 rays).
    if (best >= 0 && foregrounds > 0.0) {
        vec2 motion = foregroundFlow / foregrounds - backgroundFlow / backgrounds;
        if (length(motion) > 0.5) {
            vec2 back = -normalize(motion);
            for (int s = 1; s <= uHoleReach; ++s) {
                ivec2 q = ivec2(floor(gl_FragCoord.xy + float(s) * back));
                if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(uTargetSize)))) break;
                uint w = winners[q.y * width + q.x];
                if (w == kNoWinner) continue;
                if (viewDistance(uintBitsToFloat(depths[q.y * width + q.x])) * uSheetDepthRatio >= farthest) {
                    show(sourceCoordinate(w, vec2(q) + 0.5), uintBitsToFloat(depths[q.y * width + q.x]), true);
                    return;
                }
                break;  // the foreground itself: this line finds no background
            }
        }
    }
    if (best < 0) {
        // Nothing splatted near: the direction's own source pixel, as the border fill would.
        show(clamp(ray, vec2(0.5), uSourceSize - 0.5), 1.0, false);
        return;
    }
    ivec2 q = found[best];
    vec2 source = sourceCoordinate(winners[q.y * width + q.x], vec2(q) + 0.5);
    show(source, uintBitsToFloat(depths[q.y * width + q.x]), true);
}

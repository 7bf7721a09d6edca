#version 410 core
// Image-based bidirectional reprojection, the B-frame pass (seed 000 section 5): no scene
// geometry, only the two I-frames' colour, ids and flow fields. For each B-frame pixel p at
// t + alpha, an iterative search in each direction (eq. 3-12) finds the pixel of the same
// surface point in I-frame t (forward flow) and in I-frame t + 1 (backward flow); the
// visibility rules of section 5.2 (eq. 13-15) decide which colours to blend. Extra starting
// points (section 5.3): dual initialisation (eq. 16-17) and the previous B-frame's offsets
// (latest-frame initialisation, eq. 18-19, neighbourhood taking the nearest surface).
//
// Coordinates are GL window pixels (y up, pixel centres at +0.5) throughout; the reported
// correspondence is converted to the top-down convention of DisplayFrame at the end.

uniform sampler2D uColour0;      // I-frame t (previous)
uniform sampler2D uColour1;      // I-frame t + 1 (next)
uniform usampler2D uIds0;
uniform usampler2D uIds1;
uniform sampler2D uFlowF;        // of I-frame t, towards t + 1: xy px, z view-depth change, w view depth
uniform sampler2D uFlowB;        // of I-frame t + 1, towards t
uniform sampler2D uPreviousOffsets;  // the previous B-frame's offsets: xy forward, zw backward
uniform vec2 uSize;
uniform float uAlpha;            // (display time - t) / (t + 1 - t), in (0, 1)
uniform float uPreviousAlpha;    // alpha of uPreviousOffsets' B-frame; 0 = none
uniform float uEps1;             // screen-space error threshold, pixels
uniform float uEps2;             // depth threshold, relative to view depth
// Compile-time settings (the method's; constants let the compiler unroll the loops, which
// llvmpipe needs to run them at speed): ITERATIONS (m, 1..8), DUAL_INIT and LATEST_INIT (0/1),
// NEIGHBOURHOOD (latest-frame initialisation looks this many pixels around).

layout(location = 0) out vec4 outColour;
layout(location = 1) out uint outId;
layout(location = 2) out vec4 outCorrespondence;
layout(location = 3) out vec4 outOffsets;

const float kFar = 1e9;  // the error of a search that left the image
const float kExact = 0.1;  // pixels: two searches this close to p both solved eq. 3 / 8

bool inside(vec2 q) { return all(greaterThanEqual(q, vec2(0.0))) && all(lessThan(q, uSize)); }
ivec2 texel(vec2 q) { return clamp(ivec2(floor(q)), ivec2(0), ivec2(uSize) - 1); }
vec4 flowF(vec2 q) { return texelFetch(uFlowF, texel(q), 0); }
vec4 flowB(vec2 q) { return texelFetch(uFlowB, texel(q), 0); }
vec3 colour0(vec2 q) { return texture(uColour0, clamp(q, vec2(0.5), uSize - 0.5) / uSize).rgb; }
vec3 colour1(vec2 q) { return texture(uColour1, clamp(q, vec2(0.5), uSize - 0.5) / uSize).rgb; }

struct Search {
    vec2 at;      // the pixel found in the I-frame
    float depth;  // the point's view depth carried to t + alpha (eq. 6 / 11)
    float error;  // screen-space error (eq. 7 / 12)
};

// Forward: p = q + alpha Vf[q].xy solved for q by fixed-point iteration from `start`.
Search searchForward(vec2 p, vec2 start) {
    vec2 q = start;
    for (int i = 0; i < ITERATIONS; ++i) q = p - uAlpha * flowF(q).xy;
    vec4 f = flowF(q);
    Search s;
    s.at = q;
    s.depth = f.w + uAlpha * f.z;
    s.error = inside(q) ? length(q + uAlpha * f.xy - p) : kFar;
    return s;
}

Search searchBackward(vec2 p, vec2 start) {
    float beta = 1.0 - uAlpha;
    vec2 q = start;
    for (int i = 0; i < ITERATIONS; ++i) q = p - beta * flowB(q).xy;
    vec4 f = flowB(q);
    Search s;
    s.at = q;
    s.depth = f.w + beta * f.z;
    s.error = inside(q) ? length(q + beta * f.xy - p) : kFar;
    return s;
}

// Of two searches from different starting points, the smaller error, as the paper says --
// except where both land within kExact of p: then both found a surface point that projects
// to p at t + alpha (with exact flows an occluded one converges as well as the visible one:
// the background behind a moving sphere), and the nearer is the one p shows.
Search better(Search a, Search b) {
    if (a.error < kExact && b.error < kExact) return b.depth < a.depth ? b : a;
    return b.error < a.error ? b : a;
}

// Latest-frame initialisation: among the previous B-frame's offsets around p (scaled to this
// alpha), the start whose I-frame pixel is nearest the camera.
vec2 latestStart(vec2 p, bool forward) {
    float scale = forward ? uAlpha / uPreviousAlpha : (1.0 - uAlpha) / (1.0 - uPreviousAlpha);
    vec2 best = p;
    float bestDepth = kFar;
    for (int dy = -NEIGHBOURHOOD; dy <= NEIGHBOURHOOD; ++dy) {
        for (int dx = -NEIGHBOURHOOD; dx <= NEIGHBOURHOOD; ++dx) {
            vec4 o = texelFetch(uPreviousOffsets, texel(p + vec2(dx, dy)), 0);
            vec2 start = p - scale * (forward ? o.xy : o.zw);
            float depth = forward ? flowF(start).w : flowB(start).w;
            if (depth < bestDepth) {
                bestDepth = depth;
                best = start;
            }
        }
    }
    return best;
}

bool sameSurface(float a, float b) { return abs(a - b) < uEps2 * min(a, b); }

float none() { return uintBitsToFloat(0x7fc00000u); }
vec2 topDown(vec2 q) { return vec2(q.x, uSize.y - q.y); }

void main() {
    vec2 p = gl_FragCoord.xy;
    float alpha = uAlpha;
    bool latest = LATEST_INIT != 0 && uPreviousAlpha > 0.0 && uPreviousAlpha < 1.0;

    Search f = searchForward(p, p);
    Search b = searchBackward(p, p);
    if (DUAL_INIT != 0) {
        f = better(f, searchForward(p, p + alpha * flowB(p).xy));          // eq. 16
        b = better(b, searchBackward(p, p + (1.0 - alpha) * flowF(p).xy));  // eq. 17
    }
    if (LATEST_INIT != 0 && latest) {
        f = better(f, searchForward(p, latestStart(p, true)));    // eq. 18
        b = better(b, searchBackward(p, latestStart(p, false)));  // eq. 19
    }

    bool okF = f.error < uEps1, okB = b.error < uEps1;
    // Which search the colour starts from (section 5.2): both found the same surface -> the
    // one with the smaller error (case 1); different surfaces -> the nearer, which occludes
    // the other (case 2); only one converged -> that one; neither -> blend both (case 3).
    int from;  // 0 forward, 1 backward, 2 both as found
    if (okF && okB) from = sameSurface(f.depth, b.depth) ? (f.error < b.error ? 0 : 1) : (f.depth <= b.depth ? 0 : 1);
    else if (okF) from = 0;
    else if (okB) from = 1;
    else from = 2;

    vec2 q0 = f.at, q1 = b.at;
    bool use0 = true, use1 = true;
    if (from == 0) {
        // Carry the point exactly into I-frame t + 1 along its forward flow (eq. 14) and use
        // it there if it is visible there: the depth the flow predicts matches the depth seen.
        vec4 v = flowF(q0);
        q1 = q0 + v.xy;
        use1 = inside(q1) && sameSurface(v.w + v.z, flowB(q1).w);
    } else if (from == 1) {
        vec4 v = flowB(q1);  // eq. 15
        q0 = q1 + v.xy;
        use0 = inside(q0) && sameSurface(v.w + v.z, flowF(q0).w);
    }
    float w1 = use0 && use1 ? alpha : (use1 ? 1.0 : 0.0);
    outColour = vec4(mix(colour0(q0), colour1(q1), w1), 1.0);
    outId = w1 < 0.5 ? texelFetch(uIds0, texel(q0), 0).r : texelFetch(uIds1, texel(q1), 0).r;
    outCorrespondence = vec4(use0 ? topDown(q0) : vec2(none()), use1 ? topDown(q1) : vec2(none()));
    outOffsets = vec4(p - f.at, p - b.at);
}

#version 410 core
// Extrapolation by iterative search ("warp-search"): the displayed frame from the latest
// source frame alone, without warp's mesh. The source's motion towards the displayed instant
// is the warp's (warp_common.glsl, seed 004 eq. 5-11): a source pixel q is displayed at
// D(q) = project_display(unproject_source(q, depth(q)) + velocity(q) dt), its flow is
// F(q) = D(q) - q. Each displayed pixel p solves p = q + F(q) for q by the fixed-point search
// of seed 000 eq. 4-7 (q_0 = start, q_i = p - F(q_{i-1}), m = ITERATIONS steps, error
// e = |q_m + F(q_m) - p|), from these starts:
//  - p, and p - F(p) (one step further along the same sequence, so both come from one loop
//    of m + 1 steps);
//  - with RINGS > 0, a start from the neighbourhood, like seed 000's latest-frame
//    initialisation (eq. 18-19) but from the source's own flow: the flow sampled on RINGS
//    rings of 8 points around p proposes starts p - F(p + o); of those that land on a surface
//    moving onto p (one step error under 2 eps), the nearest. Without it nothing finds a
//    surface that moved onto p from elsewhere over a surface that stays (the leading edge of
//    a moving target over the static hangar): from p the search only ever sees what the
//    source shows at p.
// Of the searches that converged, the nearest surface wins (several converge where one
// surface moved in front of another); where none did, the pixel is a disocclusion.
//
// Coordinates are GL window pixels (y up, pixel centres at +0.5); the reported
// correspondence is converted to the top-down convention of DisplayFrame at the end.
// warp_common.glsl is compiled in before this file for its uniforms. Compile-time settings
// (constants let the compiler unroll the loops): ITERATIONS (m, 1..8), RINGS (0..4).

uniform sampler2D uSourceColour;
uniform usampler2D uSourceIds;
uniform float uEps;         // pixels: a search with a smaller error converged
uniform float uRingRadius;  // pixels: the outermost ring; each inner one half the one outside

layout(location = 0) out vec4 outColour;
layout(location = 1) out uint outId;
layout(location = 2) out vec4 outCorrespondence;

const float kFar = 1e9;  // the error of a search that left the image; the depth of an unseen point

bool inside(vec2 q) { return all(greaterThanEqual(q, vec2(0.0))) && all(lessThan(q, uSize)); }
ivec2 texel(vec2 q) { return clamp(ivec2(floor(q)), ivec2(0), ivec2(uSize) - 1); }
// Searches are kept within a few image sizes: a flow far off-screen makes a finite, failing one.
vec2 bounded(vec2 q) { return clamp(q, -2.0 * uSize, 3.0 * uSize); }

struct Flow {
    vec2 flow;    // F(q), pixels
    float depth;  // view depth of the point at the displayed instant (kFar if behind the eye)
};

// warpPixel's arithmetic at a continuous source coordinate q: depth and velocity are the
// nearest source pixel's (the one that shows q), the point is unprojected at q itself, so a
// pure camera rotation maps q exactly. Outside the image the border pixel's depth is used,
// as for the mesh's outer ring.
Flow flowAt(vec2 q) {
    ivec2 t = texel(q);
    float depth = texelFetch(uSourceDepth, t, 0).r;
    vec2 ndc = q / uSize * 2.0 - 1.0;
    vec4 world = uSourceInverseViewProjection * vec4(ndc, 2.0 * depth - 1.0, 1.0);
    vec3 point = world.xyz / world.w;
    vec3 velocity = vec3(0.0);
    if (depth >= 1.0) {
        point = uSourceEye + normalize(point - uSourceEye) * uSkyDistance;  // sky: a direction
    } else {
        velocity = texelFetch(uSourceVelocity, t, 0).xyz;
    }
    vec4 clip = uTargetViewProjection * vec4(point + velocity * uDt, 1.0);
    Flow f;
    if (clip.w > 1e-6) {
        f.flow = bounded((clip.xy / clip.w * 0.5 + 0.5) * uSize) - q;
        f.depth = clip.w;
    } else {
        // Behind the displayed eye: shown nowhere. A flow that throws the search off-screen.
        f.flow = vec2(-8.0 * uSize.x, 0.0);
        f.depth = kFar;
    }
    return f;
}

struct Search {
    vec2 at;      // q_m, the source coordinate found
    float depth;  // its view depth at the displayed instant
    float error;  // eq. 7
};

Search result(vec2 p, vec2 q, Flow f) {
    Search s;
    s.at = q;
    s.depth = f.depth;
    s.error = inside(q) ? length(q + f.flow - p) : kFar;
    return s;
}

Search search(vec2 p, vec2 start) {
    vec2 q = start;
    Flow f = flowAt(q);
    for (int i = 0; i < ITERATIONS; ++i) {
        q = bounded(p - f.flow);
        f = flowAt(q);
    }
    return result(p, q, f);
}

// Of two searches: both converged -> the nearer surface (with exact flows an occluded surface
// solves p = q + F(q) as well as the visible one does: the background behind a moving
// object); otherwise the smaller error.
Search better(Search a, Search b) {
    if (a.error < uEps && b.error < uEps) return b.depth < a.depth ? b : a;
    return b.error < a.error ? b : a;
}

#if RINGS > 0
// The neighbourhood's proposal: the start p - F(p + o) whose surface lands within 2 eps of p
// after one step, nearest first; `found` false when none does. A sample moving as p's own
// source pixel does (flow within eps of F(p)) proposes what the start p - F(p) already tried
// and is not checked -- in smooth flow, most of them: the check's fetches are the cost.
vec2 ringStart(vec2 p, vec2 flowAtP, out bool found) {
    vec2 best = p;
    float bestDepth = kFar;
    found = false;
    for (int r = 0; r < RINGS; ++r) {
        float radius = uRingRadius * exp2(float(r + 1 - RINGS));
        float turn = float(r) * 0.39269908;  // 22.5 degrees: alternate rings fill each other's gaps
        for (int k = 0; k < 8; ++k) {
            float angle = turn + float(k) * 0.78539816;
            Flow there = flowAt(p + radius * vec2(cos(angle), sin(angle)));
            if (length(there.flow - flowAtP) < uEps) continue;
            vec2 start = bounded(p - there.flow);
            Flow f = flowAt(start);
            if (inside(start) && length(start + f.flow - p) < 2.0 * uEps && f.depth < bestDepth) {
                bestDepth = f.depth;
                best = start;
                found = true;
            }
        }
    }
    return best;
}
#endif

float none() { return uintBitsToFloat(0x7fc00000u); }

void main() {
    vec2 p = gl_FragCoord.xy;

    // q_0 = p; after m steps the search from p ends at q_m, the one from p - F(p) = q_1 at
    // q_{m+1}. F(q_m) is both the first one's error term and the second one's last step.
    vec2 q = p;
    Flow f = flowAt(q);
    vec2 flowAtP = f.flow;
    for (int i = 0; i < ITERATIONS; ++i) {
        q = bounded(p - f.flow);
        f = flowAt(q);
    }
    Search a = result(p, q, f);
    q = bounded(p - f.flow);
    Search b = result(p, q, flowAt(q));

    Search s = better(a, b);
#if RINGS > 0
    bool proposed;
    vec2 start = ringStart(p, flowAtP, proposed);
    if (proposed) s = better(s, search(p, start));
#endif
    bool found = s.error < uEps;
    if (!found) {
        // Disocclusion: no start found a surface that lands on p. What a hole most likely
        // reveals is the background, so the farther of the two default searches' surfaces
        // fills it (of those that stayed inside the image), and no correspondence is claimed.
        bool inA = a.error < kFar, inB = b.error < kFar;
        if (inA && inB) s = b.depth > a.depth ? b : a;
        else s = inB ? b : a;
    }

    vec2 at = clamp(s.at, vec2(0.5), uSize - 0.5);
    outColour = texture(uSourceColour, at / uSize);
    outId = texelFetch(uSourceIds, texel(s.at), 0).r;
    outCorrespondence = found ? vec4(s.at.x, uSize.y - s.at.y, none(), none()) : vec4(none());
}

#version 410 core
// Spatio-temporal upsampling (seed 001, Herzog et al. 2010, section 3): one displayed pixel
// from the lattice of pixels shaded this frame (a low-resolution render whose sample points
// rotate over the frame's pixels) and the exponential history buffer of the frames before,
// reprojected by the scene's motion.
//
//   spatial    h~(i) = sum w_s(i, j) l(j) / sum w_s, w~(i) = sum w_s       (eq. 6)
//              w_s = d(|z_i - z_j|^2, sigma_d^2) k(i, j) [same id]        (eq. 2, 3)
//   temporal   h = (h~ w~ + w_f h_w h_r) / (w~ + w_f h_w)                  (eq. 7)
//              h_w := w~ + w_f h_w
//   confidence w_f = a (1 - |grad|)^2, |grad| the weighted sum of the last four relative
//              temporal gradients (eq. 8, section 3.5.1); k's fall-off is 4 w_f (section 3.5)
//
// What the G-buffer holds decides two departures from the paper: there are no normals, so the
// geometric weight has the depth term and the object id (a different id weighs epsilon), and
// the gradients are low-passed over the lattice's neighbours instead of a mipmap's level 2.5.
//
// A third departure lets a still pixel converge to its own exact samples. k's fall-off, at
// most 4 (section 3.5), keeps mixing the neighbours' samples into every pixel: summed over a
// cycle of a 2x2 lattice a pixel is about half its own sample and half its neighbours',
// however long the scene stays still (27.5 dB on a still 128x72 hangar; with the fall-off
// unbounded, 38.5). k's other limit, a dirac (gamma = infinity, section 3.3), is
// temporally-amortized upsampling (eq. 4), which for a static pixel gathers only its own
// samples: section 4's "up to 16 frames are needed to produce an accurate result in a static
// scene" holds there. So a still pixel -- one whose reprojection lands on its own texel's
// centre, so that nothing is resampled (Figure 9's blur) -- takes that limit: when this frame
// shades it, its own sample is shown and kept (eq. 4's w_t = 1); when not, and the history
// holds that sample, the neighbours' samples weigh w~ (1 - w_f), so they show only as far as
// the temporal gradient doubts the history, and the history keeps the sample unblended. A
// flag in the gradients' fourth channel says the history is the pixel's own sample. Every
// other pixel -- moving, resampled, disoccluded -- is filtered as above.
// Rows are GL's (bottom-up) throughout.

uniform sampler2D uDepth;          // this frame's geometry pass, full resolution
uniform usampler2D uIds;
uniform sampler2D uVelocity;       // world-space m/s
uniform sampler2D uLowColour;      // this frame's lattice, shaded
uniform sampler2D uLowDepth;
uniform usampler2D uLowIds;
uniform sampler2D uHistory;        // rgb: h_r, a: h_w (previous frame)
uniform sampler2D uGradients;      // x, y, z: the last three relative gradients; w: own flag
uniform sampler2D uPreviousDepth;  // the previous frame's geometry pass
uniform usampler2D uPreviousIds;

uniform ivec2 uStep;               // lattice step: one pixel of each uStep.x x uStep.y block shaded
uniform ivec2 uPhase;              // which one, this frame
uniform mat4 uInverseViewProjection;
uniform mat4 uPreviousViewProjection;
uniform mat4 uReprojection;        // uPreviousViewProjection * uInverseViewProjection, in double
uniform float uDt;                 // seconds since the previous frame
uniform float uNear;
uniform float uFar;
uniform int uHaveHistory;
uniform float uMaxHistoryWeight;
uniform float uDepthTolerance;     // relative, for the disocclusion test
uniform float uStillTolerance;     // pixels: a reprojection this near a texel centre is that texel

layout(location = 0) out vec4 outColour;
layout(location = 1) out uint outId;
layout(location = 2) out vec4 outCorrespondence;
layout(location = 3) out vec4 outHistory;
layout(location = 4) out vec4 outGradients;

const float kEpsilon = 1e-3;  // eq. 3's floor: no weight is ever exactly zero

float linearDepth(float d) {
    float ndc = 2.0 * d - 1.0;
    return 2.0 * uNear * uFar / (uFar + uNear - ndc * (uFar - uNear));
}

// Eq. 3: max(epsilon, 1 - x / sigma)^gamma.
float falloff(float x, float sigma, float gamma) {
    return pow(max(kEpsilon, 1.0 - x / sigma), gamma);
}

float luma(vec3 c) {
    return dot(c, vec3(0.299, 0.587, 0.114));
}

// The relative temporal gradient of section 3.5.1, on luminance.
float relativeGradient(vec3 now, vec3 before) {
    float a = luma(now), b = luma(before);
    return (a - b) / max(max(abs(a), abs(b)), 1e-3);
}

// What the previous frame left for this pixel.
struct History {
    bool found;       // some texel around q shows the same surface (not disoccluded)
    bool still;       // q is the centre of one such texel, which is all that is read
    vec4 value;       // rgb h_r, a h_w
    vec3 gradients;   // the last three gradients, low-passed over a lattice cell
    bool own;         // h_r is this pixel's own exact sample (still only)
    float gradient;   // the texel's own last gradient (still only)
};

// A texel of the previous frame shows the point when it has its object at the depth the
// point had (Herzog et al.'s depth and id test, Figure 3).
bool sameSurface(ivec2 t, ivec2 size, uint id, float expected) {
    if (any(lessThan(t, ivec2(0))) || any(greaterThanEqual(t, size))) return false;
    if (texelFetch(uPreviousIds, t, 0).r != id) return false;
    float previous = linearDepth(texelFetch(uPreviousDepth, t, 0).r);
    return abs(previous - expected) <= uDepthTolerance * min(previous, expected);
}

// q: the point's position in the previous frame, pixel centres at +0.5; expected: its view
// depth there. Bilinear over the four texels around q, each kept only if it is the same
// surface; a still pixel reads its one texel.
History fetchHistory(vec2 q, float expected, uint id, ivec2 size) {
    History h = History(false, false, vec4(0.0), vec3(0.0), false, 1.0);
    ivec2 nearest = ivec2(floor(q));
    vec2 offset = q - (vec2(nearest) + 0.5);
    if (all(lessThan(abs(offset), vec2(uStillTolerance))) && sameSurface(nearest, size, id, expected)) {
        h.found = h.still = true;
        h.value = texelFetch(uHistory, nearest, 0);
        vec4 g = texelFetch(uGradients, nearest, 0);
        h.own = g.w > 0.5;
        h.gradient = g.x;
    } else {
        vec2 base = q - 0.5;
        ivec2 t0 = ivec2(floor(base));
        vec2 f = base - vec2(t0);
        float weight = 0.0;
        for (int k = 0; k < 4; ++k) {
            ivec2 t = t0 + ivec2(k & 1, k >> 1);
            if (!sameSurface(t, size, id, expected)) continue;
            float w = ((k & 1) != 0 ? f.x : 1.0 - f.x) * ((k >> 1) != 0 ? f.y : 1.0 - f.y);
            h.value += w * texelFetch(uHistory, t, 0);
            weight += w;
        }
        h.found = weight > 1e-4;
        if (h.found) h.value /= weight;
    }
    if (h.found) {
        // The last gradients, low-passed over a lattice cell around q (four bilinear taps half a
        // step away) as the paper low-passes them with a mipmap: aliasing shows as a gradient
        // that changes sign from pixel to pixel and frame to frame, and averages away.
        vec2 half_ = 0.5 * vec2(uStep);
        for (int k = 0; k < 4; ++k) {
            vec2 at = q + half_ * vec2((k & 1) != 0 ? 1.0 : -1.0, (k >> 1) != 0 ? 1.0 : -1.0);
            h.gradients += 0.25 * texture(uGradients, at / vec2(size)).xyz;
        }
    }
    return h;
}

// Eq. 6 over the four lattice samples around the pixel, this frame's: rgb h~, a w~. `own`
// is set to the pixel's own sample when this frame shaded it, on the pixel's surface.
vec4 spatialEstimate(ivec2 p, float z, uint id, float gamma, out vec4 own) {
    own = vec4(0.0);
    vec2 centre = vec2(p) + 0.5;
    ivec2 lowSize = textureSize(uLowColour, 0);
    ivec2 cell = (p - uPhase) / uStep;  // towards zero; corrected below for the first row/column
    if (p.x < uPhase.x) cell.x = -1;
    if (p.y < uPhase.y) cell.y = -1;
    float sigmaD = 0.03 * (uFar - uNear);
    float r = length(vec2(uStep));  // the low-resolution pixel's diagonal, in pixels
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 j = cell + ivec2(k & 1, k >> 1);
        if (any(lessThan(j, ivec2(0))) || any(greaterThanEqual(j, lowSize))) continue;
        ivec2 at = j * uStep + uPhase;  // where sample j was shaded, in pixels
        float zj = linearDepth(texelFetch(uLowDepth, j, 0).r);
        float dz = z - zj;
        float w = falloff(dz * dz, sigmaD * sigmaD, 3.0) * falloff(distance(centre, vec2(at) + 0.5), r, gamma);
        bool sameId = texelFetch(uLowIds, j, 0).r == id;
        if (!sameId) w *= kEpsilon;
        vec3 colour = texelFetch(uLowColour, j, 0).rgb;
        if (at == p && sameId && abs(dz) <= uDepthTolerance * min(z, zj)) own = vec4(colour, 1.0);
        sum += w * colour;
        weight += w;
    }
    return vec4(weight > 0.0 ? sum / weight : vec3(0.0), weight);
}

void main() {
    ivec2 size = textureSize(uDepth, 0);
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec2 centre = vec2(p) + 0.5;
    float depth = texelFetch(uDepth, p, 0).r;
    uint id = texelFetch(uIds, p, 0).r;
    float z = linearDepth(depth);

    // Reprojection into the previous frame: the surface point, moved back by its own velocity,
    // seen by the previous camera.
    vec2 ndc = centre / vec2(size) * 2.0 - 1.0;
    // The camera's part goes through one matrix multiplied in double, so that a still camera's
    // reprojection is the identity to float rounding and a still pixel lands on its own texel
    // centre (uStillTolerance); through the two float matrices most pixels of a still 1080p
    // frame land more than 0.001 px off.
    vec4 x = vec4(ndc, 2.0 * depth - 1.0, 1.0);
    float w = (uInverseViewProjection * x).w;  // world = (uInverseViewProjection x) / w
    vec3 moved = texelFetch(uVelocity, p, 0).xyz * uDt;
    vec4 clip = uReprojection * x / w - uPreviousViewProjection * vec4(moved, 0.0);
    History history = History(false, false, vec4(0.0), vec3(0.0), false, 1.0);
    if (uHaveHistory != 0 && clip.w > 0.0)
        history = fetchHistory((clip.xy / clip.w * 0.5 + 0.5) * vec2(size), clip.w, id, size);
    bool reprojected = history.found;

    // The last three gradients' share of the weighted sum |(0.4, 0.3, 0.2, 0.1) . grad|; this
    // frame's (weight 0.4) is added once h~ is known.
    vec3 gradients = history.gradients;
    float smoothed = 0.3 * gradients.x + 0.2 * gradients.y + 0.1 * gradients.z;

    // k's fall-off is gamma w_f, at most 4 (section 3.5); w_f is estimated here from the last
    // three gradients alone (their weighted mean), as h~ is what k makes.
    float wf0 = reprojected ? pow(1.0 - clamp(abs(smoothed) / 0.6, 0.0, 1.0), 2.0) : 0.0;
    vec4 own;
    vec4 estimate = spatialEstimate(p, z, id, 4.0 * wf0, own);
    float weight = estimate.a;
    vec3 spatial = weight > 0.0 ? estimate.rgb : history.value.rgb;

    // This frame's relative temporal gradient (section 3.5.1), from h~ against the history; the
    // largest possible where the history was lost (disocclusions), so that it spreads. A still
    // pixel shaded this frame measures its change exactly, its own sample against its history;
    // one not shaded this frame whose history is its own sample has no new measure (h~ against
    // it is only h~'s aliasing) and keeps its last.
    bool shadedNow = history.still && own.a > 0.0;
    bool ownHistory = history.still && history.own;
    float g0 = 1.0;
    if (reprojected) g0 = relativeGradient(spatial, history.value.rgb);
    if (shadedNow) g0 = relativeGradient(own.rgb, history.value.rgb);
    else if (ownHistory) g0 = history.gradient;
    float grad = clamp(abs(0.4 * g0 + smoothed), 0.0, 1.0);
    float wf = reprojected ? (1.0 - grad) * (1.0 - grad) : 0.0;  // eq. 8 with a = 1

    float hw = reprojected ? history.value.a : 0.0;
    // k towards its dirac where the history is the pixel's own sample, as far as w_f trusts it.
    float spatialWeight = ownHistory ? weight * (1.0 - wf) : weight;
    float total = spatialWeight + wf * hw;
    vec3 colour = (spatial * spatialWeight + wf * hw * history.value.rgb) / max(total, 1e-6);
    vec3 kept = colour;  // what the history keeps for the next frame
    bool nextOwn = false;
    if (shadedNow) {
        colour = kept = own.rgb;  // eq. 4's w_t = 1: the pixel's own sample, shaded at this instant
        nextOwn = true;
    } else if (ownHistory) {
        kept = history.value.rgb;  // the neighbours may lend the picture, not the history
        nextOwn = true;
    }
    float newWeight = min(total, uMaxHistoryWeight);

    outColour = vec4(clamp(colour, 0.0, 1.0), 1.0);
    outId = id;
    float none = uintBitsToFloat(0x7fc00000u);  // no correspondence claimed
    outCorrespondence = vec4(none);
    outHistory = vec4(kept, newWeight);
    outGradients = vec4(g0, gradients.x, gradients.y, nextOwn ? 1.0 : 0.0);
}

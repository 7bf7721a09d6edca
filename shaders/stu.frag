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
// Rows are GL's (bottom-up) throughout.

uniform sampler2D uDepth;          // this frame's geometry pass, full resolution
uniform usampler2D uIds;
uniform sampler2D uVelocity;       // world-space m/s
uniform sampler2D uLowColour;      // this frame's lattice, shaded
uniform sampler2D uLowDepth;
uniform usampler2D uLowIds;
uniform sampler2D uHistory;        // rgb: h_r, a: h_w (previous frame)
uniform sampler2D uGradients;      // x, y, z: the last three relative gradients (previous frame)
uniform sampler2D uPreviousDepth;  // the previous frame's geometry pass
uniform usampler2D uPreviousIds;

uniform ivec2 uStep;               // lattice step: one pixel of each uStep.x x uStep.y block shaded
uniform ivec2 uPhase;              // which one, this frame
uniform mat4 uInverseViewProjection;
uniform mat4 uPreviousViewProjection;
uniform float uDt;                 // seconds since the previous frame
uniform float uNear;
uniform float uFar;
uniform int uHaveHistory;
uniform float uMaxHistoryWeight;
uniform float uDepthTolerance;     // relative, for the disocclusion test

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
    vec4 world = uInverseViewProjection * vec4(ndc, 2.0 * depth - 1.0, 1.0);
    vec3 point = world.xyz / world.w - texelFetch(uVelocity, p, 0).xyz * uDt;
    vec4 clip = uPreviousViewProjection * vec4(point, 1.0);
    vec2 q = (clip.xy / clip.w * 0.5 + 0.5) * vec2(size);  // continuous, pixel centres at +0.5
    float expected = clip.w;  // the point's view depth in the previous frame

    // History: bilinear over the four texels around q, each kept only if it shows the same
    // object at the depth the point had (Herzog et al.'s depth and id test, Figure 3).
    vec4 history = vec4(0.0);
    vec3 gradients = vec3(0.0);
    float historyWeight = 0.0;
    if (uHaveHistory != 0 && clip.w > 0.0) {
        vec2 base = q - 0.5;
        ivec2 t0 = ivec2(floor(base));
        vec2 f = base - vec2(t0);
        for (int k = 0; k < 4; ++k) {
            ivec2 t = t0 + ivec2(k & 1, k >> 1);
            if (any(lessThan(t, ivec2(0))) || any(greaterThanEqual(t, size))) continue;
            if (texelFetch(uPreviousIds, t, 0).r != id) continue;
            float previous = linearDepth(texelFetch(uPreviousDepth, t, 0).r);
            if (abs(previous - expected) > uDepthTolerance * min(previous, expected)) continue;
            float w = ((k & 1) != 0 ? f.x : 1.0 - f.x) * ((k >> 1) != 0 ? f.y : 1.0 - f.y);
            history += w * texelFetch(uHistory, t, 0);
            historyWeight += w;
        }
    }
    bool reprojected = historyWeight > 1e-4;
    if (reprojected) {
        history /= historyWeight;
        // The last gradients, low-passed over a lattice cell around q (four bilinear taps half a
        // step away) as the paper low-passes them with a mipmap: aliasing shows as a gradient
        // that changes sign from pixel to pixel and frame to frame, and averages away.
        vec2 half_ = 0.5 * vec2(uStep);
        for (int k = 0; k < 4; ++k) {
            vec2 at = q + half_ * vec2((k & 1) != 0 ? 1.0 : -1.0, (k >> 1) != 0 ? 1.0 : -1.0);
            gradients += 0.25 * texture(uGradients, at / vec2(size)).xyz;
        }
    }

    // The last three gradients' share of the weighted sum |(0.4, 0.3, 0.2, 0.1) . grad|; this
    // frame's (weight 0.4) is added once h~ is known.
    float smoothed = 0.3 * gradients.x + 0.2 * gradients.y + 0.1 * gradients.z;

    // Spatial: the four lattice samples around the pixel, this frame's.
    ivec2 lowSize = textureSize(uLowColour, 0);
    ivec2 cell = (p - uPhase) / uStep;  // towards zero; corrected below for the first row/column
    if (p.x < uPhase.x) cell.x = -1;
    if (p.y < uPhase.y) cell.y = -1;
    float sigmaD = 0.03 * (uFar - uNear);
    float r = length(vec2(uStep));  // the low-resolution pixel's diagonal, in pixels
    // k's fall-off is gamma w_f, at most 4 (section 3.5); w_f is estimated here from the last
    // three gradients alone (their weighted mean), as h~ is what k makes.
    float wf0 = reprojected ? pow(1.0 - clamp(abs(smoothed) / 0.6, 0.0, 1.0), 2.0) : 0.0;
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 j = cell + ivec2(k & 1, k >> 1);
        if (any(lessThan(j, ivec2(0))) || any(greaterThanEqual(j, lowSize))) continue;
        vec2 at = vec2(j * uStep + uPhase) + 0.5;  // where sample j was shaded, in pixels
        float zj = linearDepth(texelFetch(uLowDepth, j, 0).r);
        float dz = z - zj;
        float w = falloff(dz * dz, sigmaD * sigmaD, 3.0) * falloff(distance(centre, at), r, 4.0 * wf0);
        if (texelFetch(uLowIds, j, 0).r != id) w *= kEpsilon;
        sum += w * texelFetch(uLowColour, j, 0).rgb;
        weight += w;
    }
    vec3 spatial = weight > 0.0 ? sum / weight : history.rgb;

    // This frame's relative temporal gradient (section 3.5.1), from h~ against the history; the
    // largest possible where the history was lost (disocclusions), so that it spreads.
    float g0 = 1.0;
    if (reprojected) {
        float a = luma(spatial), b = luma(history.rgb);
        g0 = (a - b) / max(max(abs(a), abs(b)), 1e-3);
    }
    float grad = clamp(abs(0.4 * g0 + smoothed), 0.0, 1.0);
    float wf = reprojected ? (1.0 - grad) * (1.0 - grad) : 0.0;  // eq. 8 with a = 1

    float hw = reprojected ? history.a : 0.0;
    vec3 colour = (spatial * weight + wf * hw * history.rgb) / max(weight + wf * hw, 1e-6);
    float newWeight = min(weight + wf * hw, uMaxHistoryWeight);

    outColour = vec4(clamp(colour, 0.0, 1.0), 1.0);
    outId = id;
    float none = uintBitsToFloat(0x7fc00000u);  // no correspondence claimed
    outCorrespondence = vec4(none);
    outHistory = vec4(colour, newWeight);
    outGradients = vec4(reprojected ? g0 : 1.0, gradients.x, gradients.y, 0.0);
}

#version 410 core
// Disocclusion fix (seed 004 section 5.2.5): a triangle nearly parallel to the source view
// ray is a "rubber sheet" stretched across a depth discontinuity. Its corners are sorted by
// distance from the source eye: the nearest is foreground, the farthest background, the
// middle joins whichever of the two it is closer to. Foreground corners then take the
// background corners' source coordinates, so the sheet shows background colour instead of
// a smear between foreground and background.

layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

in vec3 vSourceH[];
in vec3 vSourceWorld[];
out vec3 gSourceH;
out vec3 gOwnSourceH;     // the corner's own coordinate, before the fix
out float gForeground;    // 1 at recoloured foreground corners, 0 elsewhere

uniform vec3 uSourceEye;
uniform float uGrazingCosine;  // |cos(normal, view ray)| below this = nearly parallel = a sheet
// ...and its corners' distances from the source eye must also differ by more than this ratio:
// a real surface seen at a grazing angle (the hallway's far floor) spans little depth between
// neighbouring pixels, a sheet across a silhouette spans the jump.
uniform float uSheetDepthRatio;
uniform vec2 uTargetSize;  // display size in pixels (a source with a guard band is larger; same pixel pitch)

// A sheet needs fixing only where it opens: its corners spread apart in the *target* view, as
// the foreground moves across the background. Where it does not (the identity warp, a pure
// camera turn) its pixels are the foreground's and the background's own, and recolouring them
// would erode the silhouette. Half a pixel of spread is well above a turn's distortion between
// neighbouring pixels and well below any parallax that uncovers a pixel.
const float kOpensPx = 0.5;

void main() {
    vec3 a = vSourceWorld[0], b = vSourceWorld[1], c = vSourceWorld[2];
    vec3 normal = cross(b - a, c - a);
    vec3 ray = (a + b + c) / 3.0 - uSourceEye;
    float lengths = length(normal) * length(ray);
    // Only triangles between neighbouring source pixels can be sheets: the sparse mesh
    // subdivides every depth jump down to single pixels, so its larger triangles lie on
    // surfaces (a distant floor at a grazing angle spans many metres over one big triangle).
    // A patch subdivided in one direction only leaves one-pixel-wide slivers across its jump;
    // those stay unfixed (measured: counting them as sheets recolours foreground pixels).
    vec2 pa = vSourceH[0].xy / vSourceH[0].z, pb = vSourceH[1].xy / vSourceH[1].z, pc = vSourceH[2].xy / vSourceH[2].z;
    float extent = max(max(distance(pa, pb), distance(pb, pc)), distance(pc, pa));
    bool sheet = extent < 1.5 && lengths > 0.0 && abs(dot(normal, ray)) < uGrazingCosine * lengths;
    vec4 qa = gl_in[0].gl_Position, qb = gl_in[1].gl_Position, qc = gl_in[2].gl_Position;
    if (sheet && qa.w > 0.0 && qb.w > 0.0 && qc.w > 0.0) {
        vec2 ta = qa.xy / qa.w * 0.5 * uTargetSize, tb = qb.xy / qb.w * 0.5 * uTargetSize, tc = qc.xy / qc.w * 0.5 * uTargetSize;
        float targetExtent = max(max(distance(ta, tb), distance(tb, tc)), distance(tc, ta));
        sheet = targetExtent > extent + kOpensPx;
    }

    vec3 sourceH[3] = vec3[3](vSourceH[0], vSourceH[1], vSourceH[2]);
    float foreground[3] = float[3](0.0, 0.0, 0.0);
    if (sheet) {
        float d[3] = float[3](distance(a, uSourceEye), distance(b, uSourceEye), distance(c, uSourceEye));
        int near = 0, far = 0;
        for (int i = 1; i < 3; ++i) {
            if (d[i] < d[near]) near = i;
            if (d[i] > d[far]) far = i;
        }
        if (near != far && d[far] > uSheetDepthRatio * d[near]) {
            int middle = 3 - near - far;
            bool middleIsBackground = (d[far] - d[middle]) < (d[middle] - d[near]);
            // The background corner nearest in depth to the foreground gives its colour.
            int background = middleIsBackground ? middle : far;
            sourceH[near] = vSourceH[background];
            foreground[near] = 1.0;
            if (!middleIsBackground) {
                sourceH[middle] = vSourceH[far];
                foreground[middle] = 1.0;
            }
        }
    }
    for (int i = 0; i < 3; ++i) {
        gl_Position = gl_in[i].gl_Position;
        gSourceH = sourceH[i];
        gOwnSourceH = vSourceH[i];
        gForeground = foreground[i];
        EmitVertex();
    }
    EndPrimitive();
}

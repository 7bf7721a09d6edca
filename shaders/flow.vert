#version 410 core
// Flow fields of bidirectional reprojection (seed 000 eq. 1-2): each vertex at this I-frame's
// instant, and the same surface point at the neighbouring I-frame's instant (the object's
// model there, the camera there). uSky draws one triangle at the far plane first instead, for
// pixels that show no surface. Interpolating the other clip position per fragment gives the
// exact position of the fragment's own surface point, as in Nehab et al.'s reprojection.

layout(location = 0) in vec3 inPosition;

uniform int uSky;
uniform mat4 uModel;
uniform mat4 uOtherModel;
uniform mat4 uView;
uniform mat4 uOtherView;
uniform mat4 uViewProjection;
uniform mat4 uOtherViewProjection;

out vec4 vOtherClip;
out float vViewDepth;
out float vOtherViewDepth;

void main() {
    if (uSky != 0) {
        vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)) * 2.0 - 1.0;
        gl_Position = vec4(p, 1.0, 1.0);
        vOtherClip = vec4(0.0);
        vViewDepth = vOtherViewDepth = 0.0;
        return;
    }
    vec4 world = uModel * vec4(inPosition, 1.0);
    vec4 otherWorld = uOtherModel * vec4(inPosition, 1.0);
    gl_Position = uViewProjection * world;
    vOtherClip = uOtherViewProjection * otherWorld;
    vViewDepth = -(uView * world).z;
    vOtherViewDepth = -(uOtherView * otherWorld).z;
}

#version 410 core
// Conventional renderer, vertex stage: world-space position and normal for Phong shading and
// for the per-fragment velocity of rigid bodies.

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec3 inDiffuse;
layout(location = 3) in vec4 inSpecular;  // rgb = ks, a = shininess

uniform mat4 uModel;
uniform mat3 uNormalMatrix;
uniform mat4 uViewProjection;
// Backward flow, written only when the renderer is asked for it (bidirectional reprojection's
// I-frames, seed 000 eq. 2): the object's model and the camera at the previous I-frame.
// uSky draws one far-plane triangle first, from gl_VertexID, for the sky's flow.
uniform int uSky;
uniform mat4 uOtherModel;
uniform mat4 uView;
uniform mat4 uOtherView;
uniform mat4 uOtherViewProjection;

out vec3 vWorldPosition;
out vec3 vNormal;
out vec3 vDiffuse;
out vec4 vSpecular;
out vec4 vOtherClip;
out float vViewDepth;
out float vOtherViewDepth;

void main() {
    if (uSky != 0) {
        vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)) * 2.0 - 1.0;
        gl_Position = vec4(p, 1.0, 1.0);
        vWorldPosition = vNormal = vDiffuse = vec3(0.0);
        vSpecular = vOtherClip = vec4(0.0);
        vViewDepth = vOtherViewDepth = 0.0;
        return;
    }
    vec4 world = uModel * vec4(inPosition, 1.0);
    vWorldPosition = world.xyz;
    vNormal = uNormalMatrix * inNormal;
    vDiffuse = inDiffuse;
    vSpecular = inSpecular;
    gl_Position = uViewProjection * world;
    vec4 otherWorld = uOtherModel * vec4(inPosition, 1.0);
    vOtherClip = uOtherViewProjection * otherWorld;
    vViewDepth = -(uView * world).z;
    vOtherViewDepth = -(uOtherView * otherWorld).z;
}

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

out vec3 vWorldPosition;
out vec3 vNormal;
out vec3 vDiffuse;
out vec4 vSpecular;

void main() {
    vec4 world = uModel * vec4(inPosition, 1.0);
    vWorldPosition = world.xyz;
    vNormal = uNormalMatrix * inNormal;
    vDiffuse = inDiffuse;
    vSpecular = inSpecular;
    gl_Position = uViewProjection * world;
}

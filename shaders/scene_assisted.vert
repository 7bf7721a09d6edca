#version 410 core
// Scene-assisted reprojection (seed 000 section 4), vertex stage: the scene rasterised at the
// B-frame's instant (depth only, no shading), each vertex also carried to the two I-frames'
// instants (the object's model and the camera there), so every fragment knows exactly where its
// surface point was in both. uSky draws one far-plane triangle first for pixels with no surface.

layout(location = 0) in vec3 inPosition;

uniform int uSky;
uniform mat4 uModel;
uniform mat4 uModel0;
uniform mat4 uModel1;
uniform mat4 uViewProjection;
uniform mat4 uViewProjection0;
uniform mat4 uViewProjection1;

out vec4 vClip0;
out vec4 vClip1;

void main() {
    if (uSky != 0) {
        vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)) * 2.0 - 1.0;
        gl_Position = vec4(p, 1.0, 1.0);
        vClip0 = vClip1 = vec4(0.0);
        return;
    }
    gl_Position = uViewProjection * (uModel * vec4(inPosition, 1.0));
    vClip0 = uViewProjection0 * (uModel0 * vec4(inPosition, 1.0));
    vClip1 = uViewProjection1 * (uModel1 * vec4(inPosition, 1.0));
}

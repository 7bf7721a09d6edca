#version 410 core
// Flow fields, the flow-only pass (the I-frame's colour was rendered before): flowOf in
// flow_common.glsl, with the ids of the surfaces it saw.

in vec4 vOtherClip;
in float vViewDepth;
in float vOtherViewDepth;

uniform int uSky;
uniform uint uObjectId;

layout(location = 1) out uint outId;
layout(location = 2) out vec4 outFlow;

void main() {
    outId = uObjectId;
    outFlow = flowOf(gl_FragCoord.xy, vOtherClip, vViewDepth, vOtherViewDepth, uSky != 0);
}

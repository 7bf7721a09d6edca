#version 410 core
// HUD fill: a solid colour, or a text texture's coverage tinted with that colour.
in vec2 vUv;
uniform sampler2D uText;
uniform int uTextured;
uniform vec4 uColour;

layout(location = 0) out vec4 outColour;

void main() {
    float coverage = uTextured != 0 ? texture(uText, vUv).a : 1.0;
    outColour = vec4(uColour.rgb, uColour.a * coverage);
}

#version 450
layout(set = 0, binding = 0) uniform sampler2D overlay_image;
layout(location = 0) in vec2 in_uv;
layout(location = 0) out vec4 out_colour;
void main() { out_colour = texture(overlay_image, in_uv); }

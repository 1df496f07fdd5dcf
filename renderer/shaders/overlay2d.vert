#version 450
// A screen-space textured rectangle (the colour-map legend). rect: x0, y0, x1, y1 in 0..1 of the
// image (y down).
layout(push_constant) uniform Rect { vec4 rect; } pc;
layout(location = 0) out vec2 out_uv;
void main() {
  vec2 corner = vec2(float(gl_VertexIndex & 1), float((gl_VertexIndex >> 1) & 1));
  out_uv = corner;
  vec2 p = mix(pc.rect.xy, pc.rect.zw, corner);
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}

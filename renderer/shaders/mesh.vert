#version 450
#extension GL_GOOGLE_include_directive : require
#include "frame_data.glsl"

layout(location = 0) in vec3 in_position;  // mesh frame
layout(location = 1) in vec3 in_normal;    // mesh frame
layout(location = 2) in vec2 in_uv;
layout(location = 3) in float in_scalar;   // colour-map value (displacement, curvature)
layout(location = 4) in vec3 in_overlay;   // ROI, fixed, handle weights

layout(location = 0) out vec3 out_position_world;
layout(location = 1) out vec3 out_normal_world;
layout(location = 2) out vec2 out_uv;
layout(location = 3) out vec4 out_aux;

void main() {
  vec4 world = draw.T_world_mesh * vec4(in_position, 1.0);
  out_position_world = world.xyz;
  out_normal_world = mat3(draw.T_world_mesh) * in_normal;  // rotation + uniform scale only
  out_uv = in_uv;
  out_aux = vec4(in_scalar, in_overlay);
  gl_Position = frame.views[draw.view_index].view_projection * world;
}

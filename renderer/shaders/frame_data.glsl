// Shared between mesh.vert and mesh.frag: per-frame data (set 0) and per-draw push constants.
struct ViewData {
  mat4 view_projection;  // world -> clip
  vec4 eye_world;        // xyz: eye position in world
};
layout(set = 0, binding = 0) uniform FrameData {
  ViewData views[2];
  vec4 up_world;         // xyz: world up (studio environment)
  vec4 key_light_dir;    // xyz: direction towards the key light, world
  vec4 colour_params;    // x: scalar_max, y: curvature epsilon, z: exposure, w: show overlays (0/1)
  uvec4 mode;            // x: ColorMode, y: lighting on (1) / flat colours (0)
} frame;

layout(push_constant) uniform DrawData {
  mat4 T_world_mesh;
  uint view_index;
  uint flags;  // bit 0: colour map and overlays apply to this draw
} draw;

#version 450
#extension GL_GOOGLE_include_directive : require
#include "frame_data.glsl"

layout(location = 0) in vec3 in_position_world;
layout(location = 1) in vec3 in_normal_world;
layout(location = 2) in vec2 in_uv;
layout(location = 3) in vec4 in_aux;

layout(set = 1, binding = 0) uniform MaterialData {
  vec4 base_colour;   // linear RGBA
  vec4 emissive;      // rgb
  vec4 factors;       // x metallic, y roughness, z normal scale, w clearcoat
  vec4 factors2;      // x clearcoat roughness, y unlit (0/1), z has normal map (0/1), w occlusion strength
} material;
layout(set = 1, binding = 1) uniform sampler2D base_colour_map;
layout(set = 1, binding = 2) uniform sampler2D metallic_roughness_map;
layout(set = 1, binding = 3) uniform sampler2D normal_map;
layout(set = 1, binding = 4) uniform sampler2D occlusion_map;
layout(set = 1, binding = 5) uniform sampler2D emissive_map;

layout(location = 0) out vec4 out_colour;

const float PI = 3.14159265;

// Displacement colour map: dark blue (0) -> blue -> cyan -> green -> yellow -> red (1).
// Same control points as colormap.cpp (displacement_colour), which the tests and legend use.
vec3 displacement_colour(float t) {
  const vec3 c[6] = vec3[6](vec3(0.05, 0.08, 0.45), vec3(0.10, 0.35, 0.95), vec3(0.10, 0.80, 0.90),
                            vec3(0.20, 0.85, 0.25), vec3(0.98, 0.85, 0.10), vec3(0.85, 0.08, 0.05));
  float x = clamp(t, 0.0, 1.0) * 5.0;
  int i = min(int(floor(x)), 4);
  return mix(c[i], c[i + 1], x - float(i));
}

// The studio: a bright sky dome with two soft-box bands and a dark floor, so that reflections on
// curved car paint draw readable highlight lines. d: unit direction in world; rough: 0..1 blurs.
vec3 studio(vec3 d, float rough) {
  vec3 up = frame.up_world.xyz;
  float y = dot(d, up);
  float w = 0.03 + 0.5 * rough;
  vec3 sky = mix(vec3(0.70, 0.72, 0.75), vec3(0.95, 0.96, 1.0), smoothstep(0.0, 0.8, y));
  vec3 floor_colour = vec3(0.10, 0.10, 0.11);
  vec3 env = mix(floor_colour, sky, smoothstep(-w, w, y));
  float band1 = 1.0 - smoothstep(0.0, 0.06 + 0.4 * rough, abs(y - 0.35));
  float band2 = 1.0 - smoothstep(0.0, 0.04 + 0.4 * rough, abs(y - 0.80));
  env += vec3(1.6) * band1 * (1.0 - 0.7 * rough) + vec3(1.0) * band2 * (1.0 - 0.7 * rough);
  return env;
}

vec3 studio_irradiance(vec3 n) {
  float y = dot(n, frame.up_world.xyz);
  return mix(vec3(0.22, 0.21, 0.20), vec3(0.95, 0.97, 1.0), 0.5 + 0.5 * y);
}

float ggx(float n_dot_h, float a) {
  float a2 = a * a;
  float d = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
  return a2 / (PI * d * d);
}

// Perturbs n by a tangent-space normal using screen-space derivatives (no tangent attribute needed).
vec3 apply_normal_map(vec3 n, vec3 p, vec2 uv, vec3 tangent_normal) {
  vec3 dp1 = dFdx(p);
  vec3 dp2 = dFdy(p);
  vec2 duv1 = dFdx(uv);
  vec2 duv2 = dFdy(uv);
  vec3 dp2perp = cross(dp2, n);
  vec3 dp1perp = cross(n, dp1);
  vec3 t = dp2perp * duv1.x + dp1perp * duv2.x;
  vec3 b = dp2perp * duv1.y + dp1perp * duv2.y;
  float scale = max(dot(t, t), dot(b, b));
  if (scale < 1e-30) return n;
  float inv = inversesqrt(scale);
  return normalize(mat3(t * inv, b * inv, n) * tangent_normal);
}

void main() {
  ViewData view = frame.views[draw.view_index];
  vec3 n = normalize(in_normal_world);
  if (!gl_FrontFacing) n = -n;  // CAD surfaces are open: light both sides
  vec3 v = normalize(view.eye_world.xyz - in_position_world);

  vec4 base = material.base_colour * texture(base_colour_map, in_uv);
  float metallic = material.factors.x;
  float roughness = material.factors.y;
  float clearcoat = material.factors.w;
  uint mode = frame.mode.x;
  float occlusion = 1.0;
  vec3 emissive = vec3(0.0);

  if (material.factors2.y > 0.5) {
    out_colour = vec4(base.rgb, 1.0);  // unlit material: its colour, whatever the mode
    return;
  }
  bool mapped = (draw.flags & 1u) != 0u;
  if (!mapped) mode = 0u;
  if (mode == 0u) {
    vec4 mr = texture(metallic_roughness_map, in_uv);
    roughness *= mr.g;
    metallic *= mr.b;
    occlusion = mix(1.0, texture(occlusion_map, in_uv).r, material.factors2.w);
    emissive = material.emissive.rgb * texture(emissive_map, in_uv).rgb;
    if (material.factors2.z > 0.5) {
      vec3 tn = texture(normal_map, in_uv).xyz * 2.0 - 1.0;
      tn.xy *= material.factors.z;
      n = apply_normal_map(n, in_position_world, in_uv, normalize(tn));
    }
  } else {
    float s = in_aux.x;
    if (mode == 1u) {
      base.rgb = displacement_colour(s / max(frame.colour_params.x, 1e-30));
    } else {
      float eps = frame.colour_params.y;
      base.rgb = s > eps ? vec3(0.98, 0.86, 0.10) : (s < -eps ? vec3(0.12, 0.30, 0.95) : vec3(0.55));
    }
    base.a = 1.0;
    metallic = 0.0;
    roughness = 0.45;
    clearcoat = 0.0;
  }

  if (mapped && frame.colour_params.w > 0.5) {
    // Review overlays: ROI tinted light, fixed vertices blue, handle red (the paper's Fig. 12 top row); fixed and
    // handle together: the handle a press would grab, magenta, a colour no colour map uses (red would vanish on
    // the displacement map's top). On the displacement map the dragged handle is magenta too (red there reads
    // as the legend's largest move).
    if (in_aux.y > 0.5) base.rgb = mix(base.rgb, vec3(0.55, 0.95, 0.55), mode == 0u ? 0.45 : 0.0);
    if (in_aux.z > 0.5 && in_aux.w > 0.5) {
      base.rgb = vec3(0.90, 0.15, 0.95); metallic = 0.0; roughness = 0.5;
    } else {
      if (in_aux.z > 0.5) { base.rgb = vec3(0.10, 0.25, 0.95); metallic = 0.0; roughness = 0.5; }
      if (in_aux.w > 0.5) {
        base.rgb = mode == 1u ? vec3(0.90, 0.15, 0.95) : vec3(0.95, 0.08, 0.06);
        metallic = 0.0; roughness = 0.5;
      }
    }
  }

  if (frame.mode.y == 0u) {
    out_colour = vec4(base.rgb, 1.0);  // flat: exact colours, no tone mapping
    return;
  }
  vec3 l = normalize(frame.key_light_dir.xyz);
  if (mode != 0u) {
    // Colour maps: matte shading that keeps the map's colours recognisable (no tone mapping).
    float hemi = 0.5 + 0.5 * dot(n, frame.up_world.xyz);
    float key = max(dot(n, l), 0.0);
    float shade = 0.38 + 0.30 * hemi + 0.40 * key;
    float spec = 0.18 * pow(max(dot(reflect(-v, n), l), 0.0), 30.0);
    out_colour = vec4(min(base.rgb * shade + vec3(spec), vec3(1.0)), 1.0);
    return;
  }
  vec3 colour;
  {
    roughness = clamp(roughness, 0.04, 1.0);
    float n_dot_v = max(dot(n, v), 1e-4);
    vec3 f0 = mix(vec3(0.04), base.rgb, metallic);
    vec3 fresnel = f0 + (max(vec3(1.0 - roughness), f0) - f0) * pow(1.0 - n_dot_v, 5.0);
    vec3 diffuse_colour = base.rgb * (1.0 - metallic);

    // Environment (hemisphere irradiance + studio reflection).
    vec3 r = reflect(-v, n);
    colour = occlusion * (diffuse_colour * studio_irradiance(n) * 0.5 +
                          fresnel * studio(r, roughness) * (1.0 - 0.5 * roughness));

    // Key light.
    float n_dot_l = max(dot(n, l), 0.0);
    vec3 h = normalize(l + v);
    float a = roughness * roughness;
    float k = a * 0.5;
    float vis = 0.25 / ((n_dot_l * (1.0 - k) + k) * (n_dot_v * (1.0 - k) + k));
    vec3 f_l = f0 + (1.0 - f0) * pow(1.0 - max(dot(v, h), 0.0), 5.0);
    colour += (diffuse_colour / PI * (1.0 - f_l) + ggx(max(dot(n, h), 0.0), a) * vis * f_l) * n_dot_l * 2.3;

    // Clear coat: a sharp dielectric layer on top (car paint).
    if (clearcoat > 0.0) {
      float fc = 0.04 + 0.96 * pow(1.0 - n_dot_v, 5.0);
      float cr = clamp(material.factors2.x, 0.03, 1.0);
      colour = colour * (1.0 - clearcoat * fc) + clearcoat * fc * studio(r, cr);
    }
    colour += emissive;
  }
  colour *= frame.colour_params.z;
  // Filmic-ish tone map that keeps mid tones (Reinhard on luminance-preserving curve).
  colour = colour / (1.0 + 0.35 * colour);
  out_colour = vec4(colour * 1.2, 1.0);
}

#version 330 core
// Lueur's display transform on the GPU. The textures hold the tracer's per-pass *sums*; the image is
//   sum over slots of scale[slot] * texture[slot],  scale = weight / frames,
// then exposure (2^stops), a tone map and the sRGB curve. The CPU reference is src/render/tonemap.h.

uniform sampler2D u_slot0;
uniform sampler2D u_slot1;
uniform sampler2D u_slot2;
uniform sampler2D u_slot3;
uniform vec4 u_scale;        // weight / frames per slot; 0 for a slot not shown
uniform float u_exposure;    // stops
uniform int u_tonemap;       // 0 none, 1 Reinhard, 2 ACES fit
uniform vec4 u_rect;         // image rectangle in window pixels: x, y (bottom-left), width, height

out vec4 frag_color;

float aces_fit(float x) {
  return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

float linear_to_srgb(float x) {
  x = clamp(x, 0.0, 1.0);
  return x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1.0 / 2.4) - 0.055;
}

void main() {
  vec2 uv = (gl_FragCoord.xy - u_rect.xy) / u_rect.zw;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) {
    frag_color = vec4(0.0, 0.0, 0.0, 1.0);
    return;
  }
  // The film's first row is the top of the image; GL's first row is the bottom.
  vec2 st = vec2(uv.x, 1.0 - uv.y);
  vec3 c = u_scale.x * texture(u_slot0, st).rgb + u_scale.y * texture(u_slot1, st).rgb +
           u_scale.z * texture(u_slot2, st).rgb + u_scale.w * texture(u_slot3, st).rgb;
  c *= exp2(u_exposure);
  if (u_tonemap == 1) {
    c = c / (vec3(1.0) + c);
  } else if (u_tonemap == 2) {
    c = vec3(aces_fit(c.r), aces_fit(c.g), aces_fit(c.b));
  }
  c = vec3(linear_to_srgb(c.r), linear_to_srgb(c.g), linear_to_srgb(c.b));
  if (any(isnan(c))) c = vec3(0.0);
  frag_color = vec4(c, 1.0);
}

// Linear light from a model of sRGB-encoded values (docs/design.md §14): the GLSL twin of
// decode_expectation (model/model_colour.hpp). Each channel c with STOCHTEX_DECODE[c] becomes
// D(v, r(w)) = E[decode(v + r(w) Z)], v the method's filtered value and r(w) the deviation that a
// footprint of width w = |det(dpdx, dpdy)|^(1/2) removed from the channel; a point sample
// (w <= 1) is decoded exactly. D and r are the CPU's tables, read with its bilinear formulas:
//   stochtex_decoded: D, STOCHTEX_DEVIATION_CELLS + 1 rows of STOCHTEX_MEAN_CELLS + 1 means, four
//                     consecutive means per RGBA texel (mean m in texel m / 4, component m % 4);
//   stochtex_removed: r, one RGBA texel per width step (channel c in component c).
// Requires the constants that colour_library (colour.cpp) writes before it, STOCHTEX_DECODE
// among them.

uniform sampler2D stochtex_decoded;
uniform sampler2D stochtex_removed;

float stochtex_srgb_decode(float v) {
  return v <= 0.04045 ? v * (1.0 / 12.92) : pow((v + 0.055) * (1.0 / 1.055), 2.4);
}

float stochtex_decoded_at(int m, int s) {
  return texelFetch(stochtex_decoded, ivec2(m / 4, s), 0)[m % 4];
}

float stochtex_expected_decoded(float mean, float deviation) {
  if (!(deviation > 0.0)) return stochtex_srgb_decode(mean);
  float u = (clamp(mean, STOCHTEX_MEAN_LOW, STOCHTEX_MEAN_HIGH) - STOCHTEX_MEAN_LOW) *
            (float(STOCHTEX_MEAN_CELLS) / (STOCHTEX_MEAN_HIGH - STOCHTEX_MEAN_LOW));
  float v = sqrt(min(deviation, STOCHTEX_DEVIATION_HIGH) * (1.0 / STOCHTEX_DEVIATION_HIGH)) *
            float(STOCHTEX_DEVIATION_CELLS);
  int m = min(int(u), STOCHTEX_MEAN_CELLS - 1);
  int s = min(int(v), STOCHTEX_DEVIATION_CELLS - 1);
  float fu = u - float(m);
  float fv = v - float(s);
  float a = stochtex_decoded_at(m, s);
  float b = stochtex_decoded_at(m + 1, s);
  float c = stochtex_decoded_at(m, s + 1);
  float d = stochtex_decoded_at(m + 1, s + 1);
  float low = a + fu * (b - a);
  float high = c + fu * (d - c);
  return low + fv * (high - low);
}

vec4 stochtex_removed_deviation(float width) {
  if (!(width > 1.0)) return vec4(0.0);
  float step = min(log2(width) * float(STOCHTEX_REMOVED_STEPS_PER_OCTAVE),
                   float(STOCHTEX_REMOVED_STEPS - 1));
  int k = min(int(step), STOCHTEX_REMOVED_STEPS - 2);
  float t = step - float(k);
  vec4 low = texelFetch(stochtex_removed, ivec2(k, 0), 0);
  vec4 high = texelFetch(stochtex_removed, ivec2(k + 1, 0), 0);
  return low + t * (high - low);
}

// `value` of a footprint of width `width` as linear light.
vec4 stochtex_linear_light_of_width(vec4 value, float width) {
  vec4 removed = stochtex_removed_deviation(width);
  for (int c = 0; c < 4; ++c)
    if (STOCHTEX_DECODE[c]) value[c] = stochtex_expected_decoded(value[c], removed[c]);
  return value;
}

// A planar footprint's width: |det(dpdx, dpdy)|^(1/2).
vec4 stochtex_linear_light(vec4 value, vec2 dpdx, vec2 dpdy) {
  return stochtex_linear_light_of_width(value, sqrt(abs(dpdx.x * dpdy.y - dpdx.y * dpdy.x)));
}

// A surface point's: the square root of the area its 3-D footprint covers, |dpdx x dpdy|^(1/2)
// (decode_surface).
vec4 stochtex_surface_linear_light(vec4 value, vec3 dpdx, vec3 dpdy) {
  return stochtex_linear_light_of_width(value, sqrt(length(cross(dpdx, dpdy))));
}

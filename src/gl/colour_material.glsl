// Linear light for a material's sRGB maps (export-shader of a material, src/gl/colour.cpp): what
// colour.glsl does for a model of one image, for channel c of up to 16, whose removed deviation
// r(w) is in row c / 4, component c % 4 of stochtex_removed (one RGBA texel per width step), as
// decode_expectation reads the CPU's table (model/model_colour.hpp). Compiled after colour.glsl.

float stochtex_removed_channel(float width, int c) {
  if (!(width > 1.0)) return 0.0;
  float step = min(log2(width) * float(STOCHTEX_REMOVED_STEPS_PER_OCTAVE),
                   float(STOCHTEX_REMOVED_STEPS - 1));
  int k = min(int(step), STOCHTEX_REMOVED_STEPS - 2);
  float t = step - float(k);
  float low = texelFetch(stochtex_removed, ivec2(k, c / 4), 0)[c % 4];
  float high = texelFetch(stochtex_removed, ivec2(k + 1, c / 4), 0)[c % 4];
  return low + t * (high - low);
}

// Channel c's filtered value `value` of a footprint of width `width` (|det(dpdx, dpdy)|^(1/2)) as
// linear light: D(value, r_c(width)).
float stochtex_material_linear_light(float value, float width, int c) {
  return stochtex_expected_decoded(value, stochtex_removed_channel(width, c));
}

// Texton noise of a material beyond 4 channels (`export-shader`, material_shader in gl_data.cpp):
// every channel at p, summed chunk by chunk of 4 channels from the same impulses (same cells,
// seed and draws), as the renderer's chunks (gl_pass.cpp) and TextonModel::evaluate_typed compute
// them. Compiled after noise.glsl, with the atlas read of the chunk `texton_chunk` and the
// constants TEXTON_MATERIAL_CHANNELS, TEXTON_MATERIAL_CONSTANT and TEXTON_MATERIAL_MEAN (one per
// channel).
float[TEXTON_MATERIAL_CHANNELS] texton_channels(vec2 p, vec2 dpdx, vec2 dpdy, uint seed) {
  TextonFilter f = texton_filter(dpdx, dpdy);
  float channels[TEXTON_MATERIAL_CHANNELS];
  for (int first = 0; first < TEXTON_MATERIAL_CHANNELS; first += 4) {
    texton_chunk = first / 4;
    vec4 acc = texton_sum_impulses(p, uvec2(0u), seed, f);
    // texton_output (noise.glsl) per channel: the fade scales the fluctuation only.
    for (int c = first; c < min(first + 4, TEXTON_MATERIAL_CHANNELS); ++c) {
      float noise =
          acc[c - first] * TEXTON_INVERSE_SQRT_INTENSITY + TEXTON_MATERIAL_CONSTANT[c] -
          TEXTON_MATERIAL_MEAN[c];
      channels[c] = TEXTON_MATERIAL_MEAN[c] + f.fade * noise;
    }
  }
  return channels;
}

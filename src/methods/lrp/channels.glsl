// Local random-phase noise of a material beyond 4 channels (`export-shader`, Twin::shader in
// gl_data.cpp): every channel at p, LrpModel::evaluate_typed's sums in its order (each channel's
// strata, then mean + basis * noise over the N channels). Compiled after evaluate.glsl, with the
// constants LRP_MATERIAL_CHANNELS, LRP_MATERIAL_MEAN (one per channel) and LRP_TURBULENCE_AXES.
// Section 5's structure is refused beyond 4 channels (gl_data.cpp).
float[LRP_MATERIAL_CHANNELS] lrp_channels(vec2 p, vec2 dpdx, vec2 dpdy, uint seed) {
  float noise[LRP_MATERIAL_CHANNELS];
  for (int c = 0; c < LRP_MATERIAL_CHANNELS; ++c) noise[c] = 0.0;
  for (int s = 0; s < LRP_STRATA_TOTAL; ++s) {
    if (LRP_STRATUM_AMPLITUDE[s] == 0.0) continue;
    // channel_stream (structure.hpp): channels from 4 on skip the turbulence axes' keys.
    int channel = LRP_STRATUM_CHANNEL[s];
    int stream = channel < LRP_TURBULENCE_STREAM_BASE ? channel : channel + LRP_TURBULENCE_AXES;
    uint stratum_seed = cell_key(uint(stream), uint(s % LRP_STRATA), seed, STREAM_PHASES);
    noise[channel] += lrp_stratum_noise(s, p / LRP_STRATUM_SPACING[s], uvec2(0u), stratum_seed,
                                        true, dpdx, dpdy);
  }
  float channels[LRP_MATERIAL_CHANNELS];
  for (int c = 0; c < LRP_MATERIAL_CHANNELS; ++c) {
    channels[c] = LRP_MATERIAL_MEAN[c];
    for (int k = 0; k < LRP_MATERIAL_CHANNELS; ++k)
      channels[c] += LRP_BASIS[c * LRP_MATERIAL_CHANNELS + k] * noise[k];
  }
  return channels;
}

// The colour of Gabor noise of more than 4 channels (a material's maps, up to kMaxChannels), for
// noise.glsl in colour.glsl's place: an array of GABOR_CHANNELS floats (GABOR_COLOUR) instead of a
// vec4, GABOR_MEAN an array of GABOR_CHANNELS and GABOR_MIXING of GABOR_CHANNELS^2 floats
// (gl_data.cpp); noise.glsl's entry point is then gabor_channels. Same sums, in the same order, as
// mix_to_colour.
#define GABOR_COLOUR float[GABOR_CHANNELS]
#define GABOR_CHANNEL_ARRAY

// colour = mean + mixing * noise (section 7; mix_to_colour in model.cpp).
GABOR_COLOUR gabor_colour(GABOR_COLOUR noise) {
  precise GABOR_COLOUR colour;
  for (int c = 0; c < GABOR_CHANNELS; ++c) {
    colour[c] = GABOR_MEAN[c];
    for (int k = 0; k < GABOR_CHANNELS; ++k)
      colour[c] += GABOR_MIXING[c * GABOR_CHANNELS + k] * noise[k];
  }
  return colour;
}

GABOR_COLOUR gabor_zero() {
  GABOR_COLOUR zero;
  for (int c = 0; c < GABOR_CHANNELS; ++c) zero[c] = 0.0;
  return zero;
}

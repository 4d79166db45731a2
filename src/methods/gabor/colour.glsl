// The colour of Gabor noise of 1 to 4 channels, a vec4 (GABOR_COLOUR), for noise.glsl; beyond 4
// channels colour_channels.glsl stands in its place.
#define GABOR_COLOUR vec4

// colour = mean + mixing * noise (section 7; mix_to_colour in model.cpp): the planar noise's and
// surface noise's (surface.glsl).
vec4 gabor_colour(vec4 noise) {
  precise vec4 colour = GABOR_MEAN;
  for (int c = 0; c < GABOR_CHANNELS; ++c)
    for (int k = 0; k < GABOR_CHANNELS; ++k)
      colour[c] += GABOR_MIXING[c * GABOR_CHANNELS + k] * noise[k];
  return colour;
}

vec4 gabor_zero() {
  return vec4(0.0);
}

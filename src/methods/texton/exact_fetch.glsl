// B-spline interpolation weights of order TEXTON_ORDER at texel coordinate u (BsplineKernel).
int texton_weights(float u, out float w[6]) {
  for (int i = 0; i < 6; ++i) w[i] = 0.0;
  if (TEXTON_ORDER == 0) {
    w[0] = 1.0;
    return int(floor(u + 0.5));
  }
  float cell = floor(u);
  float t = u - cell;
  int first = int(cell) - (TEXTON_ORDER - 1) / 2;
  if (TEXTON_ORDER == 1) {
    w[0] = 1.0 - t;
    w[1] = t;
  } else if (TEXTON_ORDER == 3) {
    float s = 1.0 - t;
    float t2 = t * t;
    float t3 = t2 * t;
    w[0] = s * s * s * (1.0 / 6.0);
    w[1] = (4.0 - 6.0 * t2 + 3.0 * t3) * (1.0 / 6.0);
    w[2] = (1.0 + 3.0 * t + 3.0 * t2 - 3.0 * t3) * (1.0 / 6.0);
    w[3] = t3 * (1.0 / 6.0);
  } else {
    float s = 1.0 - t;
    float t2 = t * t;
    float t3 = t2 * t;
    float t4 = t3 * t;
    float t5 = t4 * t;
    w[0] = s * s * s * s * s * (1.0 / 120.0);
    w[1] = (26.0 - 50.0 * t + 20.0 * t2 + 20.0 * t3 - 20.0 * t4 + 5.0 * t5) * (1.0 / 120.0);
    w[2] = (66.0 - 60.0 * t2 + 30.0 * t4 - 10.0 * t5) * (1.0 / 120.0);
    w[3] = (26.0 + 50.0 * t + 20.0 * t2 - 20.0 * t3 - 20.0 * t4 + 10.0 * t5) * (1.0 / 120.0);
    w[4] = (1.0 + 5.0 * t + 10.0 * t2 + 10.0 * t3 + 5.0 * t4 - 5.0 * t5) * (1.0 / 120.0);
    w[5] = t5 * (1.0 / 120.0);
  }
  return first;
}

// Adds weight * h_level(d) to acc (accumulate_texton in evaluate.hpp) for the texton whose pyramid
// starts at atlas texel `atlas`.
void texton_accumulate(ivec2 atlas, int level, float dx, float dy, float weight, inout vec4 acc) {
  float half_width = TEXTON_LEVEL_HALF_WIDTH[level];
  if (abs(dx) >= half_width || abs(dy) >= half_width) return;
  float wx[6];
  float wy[6];
  float inverse_spacing = 1.0 / TEXTON_LEVEL_SPACING[level];
  int x0 = texton_weights((dx - TEXTON_LEVEL_FIRST_TEXEL[level]) * inverse_spacing, wx);
  int y0 = texton_weights((dy - TEXTON_LEVEL_FIRST_TEXEL[level]) * inverse_spacing, wy);
  ivec2 base =
      atlas + ivec2(x0 + TEXTON_PADDING, TEXTON_LEVEL_ROW[level] + y0 + TEXTON_PADDING);
  for (int j = 0; j <= TEXTON_ORDER; ++j)
    for (int i = 0; i <= TEXTON_ORDER; ++i)
      acc += (weight * wy[j] * wx[i]) * texton_atlas_texel(base + ivec2(i, j));
}


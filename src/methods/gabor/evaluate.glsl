#ifdef STOCHTEX_FLOAT
// Gabor noise by example in GLSL without doubles: the float-only variant of the GLSL twin of
// GaborModel::evaluate (model.cpp), made from the same source (glsl_precision_variant) and run by
// `render --backend gl --gl-filter hardware`. Same hash, streams, draws and maths as the C++ and
// the double variant; what is float here is the filter maths, the positions and the cell
// arithmetic, so the CPU and GPU agree to about 1e-5 of the image's standard deviation rather than
// byte for byte (tests/gl/gabor_gl_test.cpp, docs/methods/gabor.md). Requires random.glsl and
// float_math.glsl, then the model's constants (gabor_glsl() in gl_data.cpp:
// GABOR_CHANNELS, GABOR_GRIDS, GABOR_GRID_ARRAY, GABOR_DATA_WIDTH, GABOR_MIXING, GABOR_MEAN and the
// GABOR_GRID_* arrays, one entry per Poisson grid) and `vec4 gabor_texel(int index)`:
// texel i < GABOR_GAUSSIANS is Gaussian i in grid order (frequency x, frequency y, alias
// probability, alias index relative to its grid); grid g's Poisson CDF (96 floats) fills the 24
// texels from GABOR_GRID_CDF[g]. Texels are read with texelFetch (exact floats).
//
// Positions come split as on the CPU: per grid, a 64-bit cell index of the grid's level-0 cells
// and a float offset from that cell's corner (gabor_noise); the cells the sum visits are then
// small integers relative to it, and their hash keys the low 32 bits of the sum, so a position
// 1e7 pixels out is as precise as one near 0. `precise` keeps the compiler from fusing a * b + c.
#else
// Gabor noise by example in GLSL: the twin of GaborModel::evaluate (model.cpp), same hash, same
// streams, same draws (Poisson counts, positions, alias column and coin, phase) in the same order,
// same constants and the same arithmetic statement for statement, exp and cos included (the CPU's
// float polynomials, float_math.glsl), so the CPU and GPU give the same bytes (measured on
// llvmpipe). Requires random.glsl and float_math.glsl, then the model's constants (gabor_glsl() in
// gl_data.cpp writes them: GABOR_CHANNELS, GABOR_GRIDS, GABOR_DATA_WIDTH, GABOR_MIXING, GABOR_MEAN and
// the GABOR_GRID_* arrays, one entry per Poisson grid) and `vec4 gabor_texel(int index)`:
// texel i < GABOR_GAUSSIANS is Gaussian i in grid order (frequency x, frequency y, alias
// probability, alias index relative to its grid); grid g's Poisson CDF (96 floats) fills the 24
// texels from GABOR_GRID_CDF[g]. Texels are read with texelFetch (exact floats).
//
// Positions, cell indices and the kernel-independent filter maths are doubles, as in the C++:
// the offset of a sample from a cell corner is then the same float on both sides, so every
// kernel's truncation test (envelope < pi, a jump of e^-pi of the kernel) decides the same way.
// `precise` keeps the compiler from fusing a * b + c into an fma the C++ does not use.

#endif
// GABOR_PI, GABOR_PI_F, GABOR_TAPER_SCALE, GABOR_PIXEL_VARIANCE, GABOR_NEGLIGIBLE_ATTENUATION and
// GABOR_MAX_LEVEL_RATIO (2^kMaxLevels) are the C++ constants of model.hpp, declared before this
// file from Twin::kConstants (gl_twin.hpp).

// How one grid is evaluated for one footprint: the kernel envelope exp(-x^T E x), the frequency
// map omega' = F omega and attenuation exp(-omega^T D omega), the amplitude, the thinning level
// and the reach of the kernels. The C++ computes these per sample inside the grid loop.
struct GaborGridFilter {
  bool skip;
  bool filtered;
  int level;
  float ex, exy, ey;
  float fxx, fxy, fyy;
  float dxx, dxy, dyy;
  float amplitude;
  double reach;
  double cell_size;
};

bool gabor_finite(double x) {
  return !isnan(x) && !isinf(x);
}

GaborGridFilter gabor_grid_filter(int g, dvec2 dpdx, dvec2 dpdy) {
  GaborGridFilter f;
  f.skip = false;
  f.filtered = false;
  double a = double(GABOR_GRID_BANDWIDTH[g]);
  precise double a2 = a * a;
  precise double e00 = GABOR_PI * a2;
  precise double e01 = 0.0lf;
  precise double e11 = GABOR_PI * a2;
  precise double f00 = 1.0lf, f01 = 0.0lf, f11 = 1.0lf;
  precise double d00 = 0.0lf, d01 = 0.0lf, d11 = 0.0lf;
  precise double gain = 1.0lf;
  precise double reach = GABOR_GRID_RADIUS[g];
  // The footprint's box covariance beyond one exemplar pixel's I / 12 (see model.cpp); a zero
  // footprint gives q = 0, the point sample.
  precise double q00 = (dpdx.x * dpdx.x + dpdy.x * dpdy.x) / 12.0lf;
  precise double q01 = (dpdx.x * dpdx.y + dpdy.x * dpdy.y) / 12.0lf;
  precise double q11 = (dpdx.y * dpdx.y + dpdy.y * dpdy.y) / 12.0lf;
  precise double centre = 0.5lf * (q00 + q11);
  precise double radius = sqrt(0.25lf * (q00 - q11) * (q00 - q11) + q01 * q01);
  precise double major = centre + radius - GABOR_PIXEL_VARIANCE;
  precise double minor = centre - radius - GABOR_PIXEL_VARIANCE;
  if (major <= 0.0lf) {
    q00 = 0.0lf;
    q01 = 0.0lf;
    q11 = 0.0lf;
  } else if (minor < 0.0lf) {
    precise double lambda_min = centre - radius;
    precise double axis_scale = major / (2.0lf * radius);
    q00 = axis_scale * (q00 - lambda_min);
    q01 = axis_scale * q01;
    q11 = axis_scale * (q11 - lambda_min);
  } else {
    q00 -= GABOR_PIXEL_VARIANCE;
    q11 -= GABOR_PIXEL_VARIANCE;
  }
  q00 *= 2.0lf * GABOR_PI * GABOR_PI;
  q01 *= 2.0lf * GABOR_PI * GABOR_PI;
  q11 *= 2.0lf * GABOR_PI * GABOR_PI;
  if (q00 + q11 > 0.0lf && gabor_finite(q00 + q11 + q01)) {
    f.filtered = true;
    precise double pp = GABOR_PI / a2;
    precise double s00 = pp + q00, s01 = q01, s11 = pp + q11;
    precise double det = s00 * s11 - s01 * s01;
    precise double i00 = s11 / det, i01 = -s01 / det, i11 = s00 / det;
    e00 = GABOR_PI * GABOR_PI * i00;
    e01 = GABOR_PI * GABOR_PI * i01;
    e11 = GABOR_PI * GABOR_PI * i11;
    f00 = pp * i00;
    f01 = pp * i01;
    f11 = pp * i11;
#ifdef STOCHTEX_FLOAT
    // D = P - P S^-1 P = P S^-1 Q: the same matrix without the cancellation of P - P S^-1 P,
    // which in float loses D where Q << P (narrow bands seen through small footprints).
    d00 = pp * (i00 * q00 + i01 * q01);
    d01 = pp * (i00 * q01 + i01 * q11);
    d11 = pp * (i01 * q01 + i11 * q11);
#else
    d00 = pp - pp * pp * i00;
    d01 = -pp * pp * i01;
    d11 = pp - pp * pp * i11;
#endif
    gain = pp / sqrt(det);
    precise double half_trace = 0.5lf * (s00 + s11);
    precise double spread = sqrt(0.25lf * (s00 - s11) * (s00 - s11) + s01 * s01);
    reach = sqrt((half_trace + spread) / GABOR_PI);
    precise double d_half_trace = 0.5lf * (d00 + d11);
    precise double d_spread = sqrt(0.25lf * (d00 - d11) * (d00 - d11) + d01 * d01);
    if ((d_half_trace - d_spread) * double(GABOR_GRID_MIN_FREQUENCY_SQUARED[g]) >
        GABOR_NEGLIGIBLE_ATTENUATION)
      f.skip = true;
  }
  // Thinning level: the C++ takes ceil(log2(reach / radius)); GLSL has no double log2, so the
  // same integer comes from doubling (exact): the least L with reach / radius <= 2^L.
  f.level = 0;
  double level_scale = 1.0lf;
  if (f.filtered && reach > GABOR_GRID_RADIUS[g]) {
    precise double ratio = reach / GABOR_GRID_RADIUS[g];
    if (!(ratio <= GABOR_MAX_LEVEL_RATIO)) f.skip = true;
    while (!f.skip && ratio > level_scale) {
      level_scale *= 2.0lf;
      f.level += 1;
    }
  }
  f.ex = float(e00);
  f.exy = float(2.0lf * e01);
  f.ey = float(e11);
  f.fxx = float(f00);
  f.fxy = float(f01);
  f.fyy = float(f11);
  f.dxx = float(d00);
  f.dxy = float(2.0lf * d01);
  f.dyy = float(d11);
  precise double amplitude = double(GABOR_GRID_AMPLITUDE[g]) * gain;
  f.amplitude = float(amplitude * level_scale);
  f.reach = reach;
  f.cell_size = GABOR_GRID_CELL_SIZE[g] * level_scale;
  return f;
}

// A Poisson count by inversion of the tabulated CDF (96 floats) in the data from texel
// `cdf_texel`, in `chunks` draws (CellCount in core/cell_count.hpp).
uint gabor_poisson(int cdf_texel, uint chunks, inout CounterRng rng) {
  uint total = 0u;
  for (uint c = 0u; c < chunks; ++c) {
    float u = rng_uniform(rng);
    int k = 0;
    while (u >= gabor_texel(cdf_texel + k / 4)[k % 4]) ++k;
    total += uint(k);
  }
  return total;
}

// Grid g's count per planar cell.
uint gabor_poisson_count(int g, inout CounterRng rng) {
  return gabor_poisson(GABOR_GRID_CDF[g], GABOR_GRID_POISSON_CHUNKS[g], rng);
}

// draw_alias (alias.hpp): a uniform column from the high word of word * count, then a coin; the
// drawn Gaussian's texel.
vec4 gabor_draw_alias(int g, inout CounterRng rng) {
  uint word = rng_next(rng);
  uint column;
  uint low;
  umulExtended(word, GABOR_GRID_COUNT[g], column, low);
  float coin = rng_uniform(rng);
  vec4 entry = gabor_texel(GABOR_GRID_FIRST[g] + int(column));
  return coin < entry.z ? entry : gabor_texel(GABOR_GRID_FIRST[g] + int(entry.w));
}

// The filtered kernel of Gaussian `gaussian` (its frequency in .xy) and phase at offset
// (dx, dy) = x - x_i, tapered to 0 at the cut, into `value` (KernelShape::at in evaluate.hpp);
// false where the envelope is truncated (beyond e^-pi). The planar sum below and surface noise
// (surface_impulse.glsl) share it.
bool gabor_kernel(GaborGridFilter f, vec4 gaussian, float phase, float dx, float dy,
                  out float value) {
  precise float envelope = f.ex * dx * dx + f.exy * dx * dy + f.ey * dy * dy;
  if (envelope >= GABOR_PI_F) return false;
  precise float t = min((GABOR_PI_F - envelope) * GABOR_TAPER_SCALE, 1.0);
  precise float taper = t * t * (3.0 - 2.0 * t);
  precise float wx = gaussian.x;
  precise float wy = gaussian.y;
  precise float attenuation = 0.0;
  if (f.filtered) {
    attenuation = f.dxx * wx * wx + f.dxy * wx * wy + f.dyy * wy * wy;
    precise float mapped_x = f.fxx * wx + f.fxy * wy;
    wy = f.fxy * wx + f.fyy * wy;
    wx = mapped_x;
  }
  value = exp_float(-envelope - attenuation) * cos_turns(wx * dx + wy * dy + phase) * taper;
  return true;
}

#ifdef STOCHTEX_FLOAT
// The low 32 bits (two's complement) of a small integral float: a cell relative to the origin's.
uint gabor_low_bits(float cell) {
  return uint(int(cell));
}

// The caller's cell, a 64-bit index (low, high words) of level-0 cells `cell_size` wide, on the
// lattice of level `level` (cells 2^level times as wide): the low 32 bits of the level's cell
// holding it, floor(cell / 2^level), in `origin`, and the offset of the level-0 cell's corner from
// that cell's corner, (cell mod 2^level) cell_size, returned. Integer arithmetic, as the CPU's
// floor(p / (cell_size 2^level)) on 64-bit cells.
float gabor_level_origin(uint low, uint high, int level, float cell_size, out uint origin) {
  if (level == 0) {
    origin = low;
    return 0.0;
  }
  if (level < 32) {
    origin = (low >> uint(level)) | (high << uint(32 - level));
    return float(low & ((1u << uint(level)) - 1u)) * cell_size;
  }
  uint shift = uint(level - 32);
  origin = uint(int(high) >> shift);
  return (float(high & ((1u << shift) - 1u)) * 4294967296.0 + float(low)) * cell_size;
}
#else
// The low 32 bits (two's complement) of an integral double, as cell_key takes int64 cells.
uint gabor_low_bits(double cell) {
  return uint(cell - 4294967296.0lf * floor(cell / 4294967296.0lf));
}
#endif

#ifdef STOCHTEX_FLOAT
// The noise of grid g at p (exemplar pixels from the corner of the level's cell whose index has
// the low bits `origin`) for the grid's filter f, before the amplitude: the sum over the cells
// meeting p + [-reach, reach]^2 of their truncated kernels.
float gabor_grid_sum(int g, vec2 p, uvec2 origin, GaborGridFilter f, uint level_seed) {
#else
// The noise of grid g at p (exemplar pixels, double) for the grid's filter f, before the
// amplitude: the sum over the cells meeting p + [-reach, reach]^2 of their truncated kernels.
float gabor_grid_sum(int g, dvec2 p, GaborGridFilter f, uint level_seed) {
#endif
  precise float sum = 0.0;
  float cell_size_f = float(f.cell_size);
  double first_x = floor((p.x - f.reach) / f.cell_size);
  double last_x = floor((p.x + f.reach) / f.cell_size);
  double first_y = floor((p.y - f.reach) / f.cell_size);
  double last_y = floor((p.y + f.reach) / f.cell_size);
  int columns = int(last_x - first_x);
  int rows = int(last_y - first_y);
  for (int j = 0; j <= rows; ++j) {
    double cell_y = first_y + double(j);
    precise double offset_y_exact = p.y - cell_y * f.cell_size;
    float offset_y = float(offset_y_exact);
    for (int i = 0; i <= columns; ++i) {
      double cell_x = first_x + double(i);
      precise double offset_x_exact = p.x - cell_x * f.cell_size;
      float offset_x = float(offset_x_exact);
#ifdef STOCHTEX_FLOAT
      uint key_x = origin.x + gabor_low_bits(cell_x);
      uint key_y = origin.y + gabor_low_bits(cell_y);
#else
      uint key_x = gabor_low_bits(cell_x);
      uint key_y = gabor_low_bits(cell_y);
#endif
      CounterRng point_rng = CounterRng(cell_key(key_x, key_y, level_seed, STREAM_POINTS), 0u);
      CounterRng kernel_rng = CounterRng(cell_key(key_x, key_y, level_seed, STREAM_KERNELS), 0u);
      uint impulses = gabor_poisson_count(g, point_rng);
      for (uint n = 0u; n < impulses; ++n) {
        float u = rng_uniform(point_rng);
        float v = rng_uniform(point_rng);
        vec4 gaussian = gabor_draw_alias(g, kernel_rng);
        float phase = rng_uniform(kernel_rng);
        precise float dx = offset_x - u * cell_size_f;
        precise float dy = offset_y - v * cell_size_f;
        float value;
        if (gabor_kernel(f, gaussian, phase, dx, dy, value)) sum += value;
      }
    }
  }
  return sum;
}


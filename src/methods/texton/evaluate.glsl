// Texton noise on the GPU: the GLSL twin of TextonModel::evaluate_typed (evaluate.hpp,
// model.cpp), same hash, same draws, same constants. One invocation per output pixel of a
// regular grid; the footprint is the grid's (one filter setup per render, see filter_setup).
// Requires random.glsl before it.

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = 0) readonly buffer Texels { float texels[]; };
layout(std430, binding = 1) writeonly buffer Result { float result[]; };

uniform ivec2 image_size;   // pixels of the whole render
uniform ivec2 first_pixel;  // grid.first_pixel of this render + the dispatch's offset
uniform ivec2 dispatch_size;
uniform uvec2 origin_cell;  // low 32 bits of the cell holding the grid origin
uniform vec2 origin_offset; // grid origin minus that cell's corner, exemplar pixels
uniform float scale;
uniform uint seed;
uniform int channels;
uniform int order;

uniform float cell_size;
uniform float poisson_cdf[96];
uniform uint poisson_chunks;
uniform float inverse_sqrt_intensity;
uniform vec4 constant_term;
uniform vec4 mean_colour;

// Filtering, decided once per render from the pixel footprint (filter_setup in C++).
uniform float reach;
uniform int probes;
uniform vec2 probe_step;
uniform float level_blend;
uniform float fade;
// The two pyramid levels read: [0] fine, [1] coarse. offset in floats into `texels`.
uniform int level_offset[2];
uniform int level_stride[2];
uniform float level_spacing[2];
uniform float level_first_texel[2];
uniform float level_half_width[2];

const int PADDING = 8;

uint poisson_count(inout CounterRng rng) {
  uint total = 0u;
  for (uint c = 0u; c < poisson_chunks; ++c) {
    float u = rng_uniform(rng);
    uint k = 0u;
    while (u >= poisson_cdf[k]) ++k;
    total += k;
  }
  return total;
}

// B-spline interpolation weights of order `order` at texel coordinate u (BsplineKernel in C++).
int bspline_weights(float u, out float w[6]) {
  for (int i = 0; i < 6; ++i) w[i] = 0.0;
  if (order == 0) {
    w[0] = 1.0;
    return int(floor(u + 0.5));
  }
  float cell = floor(u);
  float t = u - cell;
  int first = int(cell) - (order - 1) / 2;
  if (order == 1) {
    w[0] = 1.0 - t;
    w[1] = t;
  } else if (order == 3) {
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

void accumulate_texton(int level, float dx, float dy, float weight, inout vec4 acc) {
  float half_width = level_half_width[level];
  if (abs(dx) >= half_width || abs(dy) >= half_width) return;
  float wx[6];
  float wy[6];
  float inverse_spacing = 1.0 / level_spacing[level];
  int x0 = bspline_weights((dx - level_first_texel[level]) * inverse_spacing, wx);
  int y0 = bspline_weights((dy - level_first_texel[level]) * inverse_spacing, wy);
  int stride = level_stride[level];
  int base = level_offset[level] + ((y0 + PADDING) * stride + (x0 + PADDING)) * channels;
  int taps = order + 1;
  for (int j = 0; j < taps; ++j) {
    int row = base + j * stride * channels;
    for (int i = 0; i < taps; ++i) {
      float w = weight * wy[j] * wx[i];
      for (int c = 0; c < channels; ++c) acc[c] += w * texels[row + i * channels + c];
    }
  }
}

void main() {
  ivec2 local_pixel = ivec2(gl_GlobalInvocationID.xy);
  if (local_pixel.x >= dispatch_size.x || local_pixel.y >= dispatch_size.y) return;
  ivec2 pixel = first_pixel + local_pixel;
  // Position relative to the origin cell's corner: small numbers, so far origins stay precise.
  vec2 p = origin_offset + scale * (vec2(pixel) + 0.5);
  vec4 acc = vec4(0.0);
  int first_x = int(floor((p.x - reach) / cell_size));
  int last_x = int(floor((p.x + reach) / cell_size));
  int first_y = int(floor((p.y - reach) / cell_size));
  int last_y = int(floor((p.y + reach) / cell_size));
  float probe_weight = 1.0 / float(probes);
  for (int cell_y = first_y; cell_y <= last_y; ++cell_y) {
    float offset_y = p.y - float(cell_y) * cell_size;
    for (int cell_x = first_x; cell_x <= last_x; ++cell_x) {
      float offset_x = p.x - float(cell_x) * cell_size;
      CounterRng rng = CounterRng(
          cell_key(origin_cell.x + uint(cell_x), origin_cell.y + uint(cell_y), seed,
                   STREAM_POINTS),
          0u);
      uint impacts = poisson_count(rng);
      for (uint n = 0u; n < impacts; ++n) {
        float u = rng_uniform(rng);
        float v = rng_uniform(rng);
        float dx = offset_x - u * cell_size;
        float dy = offset_y - v * cell_size;
        if (probes == 1 && level_blend == 0.0) {
          accumulate_texton(0, dx, dy, 1.0, acc);
          continue;
        }
        for (int k = 0; k < probes; ++k) {
          float shift = float(k) + 0.5 - 0.5 * float(probes);
          float px = dx + shift * probe_step.x;
          float py = dy + shift * probe_step.y;
          accumulate_texton(0, px, py, probe_weight * (1.0 - level_blend), acc);
          if (level_blend > 0.0) accumulate_texton(1, px, py, probe_weight * level_blend, acc);
        }
      }
    }
  }
  int index = (local_pixel.y * dispatch_size.x + local_pixel.x) * channels;
  for (int c = 0; c < channels; ++c) {
    float noise = acc[c] * inverse_sqrt_intensity + constant_term[c] - mean_colour[c];
    result[index + c] = mean_colour[c] + fade * noise;
  }
}

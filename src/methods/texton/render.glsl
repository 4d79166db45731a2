// The compute shader of `render --backend gl` for texton noise: one invocation per output pixel of
// a regular grid. Requires random.glsl, the model's constants and texton evaluate.glsl. Texton noise
// mixing runs it too, with texton_noise defined as texton_mix_noise (texton_mix/gl_pass.cpp).

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 1) writeonly buffer Result { float result[]; };

uniform ivec2 first_pixel;    // grid.first_pixel + the dispatch's offset
uniform ivec2 dispatch_size;
uniform uvec2 origin_cell;    // low 32 bits of the cell holding the grid origin
uniform vec2 origin_offset;   // grid origin minus that cell's corner, exemplar pixels
uniform float scale;
uniform uint seed;
// The grid's footprint gives one filter for the whole render, chosen on the CPU by filter_setup
// (in double, exactly as the CPU evaluator chooses it).
uniform int filter_level;
uniform float filter_level_blend;
uniform int filter_probes;
uniform vec2 filter_probe_step;
uniform float filter_fade;
// --gl-filter hardware: the footprint's side (zero for point samples).
uniform float filter_scale;

// A model of more than 4 channels renders in chunks of 4 (gl_pass.cpp): each writes its
// TEXTON_CHANNELS channels from channel TEXTON_RESULT_FIRST of pixels of TEXTON_RESULT_STRIDE.
#ifndef TEXTON_RESULT_STRIDE
#define TEXTON_RESULT_STRIDE TEXTON_CHANNELS
#define TEXTON_RESULT_FIRST 0
#endif

void main() {
  ivec2 local_pixel = ivec2(gl_GlobalInvocationID.xy);
  if (local_pixel.x >= dispatch_size.x || local_pixel.y >= dispatch_size.y) return;
  vec2 p = origin_offset + scale * (vec2(first_pixel + local_pixel) + 0.5);
  TextonFilter f = TextonFilter(filter_level, filter_level_blend, filter_probes,
                                filter_probe_step, filter_fade);
#ifdef TEXTON_TEXTURE_FILTER
  texton_set_gradients(vec2(filter_scale, 0.0), vec2(0.0, filter_scale));
#endif
  vec4 value = texton_noise(p, origin_cell, seed, f);
  int index =
      (local_pixel.y * dispatch_size.x + local_pixel.x) * TEXTON_RESULT_STRIDE + TEXTON_RESULT_FIRST;
  for (int c = 0; c < TEXTON_CHANNELS; ++c) result[index + c] = value[c];
}

// The compute shader of `render --backend gl` for local random-phase noise: one invocation per
// output pixel. Requires random.glsl, the model's constants and lrp evaluate.glsl. With
// LRP_MATERIAL, the model is a chunk of up to 4 channels of a material (gl_pass.cpp), and the
// constants LRP_MATERIAL_CHANNELS, LRP_CHUNK_FIRST, LRP_MATERIAL_MEAN and LRP_CHUNK_BASIS.

layout(local_size_x = 8, local_size_y = 8) in;
#ifdef LRP_MATERIAL
layout(std430, binding = 1) buffer Result { float result[]; };
#else
layout(std430, binding = 1) writeonly buffer Result { float result[]; };
#endif

uniform ivec2 first_pixel;  // grid.first_pixel + the dispatch's offset
uniform ivec2 dispatch_size;
uniform float scale;
uniform bool filtered;
// Per stratum: the lattice node nearest the grid origin (low 32 bits), the origin's position
// relative to it in lattice units, and the stratum's random stream.
uniform uvec2 origin_node[LRP_STRATA_TOTAL];
uniform vec2 origin_offset[LRP_STRATA_TOTAL];
uniform uint stratum_seed[LRP_STRATA_TOTAL];
// Section 5 (add_structure in structure_model.cpp), all formed on the CPU in double: the grid
// origin modulo the structure period; the placement block holding the origin (low 32 bits) and
// the origin's position from it in half periods; per turbulence stratum the node nearest the
// origin and the offset, and per axis and stratum the stream.
uniform vec2 structure_origin;
uniform uvec2 placement_block;
uniform vec2 placement_offset;
uniform uint seed;
uniform uvec2 turbulence_node[LRP_TURBULENCE_ARRAY];
uniform vec2 turbulence_offset[LRP_TURBULENCE_ARRAY];
uniform uint turbulence_seed[2 * LRP_TURBULENCE_ARRAY];

void main() {
  ivec2 local_pixel = ivec2(gl_GlobalInvocationID.xy);
  if (local_pixel.x >= dispatch_size.x || local_pixel.y >= dispatch_size.y) return;
  vec2 p = scale * (vec2(first_pixel + local_pixel) + 0.5);
  vec2 axis_a = filtered ? vec2(scale, 0.0) : vec2(0.0);
  vec2 axis_b = filtered ? vec2(0.0, scale) : vec2(0.0);
  vec4 noise = vec4(0.0);
  for (int s = 0; s < LRP_STRATA_TOTAL; ++s) {
    if (LRP_STRATUM_AMPLITUDE[s] == 0.0) continue;
    vec2 u = origin_offset[s] + p / LRP_STRATUM_SPACING[s];
    noise[LRP_STRATUM_CHANNEL[s]] += lrp_stratum_noise(s, u, origin_node[s], stratum_seed[s],
                                                       filtered, axis_a, axis_b);
  }
  if (LRP_HAS_STRUCTURE)
    lrp_add_structure(p, structure_origin, placement_block, placement_offset, turbulence_node,
                      turbulence_offset, turbulence_seed, seed, filtered, axis_a, axis_b, noise);
#ifdef LRP_MATERIAL
  // mean + basis * noise over the N channels, summed in the CPU's order: the first chunk starts
  // from the mean, each later chunk adds its columns to what the chunks before it wrote.
  int index = (local_pixel.y * dispatch_size.x + local_pixel.x) * LRP_MATERIAL_CHANNELS;
  for (int c = 0; c < LRP_MATERIAL_CHANNELS; ++c) {
    float value = LRP_CHUNK_FIRST == 0 ? LRP_MATERIAL_MEAN[c] : result[index + c];
    for (int k = 0; k < LRP_CHANNELS; ++k)
      value += LRP_CHUNK_BASIS[c * LRP_CHANNELS + k] * noise[k];
    result[index + c] = value;
  }
#else
  vec4 value = lrp_colour(noise);
  int index = (local_pixel.y * dispatch_size.x + local_pixel.x) * LRP_CHANNELS;
  for (int c = 0; c < LRP_CHANNELS; ++c) result[index + c] = value[c];
#endif
}

// The compute shader of `render --backend gl` for Gabor noise: one invocation per output pixel.
// Requires random.glsl, the model's constants and gabor evaluate.glsl.

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 1) writeonly buffer Result { float result[]; };

uniform ivec2 first_pixel;  // grid.first_pixel + the dispatch's offset
uniform ivec2 dispatch_size;
uniform dvec2 origin;       // the grid's, in double as the CPU forms its positions
uniform double scale;
uniform uint seed;
uniform bool filtered;

void main() {
  ivec2 local_pixel = ivec2(gl_GlobalInvocationID.xy);
  if (local_pixel.x >= dispatch_size.x || local_pixel.y >= dispatch_size.y) return;
  // p = origin + scale (i + 1/2), the CPU renderer's position to the last bit.
  precise dvec2 p = origin + scale * (dvec2(first_pixel + local_pixel) + 0.5lf);
  dvec2 dpdx = filtered ? dvec2(scale, 0.0lf) : dvec2(0.0lf);
  dvec2 dpdy = filtered ? dvec2(0.0lf, scale) : dvec2(0.0lf);
  vec4 value = gabor_noise(p, dpdx, dpdy, seed);
  int index = (local_pixel.y * dispatch_size.x + local_pixel.x) * GABOR_CHANNELS;
  for (int c = 0; c < GABOR_CHANNELS; ++c) result[index + c] = value[c];
}

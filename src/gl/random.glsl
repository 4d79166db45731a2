// The randomness spec of docs/design.md §5 in GLSL, statement for statement the same as
// src/core/hash.hpp (uint arithmetic wraps in both languages). Tests compare the two. The stream
// constants STREAM_POINTS, STREAM_PHASES, ... of the C++ enum Stream are declared before this
// file from the enum (random_source() in random.cpp).

uint pcg_hash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

uvec4 pcg4d(uvec4 v) {
  v = v * 1664525u + 1013904223u;
  v.x += v.y * v.w;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v.w += v.y * v.z;
  v ^= v >> 16u;
  v.x += v.y * v.w;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v.w += v.y * v.z;
  return v;
}

// Cell coordinates enter as their low 32 bits, as in the C++ cell_key.
uint cell_key(uint cell_x, uint cell_y, uint seed, uint stream) {
  return pcg4d(uvec4(cell_x, cell_y, seed, stream)).x;
}

// CounterRng: draw n of a cell is pcg_hash(key ^ pcg_hash(n)). One draw per statement.
struct CounterRng {
  uint key;
  uint counter;
};

uint rng_next(inout CounterRng rng) {
  uint value = pcg_hash(rng.key ^ pcg_hash(rng.counter));
  rng.counter += 1u;
  return value;
}

float rng_uniform(inout CounterRng rng) {
  return float(rng_next(rng) >> 8u) * (1.0 / 16777216.0);
}

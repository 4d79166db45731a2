// The 3-D Poisson impulse process of surface noise in GLSL: the twin of for_each_surface_impulse
// (src/core/surface_process.hpp, docs/surface.md), same cells, same 3-D cell key, same draws in
// the same order, so the GPU sees the CPU's impulses. Requires random.glsl, then SURFACE_CONTEXT
// #defined as the method's type of per-point state (texton: TextonFilter; gabor:
// GaborSurfacePoint), and, before or after this file, the method's two callbacks:
//   uint surface_impulse_count(inout CounterRng rng, SURFACE_CONTEXT context);
//     a cell's impulse count (the method's CellCount twin);
//   void surface_impulse(inout CounterRng rng, float t, float z1, float z2,
//                        SURFACE_CONTEXT context, inout vec4 acc);
//     one impulse at local coordinates (t, z1, z2) = (<y - x_i, u3>, <y - x_i, u1>,
//     <y - x_i, u2>), called for every impulse of the visited cells, outside the box included:
//     it draws its marks from `rng` first, then rejects what lies outside.

// The key of 3-D lattice cell (x, y, z) (cell_key in core/hash.hpp): the 2-D key hashed again
// with z, seed and stream.
uint cell_key(uint cell_x, uint cell_y, uint cell_z, uint seed, uint stream) {
  return pcg4d(uvec4(cell_key(cell_x, cell_y, seed, stream), cell_z, seed, stream)).x;
}

uint surface_impulse_count(inout CounterRng rng, SURFACE_CONTEXT context);
void surface_impulse(inout CounterRng rng, float t, float z1, float z2, SURFACE_CONTEXT context,
                     inout vec4 acc);

// Sums surface_impulse over the impulses of the cells (side cell_size) that meet the bounding box
// of the oriented box |<y - x_i, u1>|, |<y - x_i, u2>| < reach, |<y - x_i, u3>| < depth around
// y = position. The cells are taken relative to the one holding the position, whose index enters
// the key as its low 32 bits (as the CPU's 64-bit index does); offsets are floats, so precision
// falls with |position| (float positions on the GPU, double on the CPU).
vec4 surface_sum_impulses(vec3 position, vec3 u1, vec3 u2, vec3 u3, float reach, float depth,
                          float cell_size, uint seed, SURFACE_CONTEXT context) {
  vec3 origin = floor(position / cell_size);
  vec3 p = position - origin * cell_size;
  uvec3 origin_cell = uvec3(ivec3(origin));
  vec3 extent = reach * (abs(u1) + abs(u2)) + depth * abs(u3);
  ivec3 first = ivec3(floor((p - extent) / cell_size));
  ivec3 last = ivec3(floor((p + extent) / cell_size));
  vec4 acc = vec4(0.0);
  for (int cz = first.z; cz <= last.z; ++cz) {
    float oz = p.z - float(cz) * cell_size;
    for (int cy = first.y; cy <= last.y; ++cy) {
      float oy = p.y - float(cy) * cell_size;
      for (int cx = first.x; cx <= last.x; ++cx) {
        float ox = p.x - float(cx) * cell_size;
        uvec3 cell = origin_cell + uvec3(ivec3(cx, cy, cz));
        CounterRng rng = CounterRng(cell_key(cell.x, cell.y, cell.z, seed, STREAM_POINTS), 0u);
        uint impulses = surface_impulse_count(rng, context);
        for (uint i = 0u; i < impulses; ++i) {
          float u = rng_uniform(rng);
          float v = rng_uniform(rng);
          float w = rng_uniform(rng);
          vec3 d = vec3(ox - u * cell_size, oy - v * cell_size, oz - w * cell_size);
          surface_impulse(rng, dot(d, u3), dot(d, u1), dot(d, u2), context, acc);
        }
      }
    }
  }
  return acc;
}

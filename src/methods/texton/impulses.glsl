// The shot-noise sum at p (sum_impulses in evaluate.hpp), filtered as section 5 of the texton paper
// says: the impulses of the grid cells that meet p's reach, each adding weight * h(p - x_j) at the
// filter's pyramid level(s) and probes. p is in exemplar pixels relative to the corner of cell
// `origin_cell` (whose index enters the hash as its low 32 bits, so callers may keep p small and
// the cell far). The one loop of texton noise (noise.glsl) and texton noise mixing
// (texton_mix/evaluate.glsl): each defines texton_impulse, which maps a point (the origin cell,
// the point's cell relative to it, its index in the cell, (u, v) in the cell) to its TextonImpulse.
TextonImpulse texton_impulse(uvec2 origin_cell, ivec2 cell, uint index, vec2 uv, uint seed);

// The random sign of the index-th point of a cell from the cell's sign key (point_sign in
// evaluate.hpp), and from the cell given as for texton_impulse (impulse_sign).
float texton_point_sign(uint sign_key, uint index) {
  return (pcg_hash(sign_key ^ pcg_hash(index)) >> 31u) != 0u ? -1.0 : 1.0;
}

// Point i of the shifted lattice of the balanced points (lattice_point in evaluate.hpp).
float texton_lattice_point(float shift, uint i, float step) {
  float x = shift + float(i) * step;
  return x - floor(x);
}

float texton_sign(uvec2 origin_cell, ivec2 cell, uint index, uint seed) {
  return texton_point_sign(
      cell_key(origin_cell.x + uint(cell.x), origin_cell.y + uint(cell.y), seed, STREAM_SIGNS),
      index);
}

// Half side of the square outside which an impact adds nothing (FilteredTexton::reach in
// evaluate.hpp): the kernel's support plus the spread of the probes.
float texton_reach(TextonFilter f) {
  int coarse = min(f.level + 1, TEXTON_LEVELS - 1);
  float probe_extent = 0.5 * float(f.probes - 1) * max(abs(f.probe_step.x), abs(f.probe_step.y));
  float kernel_reach = f.level_blend > 0.0 ? max(TEXTON_LEVEL_HALF_WIDTH[f.level],
                                                 TEXTON_LEVEL_HALF_WIDTH[coarse])
                                           : TEXTON_LEVEL_HALF_WIDTH[f.level];
  return kernel_reach + probe_extent;
}

// Adds weight * (filtered texton)(dx, dy) to acc (FilteredTexton::add in evaluate.hpp), (dx, dy)
// = x - x_i in exemplar pixels, for the texton whose pyramid starts at atlas texel `atlas`: the
// filter's pyramid level(s) and probes. The planar shot noise below and surface noise
// (surface.glsl) sum the same filtered textons.
void texton_add(ivec2 atlas, TextonFilter f, float dx, float dy, float weight, inout vec4 acc) {
#ifdef TEXTON_TEXTURE_FILTER
  // `render --gl-filter hardware` (hardware.glsl, texton noise only): one mip-mapped,
  // anisotropic texture fetch of the texton instead of the exact levels and probes.
  acc += weight * texton_texture_fetch(dx, dy);
#else
  if (f.probes == 1 && f.level_blend == 0.0) {
    texton_accumulate(atlas, f.level, dx, dy, weight, acc);
    return;
  }
  int coarse = min(f.level + 1, TEXTON_LEVELS - 1);
  float probe_weight = 1.0 / float(f.probes);
  for (int k = 0; k < f.probes; ++k) {
    float shift = float(k) + 0.5 - 0.5 * float(f.probes);
    float px = dx + shift * f.probe_step.x;
    float py = dy + shift * f.probe_step.y;
    texton_accumulate(atlas, f.level, px, py, weight * probe_weight * (1.0 - f.level_blend), acc);
    if (f.level_blend > 0.0)
      texton_accumulate(atlas, coarse, px, py, weight * probe_weight * f.level_blend, acc);
  }
#endif
}

vec4 texton_sum_impulses(vec2 p, uvec2 origin_cell, uint seed, TextonFilter f) {
  float reach = texton_reach(f);
  vec4 acc = vec4(0.0);
  int first_x = int(floor((p.x - reach) / TEXTON_CELL_SIZE));
  int last_x = int(floor((p.x + reach) / TEXTON_CELL_SIZE));
  int first_y = int(floor((p.y - reach) / TEXTON_CELL_SIZE));
  int last_y = int(floor((p.y + reach) / TEXTON_CELL_SIZE));
  for (int cell_y = first_y; cell_y <= last_y; ++cell_y) {
    float offset_y = p.y - float(cell_y) * TEXTON_CELL_SIZE;
    for (int cell_x = first_x; cell_x <= last_x; ++cell_x) {
      float offset_x = p.x - float(cell_x) * TEXTON_CELL_SIZE;
      uvec2 key_cell = origin_cell + uvec2(ivec2(cell_x, cell_y));
      CounterRng rng = CounterRng(cell_key(key_cell.x, key_cell.y, seed, STREAM_POINTS), 0u);
      // The balanced points (TEXTON_BALANCED; CellCache in evaluate.hpp): a shifted lattice, each
      // point with a random sign; else uniform points, sign 1.
      uint sign_key = TEXTON_BALANCED ? cell_key(key_cell.x, key_cell.y, seed, STREAM_SIGNS) : 0u;
      uint impacts = texton_cell_count(rng);
      float shift_u = 0.0;
      float shift_v = 0.0;
      if (TEXTON_BALANCED) {
        shift_u = rng_uniform(rng);
        shift_v = rng_uniform(rng);
      }
      for (uint n = 0u; n < impacts; ++n) {
        float u;
        float v;
        if (TEXTON_BALANCED) {
          u = texton_lattice_point(shift_u, n, TEXTON_LATTICE_STEP_U);
          v = texton_lattice_point(shift_v, n, TEXTON_LATTICE_STEP_V);
        } else {
          u = rng_uniform(rng);
          v = rng_uniform(rng);
        }
        TextonImpulse impulse =
            texton_impulse(origin_cell, ivec2(cell_x, cell_y), n, vec2(u, v), seed);
        float sign = TEXTON_BALANCED ? texton_point_sign(sign_key, n) : 1.0;
        texton_add(impulse.atlas, f, offset_x - u * TEXTON_CELL_SIZE,
                   offset_y - v * TEXTON_CELL_SIZE, impulse.weight * sign, acc);
      }
    }
  }
  return acc;
}

// Step 1 of Algorithm 1 in GLSL (the lattice's patches), shared by the blend of an image
// (blend.glsl), the material render's patch output (render.glsl) and an exported material
// (material.glsl). Requires random.glsl, the constants and tiling evaluate.glsl.

// p (exemplar pixels, |p| below ~1e4) in skewed lattice units from the cell at the origin, and
// modulo the exemplar's period (triangle_lattice and wrap_position in single precision).
void tiling_lattice_at(vec2 p, out vec2 skewed, out vec2 wrapped) {
  skewed = vec2(p.x - p.y * TILING_INVERSE_SQRT3, 2.0 * TILING_INVERSE_SQRT3 * p.y) / TILING_EDGE;
  vec2 period = vec2(TILING_WIDTH, TILING_HEIGHT);
  wrapped = p - period * floor(p / period);
}

// Step 1 of Algorithm 1: the three patches around a point, each with its blend weight (sharpened,
// sharpen_weights), where it is read (exemplar pixels), its transform M (patch_transform, the
// rotation and scale jitter) and its level of detail. `skewed` is the position in skewed lattice
// units relative to the lattice cell `origin_cell` (low 32 bits), `wrapped` the position modulo
// the exemplar's period; both formed on the CPU in double for the far part. `width` is the
// footprint's (0: a point sample), `level`, `level_blend` its level of detail; with scale jitter
// each patch reads its own level. The artist controls (TILING_ROTATION, TILING_SCALE_JITTER,
// TILING_SHARPNESS) are the model's constants: with their defaults the compiler removes their
// code.
struct TilingPatches {
  float weight[3];
  vec2 position[3];
  mat2 matrix[3];
  float scale[3];
  int level[3];
  float level_blend[3];
};

TilingPatches tiling_patches(vec2 skewed, uvec2 origin_cell, vec2 wrapped, uint seed, float width,
                             int level, float level_blend) {
  TilingPatches patches;
  vec2 cell = floor(skewed);
  vec2 f = skewed - cell;
  bool lower = f.x + f.y < 1.0;
  ivec2 d[3] = ivec2[3](lower ? ivec2(0, 0) : ivec2(1, 1), lower ? ivec2(1, 0) : ivec2(0, 1),
                        lower ? ivec2(0, 1) : ivec2(1, 0));
  patches.weight = lower ? float[3](1.0 - f.x - f.y, f.x, f.y)
                         : float[3](f.x + f.y - 1.0, 1.0 - f.x, 1.0 - f.y);
  if (TILING_SHARPNESS != 1.0) {
    // sharpen_weights (evaluate.hpp): Burley 2019's exponent, renormalised.
    float sum = 0.0;
    for (int v = 0; v < 3; ++v) {
      patches.weight[v] = pow(patches.weight[v], TILING_SHARPNESS);
      sum += patches.weight[v];
    }
    for (int v = 0; v < 3; ++v) patches.weight[v] /= sum;
  }
  for (int v = 0; v < 3; ++v) {
    uvec2 vertex = origin_cell + uvec2(ivec2(cell) + d[v]);
    CounterRng rng = CounterRng(cell_key(vertex.x, vertex.y, seed, STREAM_OFFSETS), 0u);
    uint draw_u = rng_next(rng);
    uint draw_v = rng_next(rng);
    uint high;
    uint low;
    umulExtended(draw_u, uint(TILING_WIDTH), high, low);
    float offset_x = float(high);
    umulExtended(draw_v, uint(TILING_HEIGHT), high, low);
    float offset_y = float(high);
    float x = wrapped.x + offset_x;
    float y = wrapped.y + offset_y;
    patches.matrix[v] = mat2(1.0);
    patches.scale[v] = 1.0;
    patches.level[v] = level;
    patches.level_blend[v] = level_blend;
    if (TILING_TRANSFORMED) {
      // patch_transform and patch_shift (evaluate.hpp): rotation and scale about the vertex.
      CounterRng draws =
          CounterRng(cell_key(vertex.x, vertex.y, seed, TILING_STREAM_TRANSFORMS), 0u);
      float angle_draw = rng_uniform(draws);
      float scale_draw = rng_uniform(draws);
      float angle = TILING_ROTATION * (2.0 * angle_draw - 1.0);
      float patch_scale = exp2(TILING_SCALE_JITTER * (2.0 * scale_draw - 1.0));
      float c = patch_scale * cos(angle);
      float s = patch_scale * sin(angle);
      patches.matrix[v] = mat2(c, s, -s, c);
      patches.scale[v] = patch_scale;
      vec2 from_vertex = f - vec2(d[v]);
      float local_x = TILING_EDGE * (from_vertex.x + 0.5 * from_vertex.y);
      float local_y = TILING_EDGE * from_vertex.y * (1.5 * TILING_INVERSE_SQRT3);
      x += (c - 1.0) * local_x - s * local_y;
      y += s * local_x + (c - 1.0) * local_y;
      if (TILING_SCALE_JITTER > 0.0) {
        float lod = tiling_lod_of_width(width * patch_scale);
        patches.level[v] = int(lod);
        patches.level_blend[v] = lod - float(patches.level[v]);
      }
    }
    patches.position[v] = vec2(x, y);
  }
  return patches;
}

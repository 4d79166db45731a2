// The normal maps of an exported material (`export-shader`, src/gl/export_material.cpp): compiled
// after stochtex_material_channels, the model's STOCHTEX_MATERIAL_CHANNELS channels at a point.

// The unit tangent-space normal of the slopes s = (-n_x / n_z, -n_y / n_z) that a model keeps of a
// normal map: normalize(-s_x, -s_y, 1), x right and y up, as split_maps (src/model/map_layout.cpp)
// decodes them (the derivative form of M. Mikkelsen, "Surface Gradient-Based Bump Mapping
// Framework", JCGT 9(3), 2020).
vec3 stochtex_normal(vec2 slopes) {
  return normalize(vec3(-slopes, 1.0));
}

// The slopes of a normal map derived from the height, channel `height`: slope_scale times the
// height's gradient, y up (render_maps in src/model/map_layout.cpp). The gradient g solves
// g . step = (h(p + step) - h(p - step)) / 2 for the footprint's two axes dpdx and dpdy, the
// heights filtered by the same footprint: on a grid of spacing s, whose axes are (s, 0) and
// (0, s), these are the CPU's central differences one grid step apart. Axes that are zero or
// nearly parallel (less than 1e-3 radians apart) give way to steps of one exemplar pixel along x
// and y. Costs 4 more evaluations of the noise.
vec2 stochtex_derived_slopes(vec2 p, vec2 dpdx, vec2 dpdy, uint seed, int height,
                             float slope_scale) {
  vec2 step_x = dpdx;
  vec2 step_y = dpdy;
  float determinant = step_x.x * step_y.y - step_x.y * step_y.x;
  if (!(abs(determinant) > 1e-3 * length(step_x) * length(step_y))) {
    step_x = vec2(1.0, 0.0);
    step_y = vec2(0.0, 1.0);
    determinant = 1.0;
  }
  float ahead_x[STOCHTEX_MATERIAL_CHANNELS] =
      stochtex_material_channels(p + step_x, dpdx, dpdy, seed);
  float behind_x[STOCHTEX_MATERIAL_CHANNELS] =
      stochtex_material_channels(p - step_x, dpdx, dpdy, seed);
  float ahead_y[STOCHTEX_MATERIAL_CHANNELS] =
      stochtex_material_channels(p + step_y, dpdx, dpdy, seed);
  float behind_y[STOCHTEX_MATERIAL_CHANNELS] =
      stochtex_material_channels(p - step_y, dpdx, dpdy, seed);
  float along_x = 0.5 * (ahead_x[height] - behind_x[height]);
  float along_y = 0.5 * (ahead_y[height] - behind_y[height]);
  vec2 gradient = vec2(step_y.y * along_x - step_x.y * along_y,
                       step_x.x * along_y - step_y.x * along_x) / determinant;
  return slope_scale * vec2(gradient.x, -gradient.y);
}

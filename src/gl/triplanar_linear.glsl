// Linear triplanar mapping for any method (evaluate_triplanar_linear in src/render/surface.cpp):
// the method's planar entry point, #defined as STOCHTEX_PLANAR (stochtex_<method>(vec2 p,
// vec2 dpdx, vec2 dpdy, uint seed)), on the three axis planes with seeds seed + k, the position
// and its screen derivatives projected on each, blended with the normal's weights. Requires
// triplanar.glsl and the method's library.
vec4 stochtex_triplanar_linear(vec3 position, vec3 normal, vec3 dpdx, vec3 dpdy,
                               float sharpness, uint seed) {
  vec3 weights = stochtex_triplanar_weights(normal, sharpness);
  vec4 sum = vec4(0.0);
  for (int k = 0; k < 3; ++k)
    sum += weights[k] * STOCHTEX_PLANAR(stochtex_on_plane(position, k),
                                        stochtex_on_plane(dpdx, k), stochtex_on_plane(dpdy, k),
                                        seed + uint(k));
  return sum;
}

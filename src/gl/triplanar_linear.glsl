// Linear triplanar mapping for any method (evaluate_triplanar_linear in src/render/surface.cpp):
// the method's planar entry point, #defined as STOCHTEX_PLANAR (stochtex_<method>(vec2 p,
// vec2 dpdx, vec2 dpdy, uint seed)), on the three axis planes with seeds seed + k, the position
// and its screen derivatives projected on each, blended with the normal's weights; each plane's
// value as linear light first where STOCHTEX_TRIPLANAR_DECODE is defined (a model of sRGB colour,
// gl/colour.glsl). Requires triplanar.glsl and the method's library.
vec4 stochtex_triplanar_linear(vec3 position, vec3 normal, vec3 dpdx, vec3 dpdy,
                               float sharpness, uint seed) {
  vec3 weights = stochtex_triplanar_weights(normal, sharpness);
  vec4 sum = vec4(0.0);
  for (int k = 0; k < 3; ++k) {
    vec2 plane_dpdx = stochtex_on_plane(dpdx, k);
    vec2 plane_dpdy = stochtex_on_plane(dpdy, k);
    vec4 value =
        STOCHTEX_PLANAR(stochtex_on_plane(position, k), plane_dpdx, plane_dpdy, seed + uint(k));
#ifdef STOCHTEX_TRIPLANAR_DECODE
    value = stochtex_linear_light(value, plane_dpdx, plane_dpdy);
#endif
    sum += weights[k] * value;
  }
  return sum;
}

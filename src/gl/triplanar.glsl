// The geometry of triplanar mapping in GLSL, the twin of core/triplanar.hpp: the three axis
// planes and the weights the normal gives them, shared by tiling's histogram-preserving operator
// (tiling triplanar.glsl) and linear triplanar mapping (triplanar_linear.glsl), which may meet
// in one library (tiling's): hence the guard.
#ifndef STOCHTEX_TRIPLANAR_GEOMETRY
#define STOCHTEX_TRIPLANAR_GEOMETRY

// The weights of the projections on the axis planes (y,z), (z,x), (x,y): |n_k|^sharpness,
// normalised to sum 1.
vec3 stochtex_triplanar_weights(vec3 normal, float sharpness) {
  vec3 weights = pow(abs(normal), vec3(sharpness));
  return weights / (weights.x + weights.y + weights.z);
}

// A position or footprint vector projected on axis plane k: (y,z), (z,x), (x,y).
vec2 stochtex_on_plane(vec3 v, int k) {
  return k == 0 ? v.yz : (k == 1 ? v.zx : v.xy);
}
#endif

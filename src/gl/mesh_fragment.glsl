// The fragment shader of the GL mesh renderer (mesh_gl.cpp), the way an engine calls an exported
// shader: the surface point from the interpolated position, normal and uv, its screen derivatives
// from dFdx and dFdy, the method's GLSL function, and the CPU's shading (src/render/
// mesh_shading.hpp, docs/meshes.md). Requires, before it, MESH_AMBIENT and MESH_MAX_FOOTPRINT
// (from the C++ constants), the method's library, and either STOCHTEX_MESH_UV (the 2-D entry
// stochtex_<method>, called at the mesh's uv) or STOCHTEX_SURFACE_CALL (a gl::SurfaceShader's
// call expression, from position, normal, tangent, dpdx, dpdy, seed and parameter).

in vec3 mesh_position;
in vec3 mesh_normal;
in vec2 mesh_uv;

uniform vec3 mesh_eye;
uniform vec3 mesh_light;  // unit, towards the light
uniform float mesh_texture_scale;
uniform int mesh_colours;  // channels shaded; the others (alpha) pass through
uniform uint seed;
uniform float parameter;

out vec4 colour;

// surface_tangent (mesh_shading.hpp): normalise(Y x n), or the projection of X on the tangent
// plane within 1e-6 of n = +-Y.
vec3 mesh_surface_tangent(vec3 n) {
  vec3 east = vec3(n.z, 0.0, -n.x);
  if (length(east) > 1e-6) return normalize(east);
  return normalize(vec3(1.0, 0.0, 0.0) - n * n.x);
}

vec3 mesh_clamp_length(vec3 v) {
  float l = length(v);
  return l > MESH_MAX_FOOTPRINT ? v * (MESH_MAX_FOOTPRINT / l) : v;
}

vec2 mesh_clamp_length(vec2 v) {
  float l = length(v);
  return l > MESH_MAX_FOOTPRINT ? v * (MESH_MAX_FOOTPRINT / l) : v;
}

void main() {
  // Derivatives first, in uniform control flow.
  vec3 position = mesh_position * mesh_texture_scale;
  vec3 dpdx = mesh_clamp_length(dFdx(position));
  vec3 dpdy = mesh_clamp_length(dFdy(position));
  vec2 uv = mesh_uv * mesh_texture_scale;
  vec2 duvdx = mesh_clamp_length(dFdx(uv));
  vec2 duvdy = mesh_clamp_length(dFdy(uv));
  // The face's normal where the interpolated one cancels: both derivatives lie in its plane.
  vec3 face = cross(dFdx(mesh_position), dFdy(mesh_position));
  vec3 normal = length(mesh_normal) > 1e-6 ? normalize(mesh_normal) : normalize(face);
  vec3 tangent = mesh_surface_tangent(normal);
#ifdef STOCHTEX_MESH_UV
  vec4 value = STOCHTEX_MESH_UV(uv, duvdx, duvdy, seed);
#else
  vec4 value = STOCHTEX_SURFACE_CALL;
#endif
  // shading (mesh_shading.hpp): Lambert + ambient, the normal turned towards the viewer.
  vec3 facing = dot(normal, mesh_position - mesh_eye) > 0.0 ? -normal : normal;
  float light = MESH_AMBIENT + (1.0 - MESH_AMBIENT) * max(0.0, dot(facing, mesh_light));
  bvec4 lit = lessThan(ivec4(0, 1, 2, 3), ivec4(mesh_colours));
  colour = mix(value, value * light, lit);
}

// The fragment shader of the GL mesh renderer (mesh_gl.cpp), the way an engine calls an exported
// shader: the surface point from the interpolated position, normal and uv, its footprints from the
// CPU renderer's exact ray differentials on the triangle's plane (src/render/mesh_shading.hpp,
// docs/meshes.md), the method's GLSL function, and the CPU's shading. Requires, before it,
// MESH_AMBIENT and MESH_MAX_FOOTPRINT (from the C++ constants), the method's library, and either
// STOCHTEX_MESH_UV (the 2-D entry stochtex_<method>, called at the mesh's uv) or
// STOCHTEX_SURFACE_CALL (a gl::SurfaceShader's call expression, from position, normal, tangent,
// dpdx, dpdy, seed and parameter). A material (uv only) defines STOCHTEX_MESH_UV as the exported
// stochtex_<method>_material and STOCHTEX_MESH_COLOUR(m), with STOCHTEX_MESH_NORMAL(m) and
// STOCHTEX_MESH_OCCLUSION(m) where it has them (mesh_gl.cpp's material_macros).

in vec3 mesh_position;
in vec3 mesh_normal;
in vec2 mesh_uv;

uniform vec3 mesh_eye;
// The CPU's PixelRays: the ray through the picture's pixel (x, y) has the direction
// forward + (x + 1/2 - width/2) step_x + (y + 1/2 - height/2) step_y; mesh_pixel_offset is the
// tile's origin less half the picture (gl_FragCoord is the tile's pixel centre, rows unflipped).
uniform vec3 mesh_forward;
uniform vec3 mesh_step_x;
uniform vec3 mesh_step_y;
uniform vec2 mesh_pixel_offset;
uniform vec3 mesh_light;  // unit, towards the light
uniform float mesh_texture_scale;
uniform int mesh_colours;  // channels shaded; the others (alpha) pass through
uniform uint seed;
uniform float parameter;

// Per triangle (gl_PrimitiveID), computed in double by mesh_gl.cpp: the unit normal of its plane,
// and the rows of the linear map from a displacement in its plane to the uv's displacement
// (barycentric_gradients in mesh_shading.hpp through the corners' uvs; zero without uvs).
layout(std430, binding = 7) readonly buffer MeshFaces { vec4 mesh_faces[]; };

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
  return l > MESH_MAX_FOOTPRINT ? v * MESH_MAX_FOOTPRINT / l : v;
}

#ifdef STOCHTEX_MESH_NORMAL
// The normal n bumped by a normal map's unit tangent-space normal m at the uv (render_mesh's
// bump_gradients for the uv mapping, mesh_shading.hpp; M. S. Mikkelsen, "Surface Gradient-Based
// Bump Mapping Framework", JCGT 9(3), 2020): its slopes s = -m.xy / m.z as the height's gradient
// over the texture coordinates, g = (s_x, -s_y) (texture_gradient_of_slopes), through the
// triangle's texture gradients x and y (texture_gradients' columns): the surface gradient
// x g_x + y g_y less its part along n, over the square root of |x cross y|
// (texture_surface_gradient; none where that is degenerate), subtracted from n.
vec3 mesh_bumped_normal(vec3 n, mat2x3 texture_gradients, vec3 m) {
  float area = length(cross(texture_gradients[0], texture_gradients[1]));
  if (!(area > 0.0) || isinf(area)) return n;
  vec3 gradient = texture_gradients * (vec2(-m.x, m.y) / m.z);
  return normalize(n - (gradient - n * dot(n, gradient)) / sqrt(area));
}
#endif

void main() {
  vec3 face = mesh_faces[3 * gl_PrimitiveID].xyz;
  // The pixel's ray and its parameter t at the fragment (d . forward = 1), and the ray
  // differentials on the plane (plane_differentials): dp/dx = t (step_x - (n.step_x / n.d) d).
  vec3 d = mesh_forward + mesh_step_x * (gl_FragCoord.x + mesh_pixel_offset.x) +
           mesh_step_y * (gl_FragCoord.y + mesh_pixel_offset.y);
  float t = dot(mesh_position - mesh_eye, mesh_forward);
  float nd = dot(face, d);
  vec3 plane_dpdx = (mesh_step_x - d * (dot(face, mesh_step_x) / nd)) * t;
  vec3 plane_dpdy = (mesh_step_y - d * (dot(face, mesh_step_y) / nd)) * t;
  vec3 position = mesh_position * mesh_texture_scale;
  vec3 dpdx = mesh_clamp_length(plane_dpdx * mesh_texture_scale);
  vec3 dpdy = mesh_clamp_length(plane_dpdy * mesh_texture_scale);
  vec3 normal = length(mesh_normal) > 1e-6 ? normalize(mesh_normal) : face;
  vec3 tangent = mesh_surface_tangent(normal);
  vec3 shading_normal = normal;
  float occlusion = 1.0;
#ifdef STOCHTEX_MESH_UV
  mat2x3 uv_map = mat2x3(mesh_faces[3 * gl_PrimitiveID + 1].xyz,
                         mesh_faces[3 * gl_PrimitiveID + 2].xyz);
  vec2 uv = mesh_uv * mesh_texture_scale;
  vec2 duvdx = mesh_clamp_length(plane_dpdx * uv_map * mesh_texture_scale);
  vec2 duvdy = mesh_clamp_length(plane_dpdy * uv_map * mesh_texture_scale);
#ifdef STOCHTEX_MESH_COLOUR
  StochtexMaterial material = STOCHTEX_MESH_UV(uv, duvdx, duvdy, seed);
  vec4 value = STOCHTEX_MESH_COLOUR(material);
#ifdef STOCHTEX_MESH_NORMAL
  shading_normal =
      mesh_bumped_normal(normal, uv_map * mesh_texture_scale, STOCHTEX_MESH_NORMAL(material));
#endif
#ifdef STOCHTEX_MESH_OCCLUSION
  occlusion = clamp(STOCHTEX_MESH_OCCLUSION(material), 0.0, 1.0);
#endif
#else
  vec4 value = STOCHTEX_MESH_UV(uv, duvdx, duvdy, seed);
#endif
#else
  vec4 value = STOCHTEX_SURFACE_CALL;
#endif
  // shading (mesh_shading.hpp): Lambert + ambient (a material's: the bumped normal, the ambient
  // term times its occlusion), the normal turned towards the viewer as the surface's own is.
  vec3 facing = dot(normal, mesh_position - mesh_eye) > 0.0 ? -shading_normal : shading_normal;
  float light =
      MESH_AMBIENT * occlusion + (1.0 - MESH_AMBIENT) * max(0.0, dot(facing, mesh_light));
  bvec4 lit = lessThan(ivec4(0, 1, 2, 3), ivec4(mesh_colours));
  colour = mix(value, value * light, lit);
}

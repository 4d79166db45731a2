// The compute shader of the GL surface evaluator (surface_gl.cpp): one invocation per surface
// point. Requires the method's surface library (gl::SurfaceShader), then STOCHTEX_CHANNELS and
// STOCHTEX_SURFACE_CALL, the library's call expression, defined by surface_gl.cpp.

layout(local_size_x = 64) in;
// Per point 15 floats: position, normal, tangent, dpdx, dpdy (model space).
layout(std430, binding = 2) readonly buffer Points { float points[]; };
layout(std430, binding = 1) writeonly buffer Result { float result[]; };

uniform int point_count;
uniform uint seed;
uniform float parameter;

vec3 stochtex_point_vector(int first) {
  return vec3(points[first], points[first + 1], points[first + 2]);
}

void main() {
  int index = int(gl_GlobalInvocationID.x);
  if (index >= point_count) return;
  int first = index * 15;
  vec3 position = stochtex_point_vector(first);
  vec3 normal = stochtex_point_vector(first + 3);
  vec3 tangent = stochtex_point_vector(first + 6);
  vec3 dpdx = stochtex_point_vector(first + 9);
  vec3 dpdy = stochtex_point_vector(first + 12);
  vec4 value = STOCHTEX_SURFACE_CALL;
  for (int c = 0; c < STOCHTEX_CHANNELS; ++c) result[index * STOCHTEX_CHANNELS + c] = value[c];
}

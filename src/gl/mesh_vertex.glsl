// The vertex shader of the GL mesh renderer (mesh_gl.cpp): the mesh's position, normal and uv
// passed to the fragment shader (mesh_fragment.glsl), the position projected by the camera of
// src/render/mesh_shading.hpp (clip_from_eye, made by mesh_gl.cpp, applied to position - eye).

layout(location = 0) in vec3 vertex_position;
layout(location = 1) in vec3 vertex_normal;
layout(location = 2) in vec2 vertex_uv;

uniform vec3 mesh_eye;
uniform mat4 clip_from_eye;

out vec3 mesh_position;
out vec3 mesh_normal;
out vec2 mesh_uv;

void main() {
  mesh_position = vertex_position;
  mesh_normal = vertex_normal;
  mesh_uv = vertex_uv;
  gl_Position = clip_from_eye * vec4(vertex_position - mesh_eye, 1.0);
}

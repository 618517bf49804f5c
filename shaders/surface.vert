#version 330 core
// Cloth and collider surfaces in world coordinates.
layout(location = 0) in vec3 a_position;  // m
layout(location = 1) in vec3 a_normal;    // not necessarily unit
layout(location = 2) in float a_scalar;   // strain per vertex (cloth), else unused

uniform mat4 u_view_projection;

out vec3 v_world;
out vec3 v_normal;
out float v_scalar;

void main() {
  v_world = a_position;
  v_normal = a_normal;
  v_scalar = a_scalar;
  gl_Position = u_view_projection * vec4(a_position, 1.0);
}

#version 330 core
// The ground grid: one large square on the ground; the lines are drawn per
// pixel in grid.frag.
layout(location = 0) in vec3 a_position;

uniform mat4 u_view_projection;

out vec3 v_world;

void main() {
  v_world = a_position;
  gl_Position = u_view_projection * vec4(a_position, 1.0);
}

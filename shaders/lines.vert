#version 330 core
// Lines and points with a colour per vertex (or one colour for all, when the
// colour attribute is left disabled and set as a constant).
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec4 a_colour;

uniform mat4 u_view_projection;
uniform float u_point_size;  // pixels, for points

out vec4 v_colour;

void main() {
  v_colour = a_colour;
  gl_PointSize = u_point_size;
  gl_Position = u_view_projection * vec4(a_position, 1.0);
}

#version 330 core
// Lines and points in one colour per vertex; points may be discs (nodes).
in vec4 v_colour;

uniform int u_round_points;  // 1: points are discs

out vec4 frag_colour;

void main() {
  if (u_round_points == 1 && length(gl_PointCoord - vec2(0.5)) > 0.5) discard;
  frag_colour = v_colour;
}

#version 330 core
in float v_scalar;

out vec4 frag_colour;

void main() { frag_colour = vec4(strain_colour(v_scalar), 1.0); }

#version 330 core
// Soft two-sided lighting: a hemisphere light (sky above, ground bounce below)
// plus a wrapped key light that moves with the camera, and a faint highlight.
// The side of a triangle facing the viewer decides the normal's sign and the
// tone, so the cloth's back shows in its own colour.
in vec3 v_world;
in vec3 v_normal;
in float v_scalar;

uniform vec3 u_front_colour;
uniform vec3 u_back_colour;
uniform int u_use_strain;      // 1: colour by v_scalar / u_strain_max instead
uniform float u_strain_max;
uniform vec3 u_eye;
uniform vec3 u_key_direction;  // unit, towards the light

out vec4 frag_colour;

void main() {
  float len = length(v_normal);
  vec3 n = len > 1e-12 ? v_normal / len : vec3(0.0, 1.0, 0.0);
  if (!gl_FrontFacing) n = -n;
  vec3 base = gl_FrontFacing ? u_front_colour : u_back_colour;
  if (u_use_strain == 1) base = strain_colour(v_scalar / u_strain_max);

  vec3 sky = vec3(0.95, 0.97, 1.00), ground = vec3(0.50, 0.46, 0.42);
  vec3 ambient = 0.6 * mix(ground, sky, 0.5 + 0.5 * n.y);
  float wrapped = max((dot(n, u_key_direction) + 0.3) / 1.3, 0.0);
  vec3 diffuse = 0.55 * wrapped * vec3(1.00, 0.97, 0.92);
  vec3 to_eye = normalize(u_eye - v_world);
  vec3 half_way = normalize(to_eye + u_key_direction);
  float highlight = 0.06 * pow(max(dot(n, half_way), 0.0), 32.0);
  frag_colour = vec4(min(base * (ambient + diffuse) + vec3(highlight), vec3(1.0)), 1.0);
}

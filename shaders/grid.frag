#version 330 core
// Grid lines computed per pixel, about a pixel wide whatever the distance
// (fwidth measures how much grid one pixel spans), so they stay smooth
// instead of aliasing; every tenth line is darker. The grid fades out with
// the distance from the point the camera circles.
in vec3 v_world;

uniform float u_cell;          // m between lines
uniform vec3 u_origin;         // a point where major lines cross
uniform vec3 u_minor_colour;
uniform vec3 u_major_colour;
uniform vec3 u_fade_centre;
uniform float u_fade_radius;

out vec4 frag_colour;

// 1 on a line of the lattice with unit spacing, falling to 0 a pixel away.
float line_coverage(vec2 coord) {
  vec2 width = max(fwidth(coord), vec2(1e-6));
  vec2 distance_in_pixels = abs(fract(coord - 0.5) - 0.5) / width;
  return 1.0 - min(min(distance_in_pixels.x, distance_in_pixels.y), 1.0);
}

void main() {
  vec2 coord = (v_world.xz - u_origin.xz) / u_cell;
  float minor = line_coverage(coord);
  float major = line_coverage(coord / 10.0);
  float fade = 1.0 - smoothstep(0.35 * u_fade_radius, u_fade_radius,
                                length(v_world.xz - u_fade_centre.xz));
  float alpha = max(0.45 * minor, 0.8 * major) * fade;
  if (alpha <= 0.0) discard;
  frag_colour = vec4(mix(u_minor_colour, u_major_colour, major), alpha);
}

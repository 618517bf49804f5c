#version 330 core
// The ground grid: a strip along each line, widened on the ground to the few
// pixels where grid.frag can draw that line (twice the ground the line's
// one-pixel ramp spans there), so llvmpipe shades only those pixels and not
// the whole square. The width is of the line's own pixels: narrow where the
// line runs towards the viewer, wide where the ground is seen edge on.
layout(location = 0) in vec3 a_centre;  // on the line, m
layout(location = 1) in vec3 a_side;    // unit, on the ground, across the line, +-1 for the side

uniform mat4 u_view_projection;
uniform vec2 u_viewport;          // px
uniform float u_max_half_width;   // m: half a cell, where strips meet and cover all

out vec3 v_world;

// Pixels moved on the screen per metre moved along `d` from the point at clip c.
vec2 pixels_per_metre(vec4 c, vec3 d) {
  vec4 dc = u_view_projection * vec4(d, 0.0);
  return 0.5 * u_viewport * (dc.xy * c.w - c.xy * dc.w) / (c.w * c.w);
}

void main() {
  vec3 across = a_side;                       // +-unit
  vec3 along = vec3(across.z, 0.0, -across.x);
  vec4 c = u_view_projection * vec4(a_centre, 1.0);
  float half_width = u_max_half_width;
  // Behind or at the eye the projection says nothing: the widest strip.
  if (c.w > 1e-4) {
    vec2 ju = pixels_per_metre(c, along), jv = pixels_per_metre(c, across);
    float det = ju.x * jv.y - jv.x * ju.y;
    // Metres across the line per pixel, summed over x and y as fwidth does.
    if (abs(det) > 1e-12) half_width = min(2.0 * (abs(ju.x) + abs(ju.y)) / abs(det), u_max_half_width);
  }
  v_world = a_centre + half_width * across;
  gl_Position = u_view_projection * vec4(v_world, 1.0);
}

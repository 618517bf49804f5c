#version 330 core
// The strain legend's colour bar, placed in pixels (origin top left).
layout(location = 0) in vec2 a_pixel;
layout(location = 2) in float a_scalar;  // 0 at the bottom of the bar, 1 at the top

uniform vec2 u_viewport;  // width, height in pixels

out float v_scalar;

void main() {
  v_scalar = a_scalar;
  gl_Position = vec4(2.0 * a_pixel.x / u_viewport.x - 1.0, 1.0 - 2.0 * a_pixel.y / u_viewport.y,
                     0.0, 1.0);
}

// The strain colour map: 0 (rest length or shorter) is blue, 1 (strain_max or
// more) is red, through a light neutral in between so that the middle of the
// range reads as neither (a diverging map after Moreland's "cool to warm").
vec3 strain_colour(float s) {
  const vec3 cool = vec3(0.23, 0.30, 0.75);
  const vec3 neutral = vec3(0.87, 0.86, 0.84);
  const vec3 warm = vec3(0.75, 0.05, 0.10);
  float t = clamp(s, 0.0, 1.0);
  return t < 0.5 ? mix(cool, neutral, 2.0 * t) : mix(neutral, warm, 2.0 * t - 1.0);
}

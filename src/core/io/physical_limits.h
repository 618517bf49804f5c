#pragma once
// The widest values a scene file, a rule base's outputs or a trade may give a
// simulation: far beyond any cloth anyone simulates, yet small enough that
// positions, forces and energies stay finite numbers, and that a step is not
// so small that a run never ends. What lies outside is refused at the
// boundary with the field named and the reason given (docs/robustness.md).
// The viewer's live sliders use narrower ranges (runtime/parameter_ranges.cpp).
#include <string>

namespace neurocloth {

struct Limit {
  double low, high;
  const char* unit;     // "" for a pure number
  const char* meaning;  // why the bounds are there, for the message

  bool contains(double v) const { return v >= low && v <= high; }
  // "must be in [1e-09, 1e+04] kg (got 5e-324): <meaning>"
  std::string refusal(double got) const;
};

namespace limits {
// Geometry.
inline constexpr Limit kCoordinate{-1e4, 1e4, "m", "a scene lies within 10 km of the origin"};
inline constexpr Limit kDirection{-1e4, 1e4, "",
                                  "only the direction counts; a component beyond 1e4 is a slip"};
inline constexpr Limit kSpacing{1e-4, 100, "m", "nodes lie between 0.1 mm and 100 m apart"};
inline constexpr Limit kMeshScale{1e-6, 1e6, "", "a scale beyond 1e-6 to 1e6 is a unit mistake"};
inline constexpr Limit kAngle{-36000, 36000, "degrees",
                              "a hundred turns is the most a rotation key may say"};
inline constexpr Limit kSize{1e-4, 2e4, "m", "a collider is between 0.1 mm and 20 km across"};
inline constexpr Limit kThickness{0, 1, "m", "a contact layer is at most 1 m thick"};
inline constexpr Limit kGap{1e-5, 1, "m", "cloth keeps between 0.01 mm and 1 m from itself"};
// A spring spans at most the 20 km across which every node lies; zero only
// where the mesh itself has a zero-length edge (such a spring exerts no force).
inline constexpr Limit kRestLength{0, 2e4, "m", "every node lies within 10 km of the origin"};
// Material.
inline constexpr Limit kNodeMass{1e-9, 1e4, "kg",
                                 "a mass point weighs between a microgram and ten tonnes"};
inline constexpr Limit kStiffness{0, 1e9, "N/m", "no cloth spring is stiffer than 1e9 N/m"};
inline constexpr Limit kViscosity{0, 1e6, "N s/m", "no cloth damps more than 1e6 N s/m"};
inline constexpr Limit kFriction{0, 10, "", "a Coulomb coefficient above 10 is a typo"};
inline constexpr Limit kStrain{0, 10, "", "a spring ten times its rest length is no longer cloth"};
inline constexpr Limit kStiffening{1, 1e6, "", "a spring stiffens at most a million-fold"};
inline constexpr Limit kStretch{1, 100, "", "a spring stretches at most a hundred-fold"};
// A fabric as a lab measures it (docs/materials.md, "Measured units").
inline constexpr Limit kArealDensity{
    0.005, 5, "kg/m^2", "from the sheerest tissue (5 g/m^2) to heavy canvas or leather"};
inline constexpr Limit kBendingRigidity{
    1e-9, 1, "N m", "from a sheer film to a board: a fabric's B lies between 1e-8 and 1e-2"};
inline constexpr Limit kBendingLength{
    1e-3, 1, "m", "a cantilever's bending length lies between 1 mm (chiffon) and 1 m (a board)"};
inline constexpr Limit kTensileStiffness{
    1, 1e7, "N/m", "from a loose knit (~10 N/m) to a dense technical weave (~1e6 N/m)"};
inline constexpr Limit kShearStiffness{0.01, 1e6, "N/m",
                                       "a fabric's in-plane shear lies between 1 and 1e4 N/m"};
inline constexpr Limit kTolerance{0, 1, "", "a relative tolerance is a fraction"};
// Motion and forces.
inline constexpr Limit kAcceleration{-1e3, 1e3, "m/s^2", "gravity stays within 100 g"};
inline constexpr Limit kSpeed{-1e3, 1e3, "m/s", "wind stays below three times sound"};
inline constexpr Limit kFrequency{0, 1e3, "Hz", "a pin moves at most a thousand times a second"};
inline constexpr Limit kRate{0, 1e4, "1/s", "air slows a node within 0.1 ms at the most"};
inline constexpr Limit kDensity{0, 1e4, "kg/m^3", "air or water, not lead"};
inline constexpr Limit kCoefficient{0, 100, "", "an aerodynamic coefficient stays below 100"};
inline constexpr Limit kGustAmplitude{0, 10, "", "a gust is at most ten times the mean wind"};
// Time.
inline constexpr Limit kTimeStep{1e-6, 1e9, "s",
                                 "a step below a microsecond would take millions per second"};
inline constexpr Limit kDuration{0, 1e6, "s", "a scene's motion is scripted over at most 1e6 s"};
inline constexpr Limit kStepFraction{
    1e-6, 1, "", "the adaptive step's floor is at least a millionth of its cap"};
inline constexpr Limit kGrowthTolerance{0, 1e3, "", "a force may grow at most a thousand-fold"};
inline constexpr Limit kFrameRate{
    1e-3, 1e4, "frames/s", "a cache is sampled between once in 1000 s and 10000 times a second"};
inline constexpr Limit kPeriod{1e-3, 1e6, "s", "a gust lasts between 1 ms and 1e6 s"};
// --size N: a cloth resized to N x N nodes (resized_grid).
inline constexpr Limit kGridSize{2, 1024, "", "nodes a side: at most a million nodes"};
// Loops whose length a file sets.
inline constexpr Limit kStrainIterations{1, 1000, "",
                                         "each sweep costs a pass over the springs every step"};
inline constexpr Limit kCollisionIterations{1, 100, "",
                                            "each pass costs a spatial-hash sweep every step"};
inline constexpr Limit kIterations{1, 1000, "",
                                   "each local-global iteration costs a solve every step"};
inline constexpr Limit kLinearTolerance{
    1e-14, 1e-2, "", "the implicit step's relative residual, between rounding and 1%"};
inline constexpr Limit kCheckInterval{1, 1000000, "", "checks come at least once a million steps"};
}  // namespace limits

// %g: 1e+308 rather than 309 digits.
std::string show_number(double v);

}  // namespace neurocloth

#pragma once
// The renderer's colours (linear RGB, 0..1), in one place so that the tests
// can tell the cloth's pixels from everything else: the cloth is warm (red
// well above blue) on both sides, while the background, the grid and the
// colliders are neutral or cool.
#include <array>

namespace neurocloth::palette {

using Colour = std::array<float, 3>;

inline constexpr Colour kBackground = {0.86f, 0.88f, 0.91f};
inline constexpr Colour kClothFront = {0.86f, 0.40f, 0.18f};  // terracotta
inline constexpr Colour kClothBack = {0.62f, 0.50f, 0.26f};   // khaki
inline constexpr Colour kCollider = {0.60f, 0.63f, 0.68f};
inline constexpr Colour kGridMinor = {0.56f, 0.59f, 0.64f};
inline constexpr Colour kGridMajor = {0.38f, 0.41f, 0.47f};
inline constexpr Colour kWire = {0.18f, 0.10f, 0.06f};
inline constexpr Colour kSpring[3] = {{0.10f, 0.25f, 0.85f},   // structural
                                      {0.10f, 0.62f, 0.22f},   // shear
                                      {0.78f, 0.15f, 0.68f}};  // bend
inline constexpr Colour kNodeFree = {0.12f, 0.12f, 0.14f};
inline constexpr Colour kNodePinned = {0.90f, 0.08f, 0.08f};
inline constexpr Colour kForce = {0.85f, 0.05f, 0.60f};
// The reference motion's ghost points (the Learning panel): cool and bright,
// unlike anything else in the frame.
inline constexpr Colour kGhost = {0.0f, 0.80f, 0.90f};
inline constexpr Colour kLegendText = {0.10f, 0.10f, 0.12f};

}  // namespace neurocloth::palette

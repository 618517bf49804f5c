// The disc cloth: its counts, its area against the circle's, its outline on
// the circle, its triangles' shapes and winding, its springs (a structural one
// per edge, a bend one across each interior edge), and the scene file's
// "cloth.disc" read and refused.
#include "core/scene/disc_builder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "core/scene/scene.h"
#include "support/input_error_check.h"
#include "support/scene_builder.h"

namespace neurocloth::disc_builder_test {

using Edge = std::pair<int, int>;

// Each edge of the triangles and how many triangles hold it.
std::map<Edge, int> edge_uses(const ClothTopology& t) {
  std::map<Edge, int> uses;
  for (const auto& tri : t.triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = tri[k], b = tri[(k + 1) % 3];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  return uses;
}

Vec3 corner(const ClothTopology& t, const std::array<std::int32_t, 3>& tri, int k) {
  return t.rest_positions[static_cast<std::size_t>(tri[static_cast<std::size_t>(k)])];
}

// (b - a) x (c - a): twice the area, along the side the triangle faces.
Vec3 doubled_normal(const ClothTopology& t, const std::array<std::int32_t, 3>& tri) {
  const Vec3 a = corner(t, tri, 0);
  return (corner(t, tri, 1) - a).cross(corner(t, tri, 2) - a);
}

double total_area(const ClothTopology& t) {
  double area = 0;
  for (const auto& tri : t.triangles)
    area += 0.5 * doubled_normal(t, tri).norm();
  return area;
}

double min_angle_degrees(const ClothTopology& t) {
  double least = 180;
  for (const auto& tri : t.triangles)
    for (int k = 0; k < 3; ++k) {
      const Vec3 a = corner(t, tri, k), b = corner(t, tri, (k + 1) % 3),
                 c = corner(t, tri, (k + 2) % 3);
      const double cosine = (b - a).normalized().dot((c - a).normalized());
      least = std::min(least, std::acos(std::clamp(cosine, -1.0, 1.0)) * 180 / kPi);
    }
  return least;
}

DiscSpec disc(int rings, double radius = 0.15) {
  DiscSpec s;
  s.rings = rings;
  s.radius = radius;
  return s;
}

TEST(DiscBuilder, RingKHoldsSixKNodesAndTheTrianglesTileTheDisc) {
  for (int rings : {1, 2, 3, 5, 12, 24}) {
    const ClothTopology t = build_disc(disc(rings));
    const std::size_t nodes = 1 + 3 * std::size_t(rings) * std::size_t(rings + 1);
    EXPECT_EQ(t.rest_positions.size(), nodes) << rings;
    EXPECT_EQ(t.triangles.size(), 6 * std::size_t(rings) * std::size_t(rings)) << rings;
    // One piece without holes: V - E + F = 1, and the outline is 6 rings edges.
    const std::map<Edge, int> uses = edge_uses(t);
    EXPECT_EQ(long(nodes) - long(uses.size()) + long(t.triangles.size()), 1) << rings;
    std::size_t boundary = 0;
    for (const auto& [edge, n] : uses) {
      EXPECT_LE(n, 2) << rings;
      boundary += n == 1;
    }
    EXPECT_EQ(boundary, 6 * std::size_t(rings)) << rings;
    // Its springs: one structural per edge, one bend across each interior edge.
    std::size_t structural = 0, bend = 0;
    for (const SpringSpec& s : t.springs) {
      structural += s.family == SpringFamily::structural;
      bend += s.family == SpringFamily::bend;
      EXPECT_NE(s.family, SpringFamily::shear);
    }
    EXPECT_EQ(structural, uses.size()) << rings;
    EXPECT_EQ(bend, uses.size() - boundary) << rings;
  }
  DiscSpec flat = disc(6);
  flat.bend = false;
  for (const SpringSpec& s : build_disc(flat).springs)
    EXPECT_EQ(s.family, SpringFamily::structural);
}

// The outline is the regular 6n-gon inscribed in the circle, so the area
// falls short of pi R^2 by 1 - sin(x)/x, x = pi / (3 n): 0.51% at 6 rings,
// 0.13% at 12, 0.032% at 24; the triangles neither overlap nor leave gaps.
TEST(DiscBuilder, ItsAreaIsTheInscribedPolygonsCloseToTheCircles) {
  const double radius = 0.15, circle = kPi * radius * radius;
  for (const auto& [rings, short_by] :
       std::vector<std::pair<int, double>>{{6, 0.0051}, {12, 0.0013}, {24, 0.00032}}) {
    const ClothTopology t = build_disc(disc(rings, radius));
    const double area = total_area(t);
    const double x = kPi / (3 * rings);
    EXPECT_NEAR(area, circle * std::sin(x) / x, 1e-12 * circle) << rings;
    EXPECT_LT(area, circle) << rings;
    EXPECT_GT(area, circle * (1 - short_by)) << rings;
    EXPECT_LT(area, circle * (1 - 0.9 * short_by)) << rings;
    const std::vector<double> lumped = lumped_node_areas(t);
    double sum = 0;
    for (double a : lumped) {
      EXPECT_GT(a, 0);
      sum += a;
    }
    EXPECT_NEAR(sum, area, 1e-12 * circle);
  }
}

// Every node of the outline (on an edge of one triangle) is on the circle;
// every other one is inside it.
TEST(DiscBuilder, TheOutlineIsOnTheCircle) {
  DiscSpec s = disc(9, 0.15);
  s.center = Vec3(0.2, 1.1, -0.3);
  const ClothTopology t = build_disc(s);
  std::set<int> outline;
  for (const auto& [edge, n] : edge_uses(t))
    if (n == 1) {
      outline.insert(edge.first);
      outline.insert(edge.second);
    }
  EXPECT_EQ(outline.size(), 6u * 9u);
  for (std::size_t i = 0; i < t.rest_positions.size(); ++i) {
    const double r = (t.rest_positions[i] - s.center).norm();
    if (outline.count(int(i)))
      EXPECT_NEAR(r, s.radius, 1e-14) << i;
    else
      EXPECT_LT(r, s.radius * (1 - 0.5 / 9)) << i;
  }
}

// Ring 1's triangles are equilateral; further out they are the flat
// lattice's equilateral ones bent round, and no angle falls below 43.5
// degrees (measured: 44.9 at 12 rings, 44.3 at 24, 44.0 at 48), so the
// springs' stiffness is nearly even in every direction.
TEST(DiscBuilder, ItsTrianglesAreNearlyEquilateral) {
  EXPECT_NEAR(min_angle_degrees(build_disc(disc(1))), 60, 1e-9);
  for (int rings : {2, 6, 12, 24, 48, 96})
    EXPECT_GT(min_angle_degrees(build_disc(disc(rings))), 43.5) << rings;
}

// Every triangle faces along the normal, and the disc lies across it.
TEST(DiscBuilder, TrianglesWindAboutTheNormal) {
  for (const Vec3& normal : {Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(1, 0, 0), Vec3(0.3, -0.5, 2)}) {
    DiscSpec s = disc(5);
    s.normal = normal;
    s.center = Vec3(1, 2, 3);
    const ClothTopology t = build_disc(s);
    const Vec3 n = normal.normalized();
    for (const auto& tri : t.triangles) {
      const Vec3 face = doubled_normal(t, tri);
      EXPECT_GT(face.normalized().dot(n), 1 - 1e-12) << normal.transpose();
    }
    for (const Vec3& p : t.rest_positions)
      EXPECT_NEAR((p - s.center).dot(n), 0, 1e-14);
  }
}

TEST(DiscBuilder, RefusesWhatIsNoDisc) {
  EXPECT_THROW(build_disc(disc(0)), std::invalid_argument);
  EXPECT_THROW(build_disc(disc(kMaxDiscRings + 1)), std::invalid_argument);
  EXPECT_THROW(build_disc(disc(3, 0.0)), std::invalid_argument);
  DiscSpec s = disc(3);
  s.normal = Vec3::Zero();
  EXPECT_THROW(build_disc(s), std::invalid_argument);
}

// "cloth": {"disc": ...} in a scene file: the same cloth as build_disc's.
TEST(DiscBuilder, ASceneReadsItsDisc) {
  const Scene scene = test::SceneBuilder(2, 2, 0.1).disc(0.15, 6, Vec3(0, 0.3, 0)).parse();
  DiscSpec s = disc(6);
  s.center = Vec3(0, 0.3, 0);
  const ClothTopology t = build_disc(s);
  EXPECT_EQ(scene.topology.rest_positions, t.rest_positions);
  EXPECT_EQ(scene.topology.triangles, t.triangles);
  EXPECT_EQ(scene.topology.springs.size(), t.springs.size());
  EXPECT_FALSE(scene.grid);

  test::SceneBuilder structural = test::SceneBuilder(2, 2, 0.1).disc(0.15, 6);
  structural.springs({"structural"});
  for (const SpringSpec& spring : structural.parse().topology.springs)
    EXPECT_EQ(spring.family, SpringFamily::structural);
}

// Bad discs are refused naming the field, in one line.
TEST(DiscBuilder, ASceneRefusesABadDiscNamingTheField) {
  const auto bad = [](const std::string& pointer, const nlohmann::json& value) {
    test::SceneBuilder b(2, 2, 0.1);
    b.disc(0.15, 6);
    b.set(pointer, value);
    return b;
  };
  for (const auto& [pointer, value, field, mention] :
       std::vector<std::tuple<std::string, nlohmann::json, std::string, std::string>>{
           {"/cloth/disc/rings", 0, "cloth.disc.rings", "[1, 1000]"},
           {"/cloth/disc/rings", 1000000, "cloth.disc.rings", "1000000"},
           {"/cloth/disc/rings", 2.5, "cloth.disc.rings", ""},
           {"/cloth/disc/normal", {0, 0, 0}, "cloth.disc.normal", "zero"},
           {"/cloth/disc/radius", -0.1, "cloth.disc.radius", ""},
           {"/cloth/disc/radius", "wide", "cloth.disc.radius", ""}}) {
    const test::SceneBuilder b = bad(pointer, value);
    try {
      b.parse("disc.json");
      ADD_FAILURE() << pointer << " = " << value.dump() << " accepted";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(e.field(), field) << what;
      EXPECT_EQ(e.file(), "disc.json") << what;
      EXPECT_GT(e.line(), 0) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
      EXPECT_NE(what.find(mention), std::string::npos) << what;
    }
  }
  // A disc beside a grid is not one cloth.
  test::SceneBuilder both(2, 2, 0.1);
  both.set("/cloth/disc", {{"radius", 0.15}, {"rings", 3}});
  try {
    both.parse("disc.json");
    ADD_FAILURE() << "a grid and a disc accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "cloth") << e.what();
  }
  // Missing the radius or the rings.
  for (const char* key : {"/cloth/disc/radius", "/cloth/disc/rings"}) {
    test::SceneBuilder b(2, 2, 0.1);
    b.disc(0.15, 6).erase(key);
    EXPECT_THROW(b.parse("disc.json"), InputError) << key;
  }
}

}  // namespace neurocloth::disc_builder_test

// The hierarchy's answers (triangle_bvh.h) against every triangle tried in
// turn, bit for bit, on an icosphere, a random soup and a deformed and
// refitted sphere; ties to the lowest index; inside and outside by the
// pseudo-normal near a cube's corners, edges and faces; segments aimed
// exactly at shared edges and vertices of closed meshes never slip through;
// the sharp edges' tree; and a hostile build (identical triangles).
#include "core/geometry/triangle_bvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "support/triangle_meshes.h"

namespace neurocloth {
namespace {

using test::cube_surface;
using test::icosphere;
using test::random_soup;

Vec3 random_direction(std::mt19937& rng) {
  std::normal_distribution<double> g;
  return Vec3(g(rng), g(rng), g(rng)).normalized();
}

void expect_same(const NearestHit& x, const NearestHit& y, const Vec3& p) {
  EXPECT_EQ(x.triangle, y.triangle) << p.transpose();
  EXPECT_EQ(x.distance, y.distance) << p.transpose();
  EXPECT_EQ(x.point, y.point) << p.transpose();
  EXPECT_EQ(x.weights, y.weights) << p.transpose();
  EXPECT_EQ(x.feature, y.feature) << p.transpose();
  EXPECT_EQ(x.corner, y.corner) << p.transpose();
}

void expect_same(const SegmentHit& x, const SegmentHit& y, const Vec3& a) {
  EXPECT_EQ(x.triangle, y.triangle) << a.transpose();
  EXPECT_EQ(x.t, y.t) << a.transpose();
  EXPECT_EQ(x.point, y.point) << a.transpose();
  EXPECT_EQ(x.weights, y.weights) << a.transpose();
}

// Nearest points from points scattered about the surface (half close to the
// unit sphere, half anywhere from 0.3 to 1.7 from its centre) and first
// crossings of segments, short and long, each from the tree and from every
// triangle: the same bits, and the same hits found. Returns how many queries
// found something, so a test can see that it asked real questions.
struct Found {
  int nearest = 0, crossing = 0;
};
Found expect_brute_force_answers(const TriangleSurface& s, const TriangleBvh& bvh, unsigned seed,
                                 int queries) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> shell(0.9, 1.1), wide(0.3, 1.7), u(0, 1);
  const double radii[] = {HUGE_VAL, 0.3, 0.05};
  Found found;
  for (int q = 0; q < queries; ++q) {
    const Vec3 p = (q % 2 ? shell(rng) : wide(rng)) * random_direction(rng);
    const double radius = radii[q % 3];
    NearestHit tree, brute;
    const bool in_tree = bvh.nearest(s, p, radius, tree);
    EXPECT_EQ(in_tree, nearest_brute_force(s, p, radius, brute)) << p.transpose();
    if (in_tree) expect_same(tree, brute, p);
    found.nearest += in_tree;

    const Vec3 b = p + (q % 4 < 2 ? 0.1 : 2.0) * u(rng) * random_direction(rng);
    SegmentHit seg_tree, seg_brute;
    const bool hit = bvh.first_hit(s, p, b, seg_tree);
    EXPECT_EQ(hit, first_hit_brute_force(s, p, b, seg_brute)) << p.transpose();
    if (hit) expect_same(seg_tree, seg_brute, p);
    found.crossing += hit;
  }
  return found;
}

TEST(TriangleBvh, MatchesBruteForceOnAnIcosphere) {
  const TriangleSurface s = icosphere(4);
  TriangleBvh bvh;
  bvh.build(s);
  const Found found = expect_brute_force_answers(s, bvh, 1, 3000);
  EXPECT_GT(found.nearest, 1900);  // measured 1997
  EXPECT_GT(found.crossing, 700);  // 764
}

TEST(TriangleBvh, MatchesBruteForceOnARandomSoup) {
  const TriangleSurface s = random_soup(3000, 0.08, 2);
  TriangleBvh bvh;
  bvh.build(s);
  const Found found = expect_brute_force_answers(s, bvh, 3, 3000);
  EXPECT_GT(found.nearest, 2300);  // measured 2361
  EXPECT_GT(found.crossing, 450);  // 507
}

TEST(TriangleBvh, RefitAfterMovingMatchesAFreshBuild) {
  TriangleSurface s = icosphere(4);
  TriangleBvh refitted;
  refitted.build(s);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> noise(-0.01, 0.01);
  for (int step = 1; step <= 3; ++step) {
    // A swell along x and a ripple, as a breathing body would, and noise.
    for (Vec3& v : s.vertices) {
      v.x() *= 1.1;
      v.z() += 0.05 * std::sin(6 * v.y());
      v += Vec3(noise(rng), noise(rng), noise(rng));
    }
    finish_moved_surface(s);
    refitted.refit(s);
    TriangleBvh fresh;
    fresh.build(s);
    // Every triangle still lies in each box on its way down from the root.
    const auto& nodes = refitted.triangle_tree().nodes();
    const auto& items = refitted.triangle_tree().items();
    for (const BoxTree::Node& n : nodes) {
      if (!n.leaf()) continue;
      for (std::int32_t k = n.start; k < n.start + n.count; ++k) {
        const BoundingBox b = triangle_box(s, items[static_cast<std::size_t>(k)]);
        EXPECT_TRUE((n.lo.array() <= b.lo.array()).all() && (b.hi.array() <= n.hi.array()).all());
      }
    }
    EXPECT_EQ(refitted.bounds().lo, fresh.bounds().lo);
    EXPECT_EQ(refitted.bounds().hi, fresh.bounds().hi);
    const Found found = expect_brute_force_answers(s, refitted, 10 + step, 1500);
    EXPECT_GT(found.nearest, 900);   // measured 950 to 993
    EXPECT_GT(found.crossing, 380);  // 402 to 416
    expect_brute_force_answers(s, fresh, 20 + step, 300);
  }
}

TEST(TriangleBvh, EqualDistancesGoToTheLowestIndex) {
  // A soup with copies of one triangle at indices 7, 19 and 400 (the copies
  // have vertices of their own), away from the rest: every query near them
  // answers 7.
  TriangleSurface s = random_soup(500, 0.05, 5);
  const std::array<std::int32_t, 3> copies = {7, 19, 400};
  for (std::int32_t t : copies)
    for (int k = 0; k < 3; ++k)
      s.vertices[static_cast<std::size_t>(s.triangles[static_cast<std::size_t>(t)][k])] =
          Vec3(3.1, 3.2, 3.3) + 0.1 * Vec3(k == 0, k == 1, k == 2);
  finish_surface(s);
  TriangleBvh bvh;
  bvh.build(s);
  const std::int32_t reversed[] = {400, 19, 7};
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  for (int q = 0; q < 200; ++q) {
    const Vec3 centre(3.1 + 0.1 / 3, 3.2 + 0.1 / 3, 3.3 + 0.1 / 3);
    const Vec3 p = centre + Vec3(u(rng), u(rng), u(rng));
    NearestHit hit, among;
    ASSERT_TRUE(bvh.nearest(s, p, HUGE_VAL, hit));
    EXPECT_EQ(hit.triangle, 7);
    ASSERT_TRUE(nearest_among(s, p, HUGE_VAL, reversed, 3, among));
    expect_same(among, hit, p);
    // Through the triangles, along their normal.
    const Vec3 n = s.face_normals[7];
    SegmentHit seg, seg_among;
    ASSERT_TRUE(bvh.first_hit(s, p + 0.1 * n, p - 0.1 * n, seg));
    EXPECT_EQ(seg.triangle, 7);
    ASSERT_TRUE(first_hit_among(s, p + 0.1 * n, p - 0.1 * n, reversed, 3, seg_among));
    expect_same(seg_among, seg, p);
  }
}

TEST(TriangleBvh, RadiusIsStrictAndDegenerateTrianglesAreNeverHit) {
  TriangleSurface s;
  s.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0.5}, {1, 0, 0.5}, {2, 0, 0.5}};
  s.triangles = {{0, 1, 2}, {3, 4, 5}};  // the second is a segment
  finish_surface(s);
  TriangleBvh bvh;
  bvh.build(s);
  NearestHit hit;
  EXPECT_FALSE(bvh.nearest(s, Vec3(0.25, 0.25, 0.5), 0.5, hit));
  ASSERT_TRUE(bvh.nearest(s, Vec3(0.25, 0.25, 0.5), std::nextafter(0.5, 1.0), hit));
  EXPECT_EQ(hit.triangle, 0);
  EXPECT_EQ(hit.distance, 0.5);
  EXPECT_EQ(hit.feature, TriangleFeature::face);
  SegmentHit seg;
  EXPECT_FALSE(bvh.first_hit(s, Vec3(1.5, -1, 0.5), Vec3(1.5, 1, 0.5), seg));  // the segment's line
  EXPECT_FALSE(bvh.first_hit(s, Vec3(0.2, 0.2, 1), Vec3(0.2, 0.2, 1), seg));   // no length
  EXPECT_FALSE(bvh.nearest(s, Vec3(NAN, 0, 0), HUGE_VAL, hit));
  // Only degenerate triangles: nothing at all.
  TriangleSurface slivers;
  slivers.vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  slivers.triangles = {{0, 1, 2}, {2, 1, 0}};
  finish_surface(slivers);
  bvh.build(slivers);
  EXPECT_FALSE(bvh.nearest(slivers, Vec3(1, 1, 0), HUGE_VAL, hit));
  EXPECT_FALSE(bvh.first_hit(slivers, Vec3(1, 1, 0), Vec3(1, -1, 0), seg));
  // No triangles.
  bvh.build(TriangleSurface{});
  EXPECT_FALSE(bvh.nearest(TriangleSurface{}, Vec3(1, 1, 0), HUGE_VAL, hit));
}

TEST(TriangleBvh, FeaturesAndPseudoNormalsOfACube) {
  const TriangleSurface s = cube_surface();
  TriangleBvh bvh;
  bvh.build(s);
  NearestHit hit;
  ASSERT_TRUE(bvh.nearest(s, Vec3(0.3, 0.2, 1.5), HUGE_VAL, hit));
  EXPECT_EQ(hit.feature, TriangleFeature::face);
  EXPECT_EQ(pseudo_normal(s, hit), Vec3(0, 0, 1));
  ASSERT_TRUE(bvh.nearest(s, Vec3(1.2, 0.3, 1.2), HUGE_VAL, hit));
  EXPECT_EQ(hit.feature, TriangleFeature::edge);
  EXPECT_NEAR((pseudo_normal(s, hit) - Vec3(1, 0, 1) / std::sqrt(2.0)).norm(), 0, 1e-15);
  EXPECT_NEAR((hit.point - Vec3(1, 0.3, 1)).norm(), 0, 1e-15);
  ASSERT_TRUE(bvh.nearest(s, Vec3(-1.1, 1.3, -1.2), HUGE_VAL, hit));
  EXPECT_EQ(hit.feature, TriangleFeature::vertex);
  EXPECT_EQ(hit.point, Vec3(-1, 1, -1));
  EXPECT_NEAR((pseudo_normal(s, hit) - Vec3(-1, 1, -1) / std::sqrt(3.0)).norm(), 0, 1e-15);
}

// Points close to the cube's corners, edges and faces, inside and out:
// the side of the pseudo-normal is the side of the cube.
TEST(TriangleBvh, PseudoNormalTellsInsideFromOutsideOfACube) {
  const TriangleSurface s = cube_surface();
  TriangleBvh bvh;
  bvh.build(s);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1), scale(-9, -1);
  int counts[3] = {0, 0, 0};
  for (int q = 0; q < 6000; ++q) {
    // A target on a corner, an edge or a face, then a small step from it.
    Vec3 target(u(rng), u(rng), u(rng));
    const int pinned = q % 3 + 1;  // coordinates pushed to +-1
    for (int k = 0; k < pinned; ++k)
      target[k] = target[k] > 0 ? 1 : -1;
    const Vec3 p = target + std::pow(10.0, scale(rng)) * random_direction(rng);
    const double outside = p.cwiseAbs().maxCoeff() - 1;
    if (outside == 0) continue;
    NearestHit hit;
    ASSERT_TRUE(bvh.nearest(s, p, HUGE_VAL, hit));
    ++counts[static_cast<int>(hit.feature)];
    const double side = (p - hit.point).dot(pseudo_normal(s, hit));
    EXPECT_EQ(side > 0, outside > 0)
        << p.transpose() << " feature " << static_cast<int>(hit.feature);
    EXPECT_NE(side, 0) << p.transpose();
  }
  // Each feature was nearest for many of them: measured 4529, 1224, 247.
  EXPECT_GT(counts[0], 4000);
  EXPECT_GT(counts[1], 1000);
  EXPECT_GT(counts[2], 200);
}

TEST(TriangleBvh, PseudoNormalTellsInsideFromOutsideOfAnIcosphere) {
  const TriangleSurface s = icosphere(3);
  TriangleBvh bvh;
  bvh.build(s);
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> scale(-9, -2);
  for (int q = 0; q < 3000; ++q) {
    // Near a vertex, or an edge's middle, of the mesh itself (not the sphere).
    const auto& t = s.triangles[static_cast<std::size_t>(q) % s.triangles.size()];
    const Vec3 a = s.vertices[static_cast<std::size_t>(t[0])];
    const Vec3 target = q % 2 ? a : 0.5 * (a + s.vertices[static_cast<std::size_t>(t[1])]);
    const double step = std::pow(10.0, scale(rng));
    for (double sign : {1.0, -1.0}) {
      // Along the vertex's own normal, bent a little: its side is clear.
      const Vec3 dir = (target.normalized() + 0.3 * random_direction(rng)).normalized();
      const Vec3 p = target + sign * step * dir;
      NearestHit hit;
      ASSERT_TRUE(bvh.nearest(s, p, HUGE_VAL, hit));
      EXPECT_EQ((p - hit.point).dot(pseudo_normal(s, hit)) > 0, sign > 0) << p.transpose();
    }
  }
}

// Segments from inside a closed mesh to outside, aimed exactly at its shared
// edges and vertices: a watertight test finds a crossing for every one (a
// test with a gap along edges lets some through), and the tree agrees with
// brute force.
void expect_watertight(const TriangleSurface& s, const std::vector<Vec3>& targets, unsigned seed,
                       double inner) {
  TriangleBvh bvh;
  bvh.build(s);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-inner, inner), far(1.5, 4);
  int shot = 0;
  for (const Vec3& target : targets)
    for (int k = 0; k < 40; ++k) {
      const Vec3 in(u(rng), u(rng), u(rng));
      const Vec3 out = in + far(rng) * (target - in);
      for (int way = 0; way < 2; ++way) {
        const Vec3 a = way ? out : in, b = way ? in : out;
        SegmentHit hit, brute;
        ASSERT_TRUE(bvh.first_hit(s, a, b, hit)) << a.transpose() << " -> " << b.transpose();
        ASSERT_TRUE(first_hit_brute_force(s, a, b, brute));
        expect_same(hit, brute, a);
        EXPECT_LT((hit.point - target).norm(), 1e-12);
        ++shot;
      }
    }
  EXPECT_GE(shot, 2000);
}

TEST(TriangleBvh, SegmentsThroughSharedEdgesAndVerticesAlwaysHit) {
  const TriangleSurface cube = cube_surface();
  std::vector<Vec3> targets;
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(0, 1);
  for (const TriangleSurface::Edge& e : cube.edges)
    for (int k = 0; k < 3; ++k) {
      const double f = k == 0 ? 0 : k == 1 ? 0.5 : u(rng);
      targets.push_back((1 - f) * cube.vertices[static_cast<std::size_t>(e.a)] +
                        f * cube.vertices[static_cast<std::size_t>(e.b)]);
    }
  expect_watertight(cube, targets, 10, 0.9);

  const TriangleSurface sphere = icosphere(2);
  targets.clear();
  for (const Vec3& v : sphere.vertices)
    targets.push_back(v);
  for (const TriangleSurface::Edge& e : sphere.edges)
    targets.push_back(0.5 * (sphere.vertices[static_cast<std::size_t>(e.a)] +
                             sphere.vertices[static_cast<std::size_t>(e.b)]));
  expect_watertight(sphere, targets, 11, 0.5);
}

// Box queries, exact (given the surface) and leaf by leaf (without it),
// against every box tried in turn.
std::vector<int> sorted(std::vector<int> v) {
  std::sort(v.begin(), v.end());
  return v;
}

TEST(TriangleBvh, TrianglesOverlappingABox) {
  const TriangleSurface s = icosphere(4);
  TriangleBvh bvh;
  bvh.build(s);
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(-1.1, 1.1), size(0, 0.2);
  long exact_count = 0, leaf_count = 0;
  for (int q = 0; q < 300; ++q) {
    const Vec3 lo(u(rng), u(rng), u(rng)), hi = lo + Vec3::Constant(size(rng));
    std::vector<int> want, exact, leaves;
    for (std::int32_t t = 0; t < static_cast<std::int32_t>(s.triangles.size()); ++t)
      if (triangle_box(s, t).overlaps(lo, hi)) want.push_back(t);
    bvh.for_each_overlapping(s, lo, hi, [&](std::int32_t t) { exact.push_back(t); });
    bvh.for_each_overlapping(lo, hi, [&](std::int32_t t) { leaves.push_back(t); });
    EXPECT_EQ(sorted(exact), want);
    leaves = sorted(leaves);
    EXPECT_TRUE(std::includes(leaves.begin(), leaves.end(), want.begin(), want.end()));
    exact_count += static_cast<long>(want.size());
    leaf_count += static_cast<long>(leaves.size());
  }
  // Measured 887 exact answers; leaf by leaf 1427.
  EXPECT_GT(exact_count, 800);
  EXPECT_LT(leaf_count, 2 * exact_count);
}

TEST(TriangleBvh, SharpEdgesOverlappingABox) {
  TriangleSurface s = cube_surface();
  TriangleBvh bvh;
  bvh.build(s);
  auto expect_answers = [&](const Vec3& lo, const Vec3& hi) {
    std::vector<int> want, exact, leaves;
    for (std::size_t i = 0; i < s.sharp_edges.size(); ++i)
      if (segment_box(s.vertices[static_cast<std::size_t>(s.sharp_edges[i].a)],
                      s.vertices[static_cast<std::size_t>(s.sharp_edges[i].b)])
              .overlaps(lo, hi))
        want.push_back(static_cast<int>(i));
    bvh.for_each_sharp_edge_overlapping(s, lo, hi, [&](std::int32_t i) { exact.push_back(i); });
    bvh.for_each_sharp_edge_overlapping(lo, hi, [&](std::int32_t i) { leaves.push_back(i); });
    EXPECT_EQ(sorted(exact), want);
    leaves = sorted(leaves);
    EXPECT_TRUE(std::includes(leaves.begin(), leaves.end(), want.begin(), want.end()));
    return want.size();
  };
  // A cloth edge's box near the corner (1, 1, 1), grown by a reach.
  EXPECT_EQ(expect_answers(Vec3(0.9, 0.9, 0.9), Vec3(1.1, 1.1, 1.1)), 3u);
  EXPECT_EQ(expect_answers(Vec3(3, 3, 3), Vec3(4, 4, 4)), 0u);
  // Two opposite top corners raised: the top's diagonal becomes a ridge
  // (bent 38.9 degrees): a sharp edge more, so refit rebuilds that tree.
  s.vertices[5].z() = 1.5;
  s.vertices[6].z() = 1.5;
  finish_moved_surface(s);
  EXPECT_EQ(s.sharp_edges.size(), 13u);
  bvh.refit(s);
  EXPECT_EQ(expect_answers(Vec3(-0.1, -0.1, 1.4), Vec3(0.1, 0.1, 1.6)), 1u);  // the ridge
  // Corner 5: its side, two top edges and the ridge.
  EXPECT_EQ(expect_answers(Vec3(0.9, -1.1, 0.9), Vec3(1.1, -0.9, 1.6)), 4u);
  TriangleBvh fresh;
  fresh.build(s);
  EXPECT_EQ(fresh.sharp_edge_tree().size(), bvh.sharp_edge_tree().size());
  EXPECT_EQ(fresh.sharp_edge_tree().bounds().hi, bvh.sharp_edge_tree().bounds().hi);
  // Lowered a little (still bent 35 degrees): the same sharp edges as the
  // tree holds, refitted in place.
  s.vertices[5].z() = 1.45;
  s.vertices[6].z() = 1.45;
  finish_moved_surface(s);
  ASSERT_EQ(s.sharp_edges.size(), 13u);
  const BoxTree::Node* nodes = bvh.sharp_edge_tree().nodes().data();
  bvh.refit(s);
  EXPECT_EQ(bvh.sharp_edge_tree().nodes().data(), nodes);
  EXPECT_EQ(bvh.sharp_edge_tree().bounds().hi.z(),
            segment_box(s.vertices[5], s.vertices[6]).hi.z());
}

TEST(TriangleBvh, IdenticalTrianglesBuildShallowAndAnswerTheFirst) {
  TriangleSurface s;
  s.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  s.triangles.assign(10000, {0, 1, 2});
  finish_surface(s);
  TriangleBvh bvh;
  bvh.build(s);
  // Halving 10,000 down to leaves of 4: 12 levels.
  EXPECT_LE(bvh.triangle_tree().depth(), 12);
  NearestHit hit;
  ASSERT_TRUE(bvh.nearest(s, Vec3(0.2, 0.2, 0.1), HUGE_VAL, hit));
  EXPECT_EQ(hit.triangle, 0);
  SegmentHit seg;
  ASSERT_TRUE(bvh.first_hit(s, Vec3(0.2, 0.2, 1), Vec3(0.2, 0.2, -1), seg));
  EXPECT_EQ(seg.triangle, 0);
  int reported = 0;
  bvh.for_each_overlapping(Vec3(0, 0, 0), Vec3(0.1, 0.1, 0.1), [&](std::int32_t) { ++reported; });
  EXPECT_EQ(reported, 10000);
}

}  // namespace
}  // namespace neurocloth

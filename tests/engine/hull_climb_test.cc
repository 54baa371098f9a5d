#include "hull_climb.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "engine/test_meshes.h"

namespace idbench::internal {
namespace {

// The support value by brute force: the greatest d·p over every point given.
double ScanValue(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& d) {
  double best = -std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& p : points) best = std::max(best, d.dot(p));
  return best;
}

// The climb against the scan on random directions, from a cold start and
// from the last support vertex of a direction that turns a little each call
// (as GJK asks): the same support value to 1e-12 m, and the vertex returned
// is one of the points given, bit for bit.
void ExpectClimbEqualsScan(const std::vector<Eigen::Vector3d>& points, unsigned seed) {
  const HullClimb climb(points);
  ASSERT_TRUE(climb.usable());
  for (int v = 0; v < climb.n_vertices(); ++v) {
    ASSERT_NE(std::find(points.begin(), points.end(), climb.vertex(v)), points.end()) << "vertex " << v;
  }
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  Eigen::Vector3d d_slow(1, 0, 0);
  int warm = -1;
  for (int trial = 0; trial < 5000; ++trial) {
    const Eigen::Vector3d d(normal(rng), normal(rng), normal(rng));
    int cold = -1;
    EXPECT_NEAR(d.dot(climb.vertex(climb.Support(d, &cold))), ScanValue(points, d), 1e-12) << "trial " << trial;
    d_slow = (d_slow + 0.05 * d).normalized();
    EXPECT_NEAR(d_slow.dot(climb.vertex(climb.Support(d_slow, &warm))), ScanValue(points, d_slow), 1e-12)
        << "trial " << trial;
    // A random warm start (any vertex) climbs to the same value.
    int any = static_cast<int>(rng() % static_cast<unsigned>(climb.n_vertices()));
    EXPECT_NEAR(d.dot(climb.vertex(climb.Support(d, &any))), ScanValue(points, d), 1e-12) << "trial " << trial;
  }
}

TEST(HullClimbTest, RandomCloudMatchesTheScan) {
  std::mt19937 rng(3);
  std::normal_distribution<double> normal(0.0, 0.1);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 2000; ++i) points.emplace_back(normal(rng), 2.0 * normal(rng), 0.5 * normal(rng));
  ExpectClimbEqualsScan(points, 11);
}

// Every point on the sphere: all 642 are hull vertices.
TEST(HullClimbTest, IcosphereMatchesTheScan) {
  ExpectClimbEqualsScan(testing::IcosphereMesh(0.07, 3).vertices, 12);
}

// A box sampled on its faces (a 9 × 9 grid each, coplanar and collinear
// points; directions along the axes tie whole faces): the value is still the scan's.
TEST(HullClimbTest, BoxWithPointsOnItsFacesMatchesTheScan) {
  std::vector<Eigen::Vector3d> points;
  const Eigen::Vector3d half(0.2, 0.05, 0.1);
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = -1; side <= 1; side += 2) {
      for (int i = 0; i <= 8; ++i) {
        for (int j = 0; j <= 8; ++j) {
          Eigen::Vector3d p;
          p[axis] = side * half[axis];
          p[(axis + 1) % 3] = (i / 4.0 - 1.0) * half[(axis + 1) % 3];
          p[(axis + 2) % 3] = (j / 4.0 - 1.0) * half[(axis + 2) % 3];
          points.push_back(p);
        }
      }
    }
  }
  ExpectClimbEqualsScan(points, 13);
  // Along the axes and the face diagonals the support value is the box's.
  const HullClimb climb(points);
  for (int axis = 0; axis < 3; ++axis) {
    int from = -1;
    const Eigen::Vector3d d = Eigen::Vector3d::Unit(axis);
    EXPECT_DOUBLE_EQ(d.dot(climb.vertex(climb.Support(d, &from))), half[axis]);
    EXPECT_DOUBLE_EQ((-d).dot(climb.vertex(climb.Support(-d, &from))), half[axis]);
  }
}

// A thin flat mesh (a disk of 200 points with a point above its centre):
// long sliver faces, the climb still exact.
TEST(HullClimbTest, NearlyFlatHullMatchesTheScan) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 200; ++i) {
    const double a = 2.0 * 3.141592653589793 * i / 200.0;
    points.emplace_back(0.3 * std::cos(a), 0.3 * std::sin(a), 1e-4 * std::sin(7 * a));
  }
  points.emplace_back(0.0, 0.0, 1e-3);
  ExpectClimbEqualsScan(points, 14);
}

// Fewer than 4 points: nothing to climb, callers scan.
TEST(HullClimbTest, FewerThanFourPointsAreNotClimbed) {
  EXPECT_FALSE(HullClimb({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}).usable());
}

}  // namespace
}  // namespace idbench::internal

// The GJK cross-check of the disk-shape solvers against FCL itself (facts.md,
// section 3): a thin fcl::Cylinder(r, h) centred on the disk contains it, and
// every point of the cylinder is within h/2 of the disk, so for the true
// distances d_cyl <= d_disk <= d_cyl + h/2. FCL's GJK answers d_cyl up to its own
// convergence error, so diskShapeDistance() must land in
// [d_gjk - kGjkError, d_gjk + h/2 + kGjkError] on every separated pair, for both of
// FCL's GJK solvers, in double, for every shape GJK supports (Sphere, Box,
// Capsule, Cylinder, Cone, Ellipsoid, Convex).
#include <fcl_disk/disk_shape_distance.h>

#include <fcl/narrowphase/detail/gjk_solver_indep.h>
#include <fcl/narrowphase/detail/gjk_solver_libccd.h>

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "test_random.h"

namespace {

using Transform3d = fcl::Transform3<double>;
using Vector3d = Eigen::Vector3d;

/// Height of the thin cylinder around the disk, relative to the disk radius:
/// thin enough that the bracket h/2 is far below any error that would matter,
/// thick enough that GJK's support function sees a solid.
constexpr double kThinRelative = 1e-6;
/// GJK's convergence error, relative to the scene size: FCL's solvers stop at
/// their tolerance (1e-6 by default), and facts.md section 5 measured errors up
/// to 5.8e-5 of the scene for libccd and 6.8e-7 for indep on these shapes; the
/// solvers are run with a tolerance of 1e-10 here, and 1e-6 of the scene is
/// several times the largest difference observed in this test.
constexpr double kGjkErrorRelative = 1e-6;
/// Pairs closer than this (relative) are skipped: GJK's distance on touching or
/// overlapping shapes is not a distance.
constexpr double kSeparatedRelative = 1e-3;
constexpr int kPairsPerShape = 2000;

Transform3d randomPose(fcl_disk_test::Random& random, double spread) {
  Transform3d X = Transform3d::Identity();
  X.linear() = random.rotation();
  X.translation() = random.inBall(spread);
  return X;
}

std::shared_ptr<fcl::Convex<double>> boxLikeConvex() {
  auto vertices = std::make_shared<std::vector<Vector3d>>(std::vector<Vector3d>{
      {-0.4, -0.25, -0.15}, {0.4, -0.25, -0.15}, {0.4, 0.25, -0.15}, {-0.4, 0.25, -0.15},
      {-0.3, -0.2, 0.15},   {0.3, -0.2, 0.15},   {0.3, 0.2, 0.15},   {-0.3, 0.2, 0.15}});
  auto faces = std::make_shared<std::vector<int>>(std::vector<int>{
      4, 0, 3, 2, 1, 4, 4, 5, 6, 7, 4, 0, 1, 5, 4, 4, 1, 2, 6, 5, 4, 2, 3, 7, 6, 4, 3, 0, 4, 7});
  return std::make_shared<fcl::Convex<double>>(vertices, 6, faces);
}

template <typename Shape>
void crossCheck(const std::string& name, const Shape& shape, double bounding_radius) {
  fcl_disk_test::Random random(std::hash<std::string>()(name) % 100000 + 17);
  fcl::detail::GJKSolver_libccd<double> libccd;
  libccd.distance_tolerance = 1e-10;
  fcl::detail::GJKSolver_indep<double> indep;
  indep.gjk_tolerance = 1e-10;
  int checked = 0;
  double worst_below = 0, worst_above = 0;
  for (int i = 0; i < kPairsPerShape; ++i) {
    const double r = random.uniform(0.1, 1.0);
    const Transform3d X_WD = randomPose(random, 1.0), X_WS = randomPose(random, 1.0);
    const auto answer = fcl_disk::diskShapeDistance(r, X_WD, shape, X_WS);
    const double scale = r + bounding_radius + (X_WD.translation() - X_WS.translation()).norm();
    if (answer.distance < kSeparatedRelative * scale) continue;
    const double h = kThinRelative * r;
    const fcl::Cylinder<double> thin(r, h);
    for (int solver = 0; solver < 2; ++solver) {
      double d_gjk = -1;
      Vector3d p1, p2;
      const bool ok = solver == 0 ? libccd.shapeDistance(thin, X_WD, shape, X_WS, &d_gjk, &p1, &p2)
                                  : indep.shapeDistance(thin, X_WD, shape, X_WS, &d_gjk, &p1, &p2);
      ASSERT_TRUE(ok);
      const double tolerance = kGjkErrorRelative * scale;
      std::ostringstream pose;
      pose.precision(17);
      pose << name << (solver == 0 ? " libccd" : " indep") << " pair " << i << ": r " << r
           << "\nX_WD\n" << X_WD.matrix() << "\nX_WS\n" << X_WS.matrix() << "\nd " << answer.distance
           << " gjk " << d_gjk;
      EXPECT_GE(answer.distance, d_gjk - tolerance) << pose.str();
      EXPECT_LE(answer.distance, d_gjk + 0.5 * h + tolerance) << pose.str();
      worst_below = std::max(worst_below, (d_gjk - answer.distance) / scale);
      worst_above = std::max(worst_above, (answer.distance - d_gjk - 0.5 * h) / scale);
    }
    ++checked;
  }
  EXPECT_GT(checked, kPairsPerShape / 4) << name << ": too few separated pairs";
  std::cout << name << ": " << checked << " separated pairs; GJK above the exact distance by "
            << worst_below << ", below the bracket by " << worst_above << " (relative)\n";
}

TEST(DiskShapeGjk, Sphere) { crossCheck("sphere", fcl::Sphere<double>(0.4), 0.4); }
TEST(DiskShapeGjk, Box) {
  crossCheck("box", fcl::Box<double>(0.8, 0.5, 0.3), 0.5 * std::sqrt(0.64 + 0.25 + 0.09));
}
TEST(DiskShapeGjk, Capsule) { crossCheck("capsule", fcl::Capsule<double>(0.2, 0.8), 0.6); }
TEST(DiskShapeGjk, Cylinder) {
  crossCheck("cylinder", fcl::Cylinder<double>(0.3, 0.8), std::hypot(0.3, 0.4));
}
TEST(DiskShapeGjk, Cone) { crossCheck("cone", fcl::Cone<double>(0.3, 0.8), std::hypot(0.3, 0.4)); }
TEST(DiskShapeGjk, Ellipsoid) {
  crossCheck("ellipsoid", fcl::Ellipsoid<double>(0.5, 0.3, 0.2), 0.5);
}
TEST(DiskShapeGjk, Convex) {
  crossCheck("convex", *boxLikeConvex(), std::sqrt(0.16 + 0.0625 + 0.0225));
}

}  // namespace

// The hook: what FCL's public entry points answer for disks and for everything
// else, the broadphase, method selection, conventions, and concurrency.
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/broadphase/default_broadphase_callbacks.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/plane.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/geometry/shape/triangle_p.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>
#include <fcl_disk/fcl_disk.h>
#include <gtest/gtest.h>

#include <dlfcn.h>

#include <atomic>
#include <cstring>
#include <random>
#include <set>
#include <thread>
#include <vector>

#include "disk_families.h"
#include "test_random.h"

namespace {

using fcl::Transform3d;
using Vec3 = Eigen::Vector3d;

Transform3d pose(const Vec3& centre, const Vec3& normal) {
  Transform3d X = Transform3d::Identity();
  X.translation() = centre;
  X.linear() =
      Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), normal.normalized()).toRotationMatrix();
  return X;
}

Transform3d randomPose(std::mt19937_64& rng, double spread) {
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Transform3d X = Transform3d::Identity();
  X.translation() = spread * Vec3(uniform(rng), uniform(rng), uniform(rng));
  X.linear() = Eigen::Quaterniond(uniform(rng), uniform(rng), uniform(rng), uniform(rng))
                   .normalized()
                   .toRotationMatrix();
  return X;
}

double fclDistance(const fcl::CollisionObjectd& a, const fcl::CollisionObjectd& b,
                   fcl::GJKSolverType solver, fcl::DistanceResultd* out = nullptr) {
  fcl::DistanceRequestd request;
  request.gjk_solver_type = solver;
  fcl::DistanceResultd result;
  const double d = fcl::distance(&a, &b, request, result);
  if (out) *out = result;
  return d;
}

// Real cylinders against other shapes get exactly what FCL's own narrow-phase
// solver computes (the entry FCL would have called); a Disk against another
// shape gets fcl_disk's diskShapeDistance(), in both argument orders.
TEST(Hook, RealCylindersKeepFclsAnswersDisksGetFcl_disks) {
  fcl_disk::registerDiskFunctions();
  auto cylinder = std::make_shared<fcl::Cylinderd>(0.5, 1.0);
  auto disk = std::make_shared<fcl_disk::Diskd>(0.7);
  auto box = std::make_shared<fcl::Boxd>(0.3, 0.6, 0.2);
  auto sphere = std::make_shared<fcl::Sphered>(0.4);
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    const Transform3d X1 = randomPose(rng, 2.0), X2 = randomPose(rng, 2.0);
    {
      SCOPED_TRACE("cylinder-cylinder and cylinder-box: FCL's");
      fcl::detail::GJKSolver_libccd<double> solver;
      double expected_cylinder = 0, expected_box = 0;
      Vec3 p1, p2;
      solver.shapeDistance(*cylinder, X1, *cylinder, X2, &expected_cylinder, &p1, &p2);
      solver.shapeDistance(*cylinder, X1, *box, X2, &expected_box, &p1, &p2);
      fcl::CollisionObjectd a(cylinder, X1), b(cylinder, X2), c(box, X2);
      EXPECT_EQ(fclDistance(a, b, fcl::GST_LIBCCD), expected_cylinder);
      EXPECT_EQ(fclDistance(a, c, fcl::GST_LIBCCD), expected_box);
    }
    const auto disk_box = fcl_disk::diskShapeDistance(0.7, X1, *box, X2);
    const auto disk_sphere = fcl_disk::diskShapeDistance(0.7, X1, *sphere, X2);
    const auto disk_cylinder = fcl_disk::diskShapeDistance(0.7, X1, *cylinder, X2);
    const struct {
      const char* name;
      std::shared_ptr<fcl::CollisionGeometryd> other;
      fcl_disk::DiskShapeDistanceResult<double> expected;
    } pairs[] = {{"disk-box", box, disk_box},
                 {"disk-sphere", sphere, disk_sphere},
                 {"disk-cylinder", cylinder, disk_cylinder}};
    for (const auto& pair : pairs) {
      SCOPED_TRACE(pair.name);
      fcl::CollisionObjectd d(disk, X1), o(pair.other, X2);
      for (auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
        fcl::DistanceResultd disk_first, disk_second;
        EXPECT_EQ(fclDistance(d, o, solver, &disk_first), pair.expected.distance);
        EXPECT_EQ(disk_first.nearest_points[0], pair.expected.p_W_disk);
        EXPECT_EQ(disk_first.nearest_points[1], pair.expected.p_W_shape);
        EXPECT_EQ(fclDistance(o, d, solver, &disk_second), pair.expected.distance);
        EXPECT_EQ(disk_second.nearest_points[0], pair.expected.p_W_shape);
        EXPECT_EQ(disk_second.nearest_points[1], pair.expected.p_W_disk);
      }
    }
  }
}

TEST(Hook, DiskPairsAreAnsweredBySelectedMethodAndRestored) {
  auto d1 = std::make_shared<fcl_disk::Diskd>(1.0);
  auto d2 = std::make_shared<fcl_disk::Diskd>(1.0);
  // facts.md counterexample A, where the methods disagree by 0.35.
  const Transform3d X1 = pose(Vec3::Zero(), Vec3::UnitZ());
  const Transform3d X2 = pose(Vec3(0, 0, -0.5), Vec3(0, 1, 2));
  fcl::CollisionObjectd a(d1, X1), b(d2, X2);
  const double exact = fcl_disk::exactDiskDistance(1.0, X1, 1.0, X2).distance;
  const double report = fcl_disk::almohamadSelimDiskDistance(1.0, X1, 1.0, X2).distance;
  ASSERT_GT(report - exact, 0.3);

  EXPECT_EQ(fcl_disk::registeredDiskDistanceMethod(), fcl_disk::DiskDistanceMethod::exact);
  for (auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) EXPECT_EQ(fclDistance(a, b, solver), exact);
  fcl_disk::registerDiskFunctions(fcl_disk::DiskDistanceMethod::almohamad_selim);
  fcl_disk::registerDiskFunctions(fcl_disk::DiskDistanceMethod::almohamad_selim);  // idempotent
  for (auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) EXPECT_EQ(fclDistance(a, b, solver), report);
  fcl_disk::registerDiskFunctions();
  EXPECT_EQ(fcl_disk::registeredDiskDistanceMethod(), fcl_disk::DiskDistanceMethod::exact);
  EXPECT_EQ(fclDistance(a, b, fcl::GST_LIBCCD), exact);
}

// Overlap: distance 0 with a common point as both nearest points, for unsigned
// and signed requests and both solvers (the indep signed path would otherwise
// call collide() and assert on a penetration depth).
TEST(Hook, OverlapGivesZeroUnsignedAndMinusTheDepthSigned) {
  auto d1 = std::make_shared<fcl_disk::Diskd>(1.0);
  auto d2 = std::make_shared<fcl_disk::Diskd>(1.0);
  // Disk 2 stands in the plane x = 0.5 through disk 1: the shortest way out is
  // +x by 0.5, until it touches disk 1's rim at (1, 0, 0).
  fcl::CollisionObjectd a(d1, pose(Vec3::Zero(), Vec3::UnitZ()));
  fcl::CollisionObjectd b(d2, pose(Vec3(0.5, 0, 0), Vec3::UnitX()));
  for (bool is_signed : {false, true}) {
    for (auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
      fcl::DistanceRequestd request(true);
      request.enable_signed_distance = is_signed;
      request.gjk_solver_type = solver;
      fcl::DistanceResultd result;
      const double expected = is_signed ? -0.5 : 0.0;
      EXPECT_NEAR(fcl::distance(&a, &b, request, result), expected, 1e-15);
      EXPECT_NEAR(result.min_distance, expected, 1e-15);
      if (is_signed && solver == fcl::GST_LIBCCD) {
        // The deepest points, as FCL's EPA reports them: p1 - p2 = PD * (+x).
        EXPECT_NEAR((result.nearest_points[0] - Vec3(1, 0, 0)).norm(), 0.0, 1e-15);
        EXPECT_NEAR((result.nearest_points[1] - Vec3(0.5, 0, 0)).norm(), 0.0, 1e-15);
        continue;
      }
      // Unsigned, and signed with the indep solver (FCL's entry then reports the
      // contact point of collide() as both points): a point on both disks.
      EXPECT_EQ(result.nearest_points[0], result.nearest_points[1]);
      EXPECT_NEAR(result.nearest_points[0].z(), 0.0, 1e-15);
      EXPECT_NEAR(result.nearest_points[0].x(), 0.5, 1e-15);
    }
  }
}

/// A penetration depth not above the smallest normal S (a disk tilted by a few
/// times numeric_limits<S>::min() through another, or whose rotation's defect
/// is min()) is reported as touching: FCL's entry, for the indep
/// solver, answers a negative signed distance by asking collide() for a contact
/// deeper than numeric_limits::min() and asserts one exists (Debian's libfcl
/// keeps its asserts: the process would abort). Corpus
/// regression-signed-subnormal-depth-indep of fuzz_hook.
template <typename S>
void checkSubnormalPenetration() {
  using X = fcl::Transform3<S>;
  auto d1 = std::make_shared<fcl_disk::Disk<S>>(S(1));
  auto d2 = std::make_shared<fcl_disk::Disk<S>>(S(0.125));
  X X2 = X::Identity();
  // Tilted by 2 min() about y: the depth is 0.125 sin(tilt), below min().
  X2.linear()(2, 0) = 2 * std::numeric_limits<S>::min();
  X2.linear()(0, 2) = -2 * std::numeric_limits<S>::min();
  const S depth = -fcl_disk::diskPenetration(S(1), X::Identity(), S(0.125), X2).signed_distance;
  ASSERT_LT(depth, std::numeric_limits<S>::min());
  // In float the depth comes out subnormal and non-zero (computed in double,
  // rounded to float); in double its square underflows in |P w| and it is 0.
  if (std::is_same<S, float>::value) {
    ASSERT_GT(depth, S(0));
  }
  fcl::CollisionObject<S> a(d1, X::Identity()), b(d2, X2);
  for (auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
    fcl::DistanceRequest<S> request(true);
    request.enable_signed_distance = true;
    request.gjk_solver_type = solver;
    fcl::DistanceResult<S> result;
    EXPECT_EQ(fcl::distance(&a, &b, request, result), S(0));
    EXPECT_EQ(result.min_distance, S(0));
  }
}

TEST(Hook, SubnormalPenetrationIsTouchingForEverySolver) {
  checkSubnormalPenetration<double>();
  checkSubnormalPenetration<float>();
  // A depth of exactly FLT_MIN (corpus regression-signed-min-depth-indep): a
  // disk whose rotation is off orthonormal by FLT_MIN, concentric with a
  // smaller disk in its plane.
  using X = fcl::Transform3f;
  X X1 = X::Identity(), X2 = X::Identity();
  X1.linear() << 0, 0, 1, 1, 0, 0, 0, 1, 0;
  X2.linear() << 0, 0, 1, 1, 0, 0, 0, 1, std::numeric_limits<float>::min();
  X1.translation().setConstant(-431.68359375f);
  X2.translation().setConstant(-431.68359375f);
  fcl::CollisionObjectf a(std::make_shared<fcl_disk::Diskf>(1.0f), X1),
      b(std::make_shared<fcl_disk::Diskf>(431.68359375f), X2);
  ASSERT_EQ(-fcl_disk::diskPenetration(1.0f, X1, 431.68359375f, X2).signed_distance,
            std::numeric_limits<float>::min());
  for (auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
    fcl::DistanceRequestf request(true);
    request.enable_signed_distance = true;
    request.gjk_solver_type = solver;
    fcl::DistanceResultf result;
    EXPECT_EQ(fcl::distance(&a, &b, request, result), 0.0f);
  }
}

TEST(Hook, CollideReportsOneContactOnBothDisks) {
  auto d1 = std::make_shared<fcl_disk::Diskd>(1.0);
  auto d2 = std::make_shared<fcl_disk::Diskd>(0.8);
  const Transform3d X1 = pose(Vec3::Zero(), Vec3::UnitZ());
  const Transform3d X2 = pose(Vec3(0.2, 0.1, 0.3), Vec3(1, 0, 0.2));
  fcl::CollisionObjectd a(d1, X1), b(d2, X2);
  fcl_disk::DiskContact<double> expected;
  ASSERT_TRUE(fcl_disk::intersectDisks(1.0, X1, 0.8, X2, &expected));
  for (auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
    fcl::CollisionRequestd request(1, true);
    request.gjk_solver_type = solver;
    fcl::CollisionResultd result;
    EXPECT_EQ(fcl::collide(&a, &b, request, result), 1u);
    ASSERT_TRUE(result.isCollision());
    const auto& contact = result.getContact(0);
    EXPECT_EQ(contact.pos, expected.pos);
    EXPECT_EQ(contact.normal, expected.normal);
    EXPECT_EQ(contact.penetration_depth, expected.penetration_depth);
    EXPECT_EQ(contact.o1, d1.get());
    EXPECT_EQ(contact.o2, d2.get());
  }
  // Apart: no contact.
  fcl::CollisionObjectd far(d2, pose(Vec3(0, 0, 3), Vec3::UnitZ()));
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  EXPECT_EQ(fcl::collide(&a, &far, request, result), 0u);
}

// The float path uses the tables compiled into user code: it must reach us too.
TEST(Hook, FloatQueriesUseTheDiskSolver) {
  auto d1 = std::make_shared<fcl_disk::Diskf>(1.0f);
  auto d2 = std::make_shared<fcl_disk::Diskf>(1.0f);
  const fcl::Transform3f X1 = pose(Vec3::Zero(), Vec3::UnitZ()).cast<float>();
  const fcl::Transform3f X2 = pose(Vec3(0, 0, -0.5), Vec3(0, 1, 2)).cast<float>();
  fcl::CollisionObjectf a(d1, X1), b(d2, X2);
  for (auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
    fcl::DistanceRequestf request;
    request.gjk_solver_type = solver;
    fcl::DistanceResultf result;
    EXPECT_EQ(fcl::distance(&a, &b, request, result),
              fcl_disk::exactDiskDistance(1.0f, X1, 1.0f, X2).distance);
  }
}

// One DistanceResult carried through several queries (as FCL's broadphase
// callbacks do): a disk pair follows the same conventions as FCL's own shape
// pairs, checked side by side on spheres. The result keeps the nearest pair
// seen, fcl::distance returns the result's minimum, and a result already at
// distance 0 is left alone.
TEST(Hook, ResultConventionsMatchFcls) {
  fcl_disk::registerDiskFunctions();
  const auto check = [](std::shared_ptr<fcl::CollisionGeometryd> shape, const char* name) {
    SCOPED_TRACE(name);
    const Transform3d at_origin = Transform3d::Identity();
    // Apart along the common normal (disks face to face): gaps 0.5 and 3 less
    // the spheres' diameters, and a copy in the same place.
    const Transform3d near = pose(Vec3(0.0, 0.0, 0.5), Vec3::UnitZ());
    const Transform3d far = pose(Vec3(0.0, 0.0, 3.0), Vec3::UnitZ());
    const Transform3d touching = at_origin;
    const fcl::CollisionObjectd base(shape, at_origin), near_object(shape, near),
        far_object(shape, far), touching_object(shape, touching);
    const fcl::DistanceRequestd request;
    fcl::DistanceResultd result;
    const double d_far = fcl::distance(&base, &far_object, request, result);
    EXPECT_GT(d_far, 0.0);
    EXPECT_EQ(result.min_distance, d_far);
    const double d_near = fcl::distance(&base, &near_object, request, result);
    ASSERT_LT(d_near, d_far);
    EXPECT_EQ(result.min_distance, d_near);
    const fcl::DistanceResultd after_near = result;
    // A farther pair leaves the result as it was and returns its minimum.
    EXPECT_EQ(fcl::distance(&base, &far_object, request, result), d_near);
    EXPECT_EQ(result.min_distance, d_near);
    EXPECT_EQ(result.o1, after_near.o1);
    EXPECT_EQ(result.o2, after_near.o2);
    EXPECT_EQ(result.nearest_points[0], after_near.nearest_points[0]);
    EXPECT_EQ(result.nearest_points[1], after_near.nearest_points[1]);
    // A result at distance 0 is settled: later pairs do not touch it.
    fcl::DistanceResultd settled;
    EXPECT_LE(fcl::distance(&base, &touching_object, request, settled), 0.0);
    const fcl::DistanceResultd after_touching = settled;
    EXPECT_EQ(fcl::distance(&base, &near_object, request, settled), after_touching.min_distance);
    EXPECT_EQ(settled.min_distance, after_touching.min_distance);
    EXPECT_EQ(settled.nearest_points[0], after_touching.nearest_points[0]);
  };
  check(std::make_shared<fcl::Sphered>(0.1), "FCL's sphere-sphere");
  check(std::make_shared<fcl_disk::Diskd>(1.0), "fcl_disk's disk-disk");
}

// One result held over many disk pairs (as FCL's default distance callback
// holds it over a manager's candidates) ends exactly as the nearest of their
// fresh answers, FCL's strict "nearer" deciding ties: the pairs the hook proves
// no nearer than the result's distance without solving them
// (diskPairNoNearerThan) change nothing. Every other pair is the best one
// moved rigidly and then apart or together by 1e-15 to 1e-3 of its distance,
// inside and outside that proof's margin; an invalid pair still makes the
// result NaN.
TEST(Hook, AHeldResultEndsAsTheNearestFreshAnswer) {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> radius(0.1, 0.6), unit(0.0, 1.0);
  const fcl::DistanceRequestd request;
  for (int trial = 0; trial < 200; ++trial) {
    fcl::DistanceResultd held, best;
    best.min_distance = std::numeric_limits<double>::max();
    std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
    Transform3d best_a = randomPose(rng, 2.0), best_b = randomPose(rng, 2.0);
    double best_r1 = radius(rng), best_r2 = radius(rng);
    for (int k = 0; k < 12; ++k) {
      double r1 = radius(rng), r2 = radius(rng);
      Transform3d a = randomPose(rng, 2.0), b = randomPose(rng, 2.0);
      if (k % 2 == 1 && best.min_distance > 0 && best.min_distance < 1e300) {
        // The best pair, moved rigidly, then b along the line of centres by
        // a signed 10^-15..10^-3 of the best distance.
        const Transform3d motion = randomPose(rng, 3.0);
        r1 = best_r1, r2 = best_r2;
        a = motion * best_a, b = motion * best_b;
        const Vec3 line = (b.translation() - a.translation()).normalized();
        const double nudge = std::pow(10.0, -15.0 + 12.0 * unit(rng)) * best.min_distance;
        b.translation() += (unit(rng) < 0.5 ? -nudge : nudge) * line;
      }
      objects.push_back(std::make_unique<fcl::CollisionObjectd>(
          std::make_shared<fcl_disk::Diskd>(r1), a));
      objects.push_back(std::make_unique<fcl::CollisionObjectd>(
          std::make_shared<fcl_disk::Diskd>(r2), b));
      const fcl::CollisionObjectd& o1 = *objects[objects.size() - 2];
      const fcl::CollisionObjectd& o2 = *objects.back();
      fcl::DistanceResultd fresh;
      fcl::distance(&o1, &o2, request, fresh);
      fcl::distance(&o1, &o2, request, held);
      if (fresh.min_distance < best.min_distance) {
        best = fresh;
        best_a = a, best_b = b, best_r1 = r1, best_r2 = r2;
      }
      ASSERT_EQ(held.min_distance, best.min_distance) << "trial " << trial << " pair " << k;
      ASSERT_EQ(held.o1, best.o1);
      ASSERT_EQ(held.o2, best.o2);
      ASSERT_EQ(held.nearest_points[0], best.nearest_points[0]);
      ASSERT_EQ(held.nearest_points[1], best.nearest_points[1]);
    }
    if (trial % 20 == 0 && held.min_distance > 0) {
      Transform3d sheared = randomPose(rng, 2.0);
      sheared.linear()(0, 0) += 0.1;  // not a rotation: no disk pose
      const fcl::CollisionObjectd invalid(std::make_shared<fcl_disk::Diskd>(0.5), sheared);
      fcl::distance(objects[0].get(), &invalid, request, held);
      EXPECT_TRUE(std::isnan(held.min_distance));
    }
  }
}

// intersectDisks and the exact solver decide a pair the same way (the
// solver's `intersecting` feature is the same common-point test), also in the
// band around the touching tolerance where intersectDisks' centre-line early
// exit (4 tolerances, src/disk_intersection.cpp) begins: each family's
// separated pairs, disk 1's centre moved to the origin (so that the moves
// below are not lost to the coordinates' rounding), disk 2 moved along p_W2 -
// p_W1 to `multiple` tolerances (1e-13 * (r1 + r2 + |c2 - c1|)), through
// intersectDisks and fcl::collide's default request.
TEST(Hook, DiskPairsDecideTheTouchingBandAsTheSolver) {
  for (const auto family : fcl_disk_families::allFamilies()) {
    for (const auto& c : fcl_disk_families::makeFamily<double>(family, 300, 20240601)) {
      Transform3d X_W1 = c.X_W1, X_W2 = c.X_W2;
      X_W2.translation() -= X_W1.translation();
      X_W1.translation().setZero();
      const auto apart = fcl_disk::exactDiskDistance(c.r1, X_W1, c.r2, X_W2);
      if (!(apart.distance > 1e-9 * (c.r1 + c.r2))) continue;
      const Vec3 along = (apart.p_W2 - apart.p_W1) / apart.distance;
      const double scale_apart = c.r1 + c.r2 + X_W2.translation().norm();
      X_W2.translation() -= apart.distance * along;  // touching
      // The nearest points are good to 1e-14 of the scene they were found in:
      // not a tenth of a tolerance of the touching scene when that one is much
      // smaller (a pair 1e6 of its radii apart).
      if (scale_apart > 4.0 * (c.r1 + c.r2 + X_W2.translation().norm())) continue;
      const double scale = c.r1 + c.r2 + X_W2.translation().norm();
      const fcl::CollisionObjectd disk1(std::make_shared<fcl_disk::Diskd>(c.r1), X_W1);
      for (const double multiple : {0.0, 0.5, 1.5, 2.5, 4.5, 8.0, 40.0}) {
        Transform3d X_moved = X_W2;
        X_moved.translation() += multiple * 1e-13 * scale * along;
        const bool common = fcl_disk::exactDiskDistance(c.r1, X_W1, c.r2, X_moved).feature ==
                            fcl_disk::DiskPairFeature::intersecting;
        ASSERT_EQ(fcl_disk::intersectDisks(c.r1, X_W1, c.r2, X_moved), common)
            << c.name << " moved to " << multiple << " touching tolerances";
        const fcl::CollisionObjectd disk2(std::make_shared<fcl_disk::Diskd>(c.r2), X_moved);
        fcl::CollisionResultd decision;
        fcl::collide(&disk1, &disk2, fcl::CollisionRequestd(), decision);
        ASSERT_EQ(decision.isCollision(), common)
            << c.name << ", fcl::collide, moved to " << multiple << " touching tolerances";
        if (multiple > 2.5) {
          EXPECT_FALSE(common) << c.name << " moved to " << multiple;
        }
      }
    }
  }
}

// A scene of disks (and boxes): the broadphase finds the same nearest pair and
// the same colliding pairs as brute-force pairwise queries.
TEST(Hook, BroadphaseAgreesWithBruteForce) {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> radius(0.1, 0.6);
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
  for (int i = 0; i < 60; ++i) {
    std::shared_ptr<fcl::CollisionGeometryd> geometry;
    if (i % 10 == 9) geometry = std::make_shared<fcl::Boxd>(0.3, 0.2, 0.1);
    else geometry = std::make_shared<fcl_disk::Diskd>(radius(rng));
    objects.push_back(std::make_unique<fcl::CollisionObjectd>(geometry, randomPose(rng, 4.0)));
  }
  fcl::DynamicAABBTreeCollisionManagerd manager;
  for (auto& object : objects) manager.registerObject(object.get());
  manager.setup();

  double brute_min = std::numeric_limits<double>::max();
  std::set<std::pair<const void*, const void*>> brute_colliding;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    for (std::size_t j = i + 1; j < objects.size(); ++j) {
      brute_min = std::min(brute_min, fclDistance(*objects[i], *objects[j], fcl::GST_LIBCCD));
      fcl::CollisionRequestd request;
      fcl::CollisionResultd result;
      if (fcl::collide(objects[i].get(), objects[j].get(), request, result) > 0) {
        const void* g1 = objects[i]->collisionGeometry().get();
        const void* g2 = objects[j]->collisionGeometry().get();
        brute_colliding.insert({std::min(g1, g2), std::max(g1, g2)});
      }
    }
  }
  fcl::DefaultDistanceData<double> distance_data;
  manager.distance(&distance_data, fcl::DefaultDistanceFunction);
  EXPECT_EQ(distance_data.result.min_distance, std::max(brute_min, 0.0));

  fcl::DefaultCollisionData<double> collision_data;
  collision_data.request.num_max_contacts = 100000;
  manager.collide(&collision_data, fcl::DefaultCollisionFunction);
  std::set<std::pair<const void*, const void*>> broad_colliding;
  for (std::size_t k = 0; k < collision_data.result.numContacts(); ++k) {
    const auto& contact = collision_data.result.getContact(k);
    const void* g1 = contact.o1;
    const void* g2 = contact.o2;
    broad_colliding.insert({std::min(g1, g2), std::max(g1, g2)});
  }
  EXPECT_EQ(broad_colliding, brute_colliding);
  EXPECT_FALSE(brute_colliding.empty());  // the scene is dense enough to test something
}

// Registration racing with queries: every query still gets the serial answer.
TEST(Hook, ConcurrentQueriesMatchSerialAnswers) {
  std::mt19937_64 rng(99);
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
  for (int i = 0; i < 40; ++i) {
    objects.push_back(std::make_unique<fcl::CollisionObjectd>(
        std::make_shared<fcl_disk::Diskd>(0.5), randomPose(rng, 2.0)));
  }
  std::vector<double> serial;
  for (std::size_t i = 0; i + 1 < objects.size(); ++i)
    serial.push_back(fclDistance(*objects[i], *objects[i + 1], fcl::GST_LIBCCD));

  std::atomic<int> mismatches{0};
  std::atomic<bool> stop{false};
  std::thread registrar([&] {
    while (!stop) fcl_disk::registerDiskFunctions(fcl_disk::DiskDistanceMethod::exact);
  });
  std::vector<std::thread> workers;
  for (int t = 0; t < 4; ++t) {
    workers.emplace_back([&, t] {
      for (int round = 0; round < 50; ++round) {
        for (std::size_t i = 0; i + 1 < objects.size(); ++i) {
          const auto solver = (t % 2) ? fcl::GST_INDEP : fcl::GST_LIBCCD;
          if (fclDistance(*objects[i], *objects[i + 1], solver) != serial[i]) ++mismatches;
        }
      }
    });
  }
  for (auto& worker : workers) worker.join();
  stop = true;
  registrar.join();
  EXPECT_EQ(mismatches.load(), 0);
}

// ---------------------------------------------------------------------------
// FCL's object-level entry points, fcl::distance / fcl::collide on two
// CollisionObjects: libfcl_disk defines them (src/fcl_hook.cpp, section 5) with
// a shortcut for pairs of Disks. This program links fcl_disk::fcl_disk, so its
// calls must reach those definitions, in double too, where libfcl exports the
// same symbols.

/// The file of the shared object that defines the code at `function`.
template <typename Function>
std::string definingObject(Function* function) {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(function), &info) == 0 || !info.dli_fname) return "?";
  return info.dli_fname;
}

TEST(Hook, ObjectEntryPointsAreFcl_disks) {
  const std::string files[] = {
      definingObject<double(const fcl::CollisionObjectd*, const fcl::CollisionObjectd*,
                            const fcl::DistanceRequestd&, fcl::DistanceResultd&)>(
          &fcl::distance<double>),
      definingObject<float(const fcl::CollisionObjectf*, const fcl::CollisionObjectf*,
                           const fcl::DistanceRequestf&, fcl::DistanceResultf&)>(
          &fcl::distance<float>),
      definingObject<std::size_t(const fcl::CollisionObjectd*, const fcl::CollisionObjectd*,
                                 const fcl::CollisionRequestd&, fcl::CollisionResultd&)>(
          &fcl::collide<double>),
      definingObject<std::size_t(const fcl::CollisionObjectf*, const fcl::CollisionObjectf*,
                                 const fcl::CollisionRequestf&, fcl::CollisionResultf&)>(
          &fcl::collide<float>)};
  for (const std::string& file : files) EXPECT_NE(file.find("libfcl_disk"), std::string::npos) << file;
}

/// Bitwise equality, NaN equal to NaN (both paths write the same quiet NaN, but
/// compare them as values of the kind, not as bits).
template <typename S>
bool same(S a, S b) {
  return (std::isnan(a) && std::isnan(b)) || std::memcmp(&a, &b, sizeof(S)) == 0;
}

template <typename S>
bool sameVector(const fcl::Vector3<S>& a, const fcl::Vector3<S>& b) {
  return same(a.x(), b.x()) && same(a.y(), b.y()) && same(a.z(), b.z());
}

template <typename S>
struct EntryPair {
  std::shared_ptr<fcl::CollisionGeometry<S>> g1, g2;
  fcl::Transform3<S> X1, X2;
  bool overlapping;
};

/// Disk pairs of every kind the shortcut can see: apart, overlapping (every
/// eighth pair is made coplanar and overlapping, in float only to rounding; every
/// eighth more crosses the other's plane at a tilt of 0.05 rad, overlapping in
/// float too), and a few with a NaN pose.
template <typename S>
std::vector<EntryPair<S>> entryPairs() {
  fcl_disk_test::Random random(4242);
  std::vector<EntryPair<S>> pairs;
  for (int i = 0; i < 240; ++i) {
    fcl::Transform3<double> X1 = fcl::Transform3<double>::Identity(), X2 = X1;
    X1.linear() = random.rotation();
    X1.translation() = random.inBall(2.0);
    X2.linear() = i % 8 == 0   ? X1.linear()
                  : i % 8 == 4 ? X1.linear() * Eigen::AngleAxisd(0.05, Vec3::UnitX()).matrix()
                               : random.rotation();
    X2.translation() = i % 4 == 0 ? X1 * Vec3(0.3, 0.2, 0.0) : X1.translation() + random.inBall(2.5);
    if (i % 60 == 59) X2.translation().x() = std::numeric_limits<double>::quiet_NaN();
    const double r1 = random.uniform(0.3, 1.5), r2 = random.uniform(0.3, 1.5);
    EntryPair<S> pair{std::make_shared<fcl_disk::Disk<S>>(S(r1)),
                      std::make_shared<fcl_disk::Disk<S>>(S(r2)), X1.cast<S>(), X2.cast<S>(),
                      false};
    pair.overlapping = fcl_disk::intersectDisks(S(r1), pair.X1, S(r2), pair.X2);
    pairs.push_back(pair);
  }
  return pairs;
}

/// A Disk against one shape of every node type fcl_disk answers it against (a
/// real fcl::Cylinder among them), the disk first in one pair and second in the
/// next, near enough to overlap in about half of them, and a few with a NaN
/// pose; `overlapping` as fcl::collide through the tables decides it.
template <typename S>
std::vector<EntryPair<S>> entryShapePairs() {
  using V = fcl::Vector3<S>;
  auto hull_points = std::make_shared<const std::vector<V>>(std::vector<V>{
      V(0.5, 0, 0), V(-0.2, 0.4, 0.1), V(-0.2, -0.4, 0.1), V(0.1, 0, 0.6), V(0, 0.1, -0.5)});
  auto hull_faces = std::make_shared<const std::vector<int>>(std::vector<int>{
      3, 0, 1, 3, 3, 1, 2, 3, 3, 2, 0, 3, 3, 0, 2, 4, 3, 2, 1, 4, 3, 1, 0, 4});
  const std::vector<std::shared_ptr<fcl::CollisionGeometry<S>>> shapes = {
      std::make_shared<fcl::Sphere<S>>(S(0.4)),
      std::make_shared<fcl::Box<S>>(S(0.6), S(0.4), S(0.8)),
      std::make_shared<fcl::Capsule<S>>(S(0.3), S(0.8)),
      std::make_shared<fcl::Cylinder<S>>(S(0.4), S(0.7)),
      std::make_shared<fcl::Cone<S>>(S(0.4), S(0.8)),
      std::make_shared<fcl::Ellipsoid<S>>(S(0.3), S(0.5), S(0.4)),
      std::make_shared<fcl::Convex<S>>(hull_points, 6, hull_faces),
      std::make_shared<fcl::Halfspace<S>>(V(0.3, -0.2, 1).normalized(), S(-0.4)),
      std::make_shared<fcl::Plane<S>>(V(-0.5, 0.2, 1).normalized(), S(0.3)),
      std::make_shared<fcl::TriangleP<S>>(V(0.5, 0, 0), V(-0.3, 0.4, 0.1), V(0, -0.5, 0.2))};
  fcl_disk_test::Random random(4343);
  std::vector<EntryPair<S>> pairs;
  for (const auto& shape : shapes) {
    for (int i = 0; i < 24; ++i) {
      fcl::Transform3<double> X_disk = fcl::Transform3<double>::Identity(), X_shape = X_disk;
      X_disk.linear() = random.rotation();
      X_disk.translation() = random.inBall(1.5);
      X_shape.linear() = random.rotation();
      X_shape.translation() = random.inBall(1.5);
      if (i == 23) X_shape.translation().y() = std::numeric_limits<double>::quiet_NaN();
      const auto disk = std::make_shared<fcl_disk::Disk<S>>(S(random.uniform(0.3, 1.0)));
      EntryPair<S> pair = i % 2 == 0
                              ? EntryPair<S>{disk, shape, X_disk.cast<S>(), X_shape.cast<S>(), false}
                              : EntryPair<S>{shape, disk, X_shape.cast<S>(), X_disk.cast<S>(), false};
      fcl::CollisionResult<S> result;
      pair.overlapping = fcl::collide(pair.g1.get(), pair.X1, pair.g2.get(), pair.X2,
                                      fcl::CollisionRequest<S>(), result) > 0;
      pairs.push_back(pair);
    }
  }
  return pairs;
}

/// entryPairs and entryShapePairs.
template <typename S>
std::vector<EntryPair<S>> allEntryPairs() {
  std::vector<EntryPair<S>> pairs = entryPairs<S>();
  const std::vector<EntryPair<S>> shape_pairs = entryShapePairs<S>();
  pairs.insert(pairs.end(), shape_pairs.begin(), shape_pairs.end());
  return pairs;
}

// The shortcut answers exactly as FCL's own entry does through the tables
// (fcl::distance on geometries and poses, which no definition here replaces),
// for disk pairs and a disk against every shape type it answers, in both
// orders: every request flag and solver, fresh and carried-over results,
// including those FCL's entry treats specially (indep, signed, result already
// negative).
template <typename S>
void expectObjectDistanceAsTables() {
  int overlapping = 0;
  for (const EntryPair<S>& pair : allEntryPairs<S>()) {
    overlapping += pair.overlapping;
    const fcl::CollisionObject<S> a(pair.g1, pair.X1), b(pair.g2, pair.X2);
    for (auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
      for (int flags = 0; flags < 4; ++flags) {
        fcl::DistanceRequest<S> request(flags & 1);
        request.enable_signed_distance = flags & 2;
        request.gjk_solver_type = solver;
        // Fresh; carried over from a farther and a nearer pair; already negative.
        // Not the last with indep and signed: there FCL's entry recomputes a
        // penetration depth with collide() and asserts that it found one above
        // the smallest positive number, which two zero-thickness disks never have
        // (the shortcut leaves that case to FCL's entry; docs/fcl_hook.md).
        for (S initial : {std::numeric_limits<S>::max(), S(5), S(0.05), S(-0.5)}) {
          if (initial < 0 && solver == fcl::GST_INDEP && request.enable_signed_distance) continue;
          fcl::DistanceResult<S> through_objects, through_tables;
          through_objects.min_distance = through_tables.min_distance = initial;
          const S d_objects = fcl::distance(&a, &b, request, through_objects);
          const S d_tables =
              fcl::distance(pair.g1.get(), pair.X1, pair.g2.get(), pair.X2, request,
                            through_tables);
          SCOPED_TRACE(::testing::Message() << "solver " << solver << " flags " << flags
                                            << " initial " << initial);
          EXPECT_TRUE(same(d_objects, d_tables)) << d_objects << " vs " << d_tables;
          EXPECT_TRUE(same(through_objects.min_distance, through_tables.min_distance));
          EXPECT_EQ(through_objects.o1, through_tables.o1);
          EXPECT_EQ(through_objects.o2, through_tables.o2);
          EXPECT_EQ(through_objects.b1, through_tables.b1);
          EXPECT_EQ(through_objects.b2, through_tables.b2);
          for (int k : {0, 1}) {
            EXPECT_TRUE(sameVector<S>(through_objects.nearest_points[k],
                                      through_tables.nearest_points[k]));
          }
        }
      }
    }
  }
  EXPECT_GT(overlapping, 80);  // overlapping pairs are answered by their common point
}

template <typename S>
void expectObjectCollideAsTables() {
  struct Flags {
    std::size_t max_contacts;
    bool contact, cost;
  };
  int colliding = 0;
  const std::vector<EntryPair<S>> pairs = allEntryPairs<S>();
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const EntryPair<S>& pair = pairs[i];
    const fcl::CollisionObject<S> a(pair.g1, pair.X1), b(pair.g2, pair.X2);
    for (auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
      // num_max_contacts = 0 makes FCL's entry print a warning: one pair does.
      for (Flags flags : {Flags{1, false, false}, Flags{1, true, false}, Flags{4, true, true},
                          Flags{0, false, false}}) {
        if (flags.max_contacts == 0 && i != 0) continue;
        fcl::CollisionRequest<S> request(flags.max_contacts, flags.contact,
                                         flags.cost ? 4 : 1, flags.cost);
        request.gjk_solver_type = solver;
        // Fresh, and carrying one contact over from an earlier pair.
        for (bool carried : {false, true}) {
          fcl::CollisionResult<S> through_objects, through_tables;
          if (carried) {
            const fcl::Contact<S> earlier(pair.g2.get(), pair.g1.get(), 7, 8,
                                          fcl::Vector3<S>::Zero(), fcl::Vector3<S>::UnitZ(),
                                          S(0));
            through_objects.addContact(earlier);
            through_tables.addContact(earlier);
          }
          const std::size_t n_objects = fcl::collide(&a, &b, request, through_objects);
          const std::size_t n_tables = fcl::collide(pair.g1.get(), pair.X1, pair.g2.get(),
                                                    pair.X2, request, through_tables);
          SCOPED_TRACE(::testing::Message() << "solver " << solver << " max_contacts "
                                            << flags.max_contacts << " carried " << carried);
          EXPECT_EQ(n_objects, n_tables);
          ASSERT_EQ(through_objects.numContacts(), through_tables.numContacts());
          colliding += !carried && n_objects > 0;
          for (std::size_t k = 0; k < through_objects.numContacts(); ++k) {
            const auto& c1 = through_objects.getContact(k);
            const auto& c2 = through_tables.getContact(k);
            EXPECT_EQ(c1.o1, c2.o1);
            EXPECT_EQ(c1.o2, c2.o2);
            EXPECT_EQ(c1.b1, c2.b1);
            EXPECT_EQ(c1.b2, c2.b2);
            if (!request.enable_contact) continue;  // FCL leaves the geometry unset
            EXPECT_TRUE(sameVector<S>(c1.pos, c2.pos));
            EXPECT_TRUE(sameVector<S>(c1.normal, c2.normal));
            EXPECT_TRUE(same(c1.penetration_depth, c2.penetration_depth));
          }
          std::vector<fcl::CostSource<S>> costs1, costs2;
          through_objects.getCostSources(costs1);
          through_tables.getCostSources(costs2);
          ASSERT_EQ(costs1.size(), costs2.size());
          for (std::size_t k = 0; k < costs1.size(); ++k) {
            EXPECT_TRUE(sameVector<S>(costs1[k].aabb_min, costs2[k].aabb_min));
            EXPECT_TRUE(sameVector<S>(costs1[k].aabb_max, costs2[k].aabb_max));
            EXPECT_TRUE(same(costs1[k].total_cost, costs2[k].total_cost));
          }
        }
      }
    }
  }
  EXPECT_GT(colliding, 80);
}

TEST(Hook, ObjectDistanceAnswersAsTheTablesDouble) { expectObjectDistanceAsTables<double>(); }
TEST(Hook, ObjectDistanceAnswersAsTheTablesFloat) { expectObjectDistanceAsTables<float>(); }
TEST(Hook, ObjectCollideAnswersAsTheTablesDouble) { expectObjectCollideAsTables<double>(); }
TEST(Hook, ObjectCollideAnswersAsTheTablesFloat) { expectObjectCollideAsTables<float>(); }

TEST(Disk, RejectsBadRadiusWithTheValue) {
  for (double bad : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
                     std::numeric_limits<double>::infinity()}) {
    try {
      fcl_disk::Diskd disk(bad);
      ADD_FAILURE() << "accepted radius " << bad;
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find("radius"), std::string::npos);
    }
  }
  EXPECT_THROW(fcl_disk::Diskf(-2.0f), std::invalid_argument);
  const fcl_disk::Diskd disk(2.5);
  EXPECT_EQ(disk.radius, 2.5);
  EXPECT_EQ(disk.lz, 0.0);
  EXPECT_EQ(disk.getNodeType(), fcl::GEOM_CYLINDER);
}

}  // namespace

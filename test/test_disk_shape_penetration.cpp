// Signed distance of a Disk against the shapes with an exact penetration depth
// (every primitive but the Ellipsoid: kExactDiskShapePenetration), standalone and through
// fcl::distance / fcl::collide, float and double, against the long-double
// reference of reference_shape_penetration.h (written from the geometry, not from
// the solver's code: closed forms for the sphere, halfspace and plane, a search
// over the sphere of directions for the others). On every intersecting pose:
// witnesses on the disk with p1 - p2 = depth * direction, the same depth after a
// common rigid motion, separation one step past the depth and none one step
// short, both argument orders and solvers through fcl::distance, fcl::collide's
// depth and normal.
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>
#include <fcl_disk/fcl_disk.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <iostream>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "disk_shape_penetration_draws.h"
#include "hull_lists.h"
#include "reference_penetration.h"
#include "reference_shape_penetration.h"
#include "test_random.h"

namespace {

using fcl_disk_test::Random;
using Vd = Eigen::Vector3d;
using fcl_disk_shape_penetration_draws::randomPose;
using fcl_disk_shape_penetration_draws::randomShape;
using fcl_disk_shape_penetration_reference::diskOf;
using fcl_disk_shape_penetration_reference::pointDiskDistance;
using fcl_disk_shape_penetration_reference::Pose;
using fcl_disk_shape_penetration_reference::referenceDepth;
using fcl_disk_shape_penetration_reference::toReal;

/// Relative tolerances (of scale = r + shape size + centre distance). double:
/// the solvers' 1e-12 promise; float: the inputs and results are rounded to
/// float, 16 ulps of the scale.
template <typename S>
constexpr double kDepthRelative = std::is_same<S, float>::value ? 16 * 1.2e-7 : 1e-12;
/// The separation check's step: far above either rounding, far below any depth tested.
constexpr double kSeparationStepRelative = 1e-6;
/// The path of the continuity check moves the shape by this much per step (scale units).
constexpr double kPathStepRelative = 1e-3;
constexpr int kPosesPerShape = 30000;
/// The searched references take ~1 ms a pose: fewer poses.
constexpr int kSearchedPoses = 1500;
/// The common rigid motions are drawn from a stream of their own (this seed offset).
constexpr std::uint64_t kMotionSeedOffset = 1000;


template <typename S, typename Shape>
void checkShape(const char* name, std::uint64_t seed, int poses = kPosesPerShape) {
  SCOPED_TRACE(name);
  Random rng(seed);
  Random motion_rng(seed + kMotionSeedOffset);  // its own stream: the poses stay as they are
  int intersecting = 0;
  double worst = 0;
  for (int i = 0; i < poses; ++i) {
    const S r = S(rng.uniform(0.2, 1.0));
    const fcl::Transform3<S> X_WD = randomPose<S>(rng, 1.0);
    const fcl::Transform3<S> X_WS = randomPose<S>(rng, 1.0);
    const Shape shape = randomShape<S>(rng, static_cast<Shape*>(nullptr));
    const double scale = double(r) + 1.0 + 2.0;  // r + shape size + centre distance bound
    const double tolerance = kDepthRelative<S> * scale;
    const auto answer = fcl_disk::signedDiskShapeDistance(r, X_WD, shape, X_WS);
    const auto trace = [&] { return std::string(name) + " pose " + std::to_string(i); };
    ASSERT_TRUE(std::isfinite(double(answer.signed_distance))) << trace();
    EXPECT_NEAR(answer.direction.template cast<double>().norm(), 1.0, 1e-6) << trace();
    if (answer.signed_distance > 0) {
      // Apart: the plain distance, direction from the disk's point to the shape's.
      const auto distance = fcl_disk::diskShapeDistance(r, X_WD, shape, X_WS);
      EXPECT_EQ(answer.signed_distance, distance.distance) << trace();
      continue;
    }
    ++intersecting;
    const double depth = -double(answer.signed_distance);
    const double reference = double(referenceDepth(r, X_WD, shape, X_WS));
    EXPECT_NEAR(depth, reference, tolerance) << trace();
    worst = std::max(worst, std::abs(depth - reference) / scale);
    // Witnesses: p1 - p2 = depth * direction, p1 on the disk.
    const Vd p1 = answer.p_W1.template cast<double>(), p2 = answer.p_W2.template cast<double>();
    const Vd w = answer.direction.template cast<double>();
    EXPECT_LE((p1 - p2 - depth * w).norm(), tolerance) << trace();
    const Pose disk = diskOf(r, X_WD);
    EXPECT_LE(double(pointDiskDistance(toReal(p1), disk.c, disk.n, disk.r)), tolerance) << trace();
    // A common rigid motion (within the unit ball: the scale grows by at most
    // 1) moves nothing but the frame: the same depth.
    const fcl::Transform3d motion = randomPose<double>(motion_rng, 1.0);
    const auto moved_answer = fcl_disk::signedDiskShapeDistance(
        r, fcl::Transform3<S>((motion * X_WD.template cast<double>()).template cast<S>()), shape,
        fcl::Transform3<S>((motion * X_WS.template cast<double>()).template cast<S>()));
    EXPECT_NEAR(-double(moved_answer.signed_distance), depth, kDepthRelative<S> * (scale + 1.0))
        << trace() << " (after a common rigid motion)";
    // Moving the shape by depth + step along the direction separates; by
    // depth - step it does not.
    const double step = kSeparationStepRelative * scale;
    fcl::Transform3<S> moved = X_WS;
    moved.translation() = (X_WS.translation().template cast<double>() + (depth + step) * w).template cast<S>();
    EXPECT_GT(fcl_disk::diskShapeDistance(r, X_WD, shape, moved).distance, S(0)) << trace();
    if (depth > 2 * step) {
      moved.translation() =
          (X_WS.translation().template cast<double>() + (depth - step) * w).template cast<S>();
      EXPECT_TRUE(fcl_disk::diskShapeIntersect(r, X_WD, shape, moved)) << trace();
    }
    // Through FCL, both orders and solvers: -depth; libccd with the deepest
    // points (FCL's EPA convention), indep with collide()'s contact point.
    auto disk_geometry = std::make_shared<fcl_disk::Disk<S>>(r);
    auto shape_geometry = std::make_shared<Shape>(shape);
    fcl::CollisionObject<S> disk_object(disk_geometry, X_WD), shape_object(shape_geometry, X_WS);
    for (const auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
      for (const bool disk_first : {true, false}) {
        fcl::DistanceRequest<S> request(true);
        request.enable_signed_distance = true;
        request.gjk_solver_type = solver;
        fcl::DistanceResult<S> result;
        if (disk_first) {
          fcl::distance(&disk_object, &shape_object, request, result);
        } else {
          fcl::distance(&shape_object, &disk_object, request, result);
        }
        EXPECT_NEAR(double(result.min_distance), -depth, tolerance) << trace();
        if (solver == fcl::GST_LIBCCD && depth > 0) {
          const Vd o1_point = (disk_first ? p1 : p2), o2_point = (disk_first ? p2 : p1);
          EXPECT_LE((result.nearest_points[0].template cast<double>() - o1_point).norm(), tolerance)
              << trace();
          EXPECT_LE((result.nearest_points[1].template cast<double>() - o2_point).norm(), tolerance)
              << trace();
        }
      }
    }
    // fcl::collide: one contact, depth and normal of the penetration.
    fcl::CollisionRequest<S> request(1, true);
    fcl::CollisionResult<S> result;
    ASSERT_EQ(fcl::collide(&disk_object, &shape_object, request, result), 1u) << trace();
    EXPECT_NEAR(double(result.getContact(0).penetration_depth), depth, tolerance) << trace();
    if (depth > tolerance) {
      EXPECT_LE((result.getContact(0).normal.template cast<double>() - w).norm(), 1e-6) << trace();
    }
  }
  std::cout << "  " << name << ": " << intersecting << " intersecting poses of " << poses
            << ", largest |PD - PD_ref| / scale " << worst << "\n";
  EXPECT_GT(intersecting, poses / 10);
}

template <typename S>
class DiskShapePenetration : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(DiskShapePenetration, Scalars);

TYPED_TEST(DiskShapePenetration, SphereMatchesReference) {
  checkShape<TypeParam, fcl::Sphere<TypeParam>>("sphere", 11);
}
TYPED_TEST(DiskShapePenetration, HalfspaceMatchesReference) {
  checkShape<TypeParam, fcl::Halfspace<TypeParam>>("halfspace", 12);
}
TYPED_TEST(DiskShapePenetration, PlaneMatchesReference) {
  checkShape<TypeParam, fcl::Plane<TypeParam>>("plane", 13);
}
TYPED_TEST(DiskShapePenetration, CapsuleMatchesReference) {
  checkShape<TypeParam, fcl::Capsule<TypeParam>>("capsule", 14, kSearchedPoses);
}
TYPED_TEST(DiskShapePenetration, CylinderMatchesReference) {
  checkShape<TypeParam, fcl::Cylinder<TypeParam>>("cylinder", 15, kSearchedPoses);
}
TYPED_TEST(DiskShapePenetration, ConeMatchesReference) {
  checkShape<TypeParam, fcl::Cone<TypeParam>>("cone", 19, kSearchedPoses);
}
TYPED_TEST(DiskShapePenetration, BoxMatchesReference) {
  checkShape<TypeParam, fcl::Box<TypeParam>>("box", 16, kSearchedPoses);
}
TYPED_TEST(DiskShapePenetration, TriangleMatchesReference) {
  checkShape<TypeParam, fcl::TriangleP<TypeParam>>("triangle", 17, kSearchedPoses);
}
TYPED_TEST(DiskShapePenetration, ConvexMatchesReference) {
  checkShape<TypeParam, fcl::Convex<TypeParam>>("convex", 18, kSearchedPoses);
}

// Contacts against hulls with many features, where most candidates are
// screened out before their support scan (ConvexTraits::contactDirections):
// a ring hull (74 vertices, 84 faces: quadrilaterals and triangle fans) and a
// cube cut into 192 coplanar triangles (98 vertices), 4 intersecting random
// poses each, against the long-double reference.
TYPED_TEST(DiskShapePenetration, LargeHullsMatchReference) {
  using S = TypeParam;
  const fcl::Convex<S> hulls[] = {
      fcl_disk_test::convexOf<S>(fcl_disk_test::ringHull(6, 12, Vd(0.9, 0.7, 0.5))),
      fcl_disk_test::convexOf<S>(fcl_disk_test::subdividedCube(4, 0.6))};
  Random rng(19);
  for (const fcl::Convex<S>& hull : hulls) {
    int intersecting = 0;
    for (int attempt = 0; attempt < 200 && intersecting < 4; ++attempt) {
      const S r = S(rng.uniform(0.2, 1.0));
      const fcl::Transform3<S> X_WD = randomPose<S>(rng, 1.0);
      const fcl::Transform3<S> X_WS = randomPose<S>(rng, 1.0);
      const auto answer = fcl_disk::signedDiskShapeDistance(r, X_WD, hull, X_WS);
      if (!(answer.signed_distance < 0)) continue;
      ++intersecting;
      const double scale = double(r) + 1.0 + 2.0;  // r + hull size + centre distance bound
      EXPECT_NEAR(-double(answer.signed_distance), double(referenceDepth(r, X_WD, hull, X_WS)),
                  kDepthRelative<S> * scale)
          << hull.getFaceCount() << " faces, attempt " << attempt;
    }
    EXPECT_EQ(intersecting, 4);
  }
}

/// The pose with these three rows of its 3x4 matrix [R | t].
template <typename S>
fcl::Transform3<S> poseFromRows(std::initializer_list<S> rows) {
  fcl::Transform3<S> X = fcl::Transform3<S>::Identity();
  const std::vector<S> m(rows);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) X.linear()(i, j) = m[4 * i + j];
    X.translation()[i] = m[4 * i + 3];
  }
  return X;
}

/// A cone whose base rim grazes through the disk by 4e-6 of the scene: the
/// generic solver stalls 5e-13 from the cone without proving either answer,
/// and the cone's penetration candidates decide the overlap.
TEST(DiskShapePenetration, GrazingOverlapTheSolverLeavesOpen) {
  // The rows are a float rotation's: orthonormal to double precision again.
  const auto pose = [](std::initializer_list<double> rows) {
    fcl::Transform3d X = poseFromRows<double>(rows);
    X.linear() = Eigen::Quaterniond(X.linear()).normalized().toRotationMatrix();
    return X;
  };
  const double r = 0.84621530771255493;
  const fcl::Transform3d X_WD = pose({0.21576054394245148, -0.94261282682418823, 0.25481066107749939,
                                      -0.16098333895206451, -0.96560460329055786, -0.2447512149810791,
                                      -0.087776049971580505, 0.50574624538421631, 0.1451040506362915,
                                      -0.22710773348808289, -0.96299892663955688, -0.44478151202201843});
  const fcl::Transform3d X_WS = pose({0.69901025295257568, 0.61131948232650757, -0.37104335427284241,
                                      -0.34618356823921204, 0.49454975128173828, -0.78802913427352905,
                                      -0.36664777994155884, 0.68888574838638306, -0.51653188467025757,
                                      0.072791144251823425, -0.85316836833953857, -0.38350799679756165});
  const fcl::Coned cone(0.30189511179924011, 0.19546227157115936);
  const double reference = double(referenceDepth(r, X_WD, cone, X_WS));
  ASSERT_GT(reference, 1e-6);
  const double scale = r + 1.0 + 2.0;
  EXPECT_EQ(fcl_disk::diskShapeDistance(r, X_WD, cone, X_WS).distance, 0.0);
  fcl_disk::DiskContact<double> contact;
  ASSERT_TRUE(fcl_disk::diskShapeIntersect(r, X_WD, cone, X_WS, &contact));
  EXPECT_NEAR(contact.penetration_depth, reference, kDepthRelative<double> * scale);
  EXPECT_NEAR(fcl_disk::signedDiskShapeDistance(r, X_WD, cone, X_WS).signed_distance, -reference,
              kDepthRelative<double> * scale);
}

/// A frustum whose corner touches the disk's rim (fuzz_disk_shapes, float, the
/// scene 5e-4 across): the penetration depth is 0 up to rounding, its
/// minimisers the sector of directions normal to the rim and to the frustum at
/// the corner, which the edge lines' candidates e x t bound (b - x alone, at a
/// rim point this near the line, reported 1.0e-7).
TEST(DiskShapePenetration, CornerOnTheRimFoundByFuzzing) {
  const auto pose = poseFromRows<float>;
  const float r = 0.00013698112161364406f;
  const fcl::Transform3f X_WD =
      pose({0.562236487865448f, -0.44838684797286987f, -0.69486641883850098f, 0.0f,
            0.57124310731887817f, -0.39699521660804749f, 0.71838438510894775f, 0.0f,
            -0.59797275066375732f, -0.80083960294723511f, 0.032932702451944351f, 0.0f});
  const fcl::Transform3f X_WS =
      pose({0.21569669246673584f, -0.45080500841140747f, -0.86616957187652588f, -5.6003296776907519e-05f,
            -0.86623835563659668f, 0.32106620073318481f, -0.38281533122062683f, -0.00012742716353386641f,
            0.45067283511161804f, 0.83288133144378662f, -0.32125169038772583f, -0.00016394465637858957f});
  const float a = 5.7389872381463647e-05f, b = 5.7085002481471747e-05f, h = 5.7073124480666593e-05f;
  const float at = 4.7347191866720095e-05f, bt = 4.7095669287955388e-05f;
  auto vertices = std::make_shared<std::vector<fcl::Vector3f>>(std::vector<fcl::Vector3f>{
      {-a, -b, -h}, {a, -b, -h}, {a, b, -h}, {-a, b, -h},
      {-at, -bt, h}, {at, -bt, h}, {at, bt, h}, {-at, bt, h}});
  auto faces = std::make_shared<std::vector<int>>(std::vector<int>{
      4, 0, 3, 2, 1, 4, 4, 5, 6, 7, 4, 0, 1, 5, 4, 4, 1, 2, 6, 5, 4, 2, 3, 7, 6, 4, 3, 0, 4, 7});
  const fcl::Convexf frustum(vertices, 6, faces);
  // The depth is 2.4e-12 (a search of F over the sphere); the reference's
  // compass search crawls on F's flat sector here, so the bound is checked.
  const double scale = double(r) + 2e-4 + X_WS.translation().cast<double>().norm();
  const auto answer = fcl_disk::signedDiskShapeDistance(r, X_WD, frustum, X_WS);
  EXPECT_NEAR(double(answer.signed_distance), 0.0, kDepthRelative<float> * scale);
}

/// Hulls touching a disk whose faces are planar only to float's precision:
/// tapered prisms over an N-gon of an ellipse (N = 32..63, quadrilateral
/// sides, as fuzz_disk_shapes builds them) with vertices rounded to float, in
/// float, and in double with the same vertices, put against a disk so that
/// their support along a random direction w meets the disk's. The shortest
/// separation is then at most F(w) = h_disk(w) + h_hull(-w) (~0: touching up
/// to the rounding of the pose): the contact's depth may not exceed it. The
/// candidates of a pair with a common point were pruned as if every F were >=
/// -1e-12 of the scene, while the face planes, which found the common point,
/// reach beyond the vertices' hull that F reads: a hull vertex touching the
/// rim then lost its edges' candidates (fuzz_disk_shapes,
/// regression-float-hull-vertex-on-rim: depth 3.2e-6 where F(w) ~ 0, 1e-3 of
/// the scene).
template <typename S>
void checkHullsTouchingAlongTheirSeparation(std::uint64_t seed) {
  Random rng(seed);
  int touching = 0;
  for (int trial = 0; trial < 1500; ++trial) {
    const auto drawn = fcl_disk_test::drawFloatPrismAndDisk(
        rng, [](Random& r) { return r.uniform(0.0, 1.0); });
    const fcl_disk_test::HullLists& lists = drawn.lists;
    const fcl::Convex<S> hull = fcl_disk_test::convexOf<S>(lists);
    const S r = S(drawn.r);
    // In double from the data in S: the disk's rim point and the hull's
    // vertex lowest along w meet.
    const Vd w = rng.unitVector();
    const auto placed = fcl_disk_test::placeHullBesideDisk<S>(lists.vertices, r, drawn.R_disk,
                                                              drawn.R_hull, w, 0.0);
    const double F = -placed.gap;
    fcl_disk::DiskContact<S> contact;
    if (!fcl_disk::diskShapeIntersect(r, placed.X_WD, hull, placed.X_WS, &contact)) continue;
    ++touching;
    const double scale = double(r) + drawn.extent.norm() + placed.t.norm();
    EXPECT_LE(double(contact.penetration_depth), F + kDepthRelative<S> * scale)
        << "trial " << trial << ": scale " << scale;
  }
  EXPECT_GT(touching, 500);
}

TEST(DiskShapePenetration, HullsPlanarToFloatTouchingAlongTheirSeparationFloat) {
  checkHullsTouchingAlongTheirSeparation<float>(20240601 + 97);
}
TEST(DiskShapePenetration, HullsPlanarToFloatTouchingAlongTheirSeparationDouble) {
  checkHullsTouchingAlongTheirSeparation<double>(20240601 + 98);
}

/// A disk in a perturbed symmetric chain link with the top cap of a thin
/// cylinder (height 1e-6 of its radius): upright on the cap's rim through the
/// cap's centre, turned by 1e-8..1e-1 rad and moved by 1e-9..1e-2 of the
/// radius; equal radii and ratios 0.2..5. The cap's rim passes next to the
/// disk's axis, where the disk-disk candidates must be placed from the other
/// rim too (docs/penetration_depth.md, sections 2 and 7). The cylinder holds
/// the cap and adds h |w.n| at most along the cap's minimiser w, so its depth
/// lies in [PD_cap, PD_cap + h |w.n|], PD_cap from the disk-disk long-double
/// reference (test/reference_penetration.h).
TEST(DiskShapePenetration, ThinCylinderCapInAPerturbedChainLink) {
  Random rng(20240601 + 81);
  int checked = 0;
  double worst = 0;
  while (checked < 300) {
    const double rc = rng.uniform(0.3, 2.0);
    const double r = checked % 2 == 0 ? rc : rc * rng.logUniform(0.2, 5.0);
    const double h = 1e-6 * rc;
    const fcl::Cylinderd cylinder(rc, h);
    fcl::Transform3d X_WS = fcl::Transform3d::Identity();
    X_WS.linear() = rng.rotation();
    X_WS.translation() = rng.inBall(1.0);
    fcl::Transform3d X_WC = X_WS;  // the top cap
    X_WC.translation() = X_WS * Vd(0, 0, h / 2);
    Eigen::Matrix3d upright;  // in-plane axes: the cap's x and normal
    upright.col(0) = X_WC.linear().col(0);
    upright.col(1) = X_WC.linear().col(2);
    upright.col(2) = -X_WC.linear().col(1);
    fcl::Transform3d X_WD = fcl::Transform3d::Identity();
    X_WD.linear() =
        Eigen::AngleAxisd(rng.logUniform(1e-8, 1e-1), rng.unitVector()).toRotationMatrix() *
        upright;
    X_WD.translation() = X_WC.translation() + r * X_WC.linear().col(0) +
                         rng.logUniform(1e-9, 1e-2) * rc * rng.unitVector();
    const auto answer = fcl_disk::signedDiskShapeDistance(r, X_WD, cylinder, X_WS);
    if (!(answer.signed_distance < 0)) continue;
    const auto cap = fcl_disk_penetration_reference::referencePenetration(r, X_WD, rc, X_WC);
    if (!(cap.pd > 0)) continue;
    ++checked;
    const double lo = double(cap.pd);
    const double hi = lo + h * double(std::abs(cap.w.dot(toReal(X_WC.linear().col(2)))));
    const double depth = -answer.signed_distance;
    const double scale = r + rc + h + (X_WD.translation() - X_WS.translation()).norm();
    const double error = std::max({lo - depth, depth - hi, 0.0}) / scale;
    EXPECT_LE(error, kDepthRelative<double>)
        << "case " << checked << ": depth " << depth << " outside [" << lo << ", " << hi << "]";
    worst = std::max(worst, error);
  }
  std::cout << "  300 thin cylinders: largest distance outside the cap's bounds / scale " << worst
            << "\n";
}

TEST(DiskShapePenetration, HandMadeCases) {
  using X = fcl::Transform3d;
  X disk = X::Identity();  // radius 1 in the XY plane at the origin
  // A sphere of radius 0.5 centred 0.2 above the disk's face: out along +z by 0.3.
  X sphere_pose = X::Identity();
  sphere_pose.translation() = Vd(0.3, 0, 0.2);
  auto s = fcl_disk::signedDiskShapeDistance(1.0, disk, fcl::Sphered(0.5), sphere_pose);
  EXPECT_NEAR(s.signed_distance, -0.3, 1e-15);
  EXPECT_NEAR((s.direction - Vd::UnitZ()).norm(), 0.0, 1e-15);
  // Centre on the disk: out along the normal by the radius (tie between +-n).
  sphere_pose.translation() = Vd(0.3, 0, 0);
  s = fcl_disk::signedDiskShapeDistance(1.0, disk, fcl::Sphered(0.5), sphere_pose);
  EXPECT_NEAR(s.signed_distance, -0.5, 1e-15);
  EXPECT_NEAR(std::abs(s.direction.z()), 1.0, 1e-15);
  // Centre beyond the rim: out radially, by 0.5 - 0.1.
  sphere_pose.translation() = Vd(1.1, 0, 0);
  s = fcl_disk::signedDiskShapeDistance(1.0, disk, fcl::Sphered(0.5), sphere_pose);
  EXPECT_NEAR(s.signed_distance, -0.4, 1e-15);
  EXPECT_NEAR((s.direction - Vd::UnitX()).norm(), 0.0, 1e-15);
  // The ground z <= 0 under a disk standing on its rim, sunk 0.25 into it.
  X standing = X::Identity();
  standing.linear() = Eigen::AngleAxisd(M_PI / 2, Vd::UnitX()).toRotationMatrix();
  standing.translation() = Vd(0, 0, 0.75);
  s = fcl_disk::signedDiskShapeDistance(1.0, standing, fcl::Halfspaced(Vd::UnitZ(), 0.0),
                                        X::Identity());
  EXPECT_NEAR(s.signed_distance, -0.25, 1e-15);
  EXPECT_NEAR((s.direction + Vd::UnitZ()).norm(), 0.0, 1e-15);
  EXPECT_NEAR((s.p_W1 - Vd(0, 0, -0.25)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((s.p_W2 - Vd(0, 0, 0)).norm(), 0.0, 1e-15);
  // The plane z = 0 through the same disk: out by the shorter side, 0.25 (down).
  s = fcl_disk::signedDiskShapeDistance(1.0, standing, fcl::Planed(Vd::UnitZ(), 0.0), X::Identity());
  EXPECT_NEAR(s.signed_distance, -0.25, 1e-15);
  // NaN in, NaN out.
  X nan_pose = X::Identity();
  nan_pose.translation().x() = std::nan("");
  s = fcl_disk::signedDiskShapeDistance(1.0, nan_pose, fcl::Sphered(0.5), X::Identity());
  EXPECT_TRUE(std::isnan(s.signed_distance));
}

/// The signed distance is continuous through contact and 1-Lipschitz in the
/// shape's translation.
TEST(DiskShapePenetration, ContinuousThroughContact) {
  using X = fcl::Transform3d;
  Random rng(21);
  for (int path = 0; path < 50; ++path) {
    const X disk = randomPose<double>(rng, 0.5);
    X sphere_pose = X::Identity();
    const Vd start = rng.inBall(0.2), direction = rng.unitVector();
    double last = NAN;
    for (int k = 0; k <= 2000; ++k) {
      sphere_pose.translation() = start + (k * kPathStepRelative) * direction;
      const double sd =
          fcl_disk::signedDiskShapeDistance(0.7, disk, fcl::Sphered(0.3), sphere_pose).signed_distance;
      if (k > 0) {
        EXPECT_LE(std::abs(sd - last), kPathStepRelative * (1 + 1e-9) + 1e-12)
            << "path " << path << " step " << k;
      }
      last = sd;
    }
  }
}

}  // namespace

// Linked into every "with fcl_disk" executable of this folder (not one of FCL's
// files): fails unless libfcl_disk is loaded into the process and its hook answers
// FCL's own entry points for disk pairs, so a passing "with" run did run FCL's
// tests with fcl_disk's tables in place.
//
// The discriminator: two crossing disks. fcl_disk answers distance 0 with a common
// point as both nearest points (docs/fcl_hook.md, "Conventions"); FCL's own
// unsigned distance between colliding shapes is -1. Checked through the object-
// and geometry-level fcl::distance, both GJK solvers, double and float.
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>
#include <fcl_disk/fcl_disk.h>
#include <gtest/gtest.h>

#include <memory>

namespace {

template <typename S>
void expectFclDiskAnswers() {
  const S radius = 1;
  auto disk1 = std::make_shared<fcl_disk::Disk<S>>(radius);
  auto disk2 = std::make_shared<fcl_disk::Disk<S>>(radius);
  // Disk 1 in the XY plane, disk 2 in the XZ plane: they cross along the x axis.
  fcl::Transform3<S> X_W1 = fcl::Transform3<S>::Identity();
  fcl::Transform3<S> X_W2 = fcl::Transform3<S>::Identity();
  X_W2.linear() = fcl::AngleAxis<S>(S(M_PI / 2), fcl::Vector3<S>::UnitX()).toRotationMatrix();
  X_W2.translation() = fcl::Vector3<S>(S(0.25), 0, 0);
  const fcl::CollisionObject<S> object1(disk1, X_W1), object2(disk2, X_W2);

  for (const auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
    SCOPED_TRACE(solver == fcl::GST_LIBCCD ? "libccd" : "indep");
    fcl::DistanceRequest<S> request(/*enable_nearest_points=*/true);
    request.gjk_solver_type = solver;
    {
      SCOPED_TRACE("object-level fcl::distance");
      fcl::DistanceResult<S> result;
      EXPECT_EQ(fcl::distance(&object1, &object2, request, result), S(0));
      EXPECT_EQ(result.min_distance, S(0));
      EXPECT_EQ(result.nearest_points[0], result.nearest_points[1]);
    }
    {
      SCOPED_TRACE("geometry-level fcl::distance");
      fcl::DistanceResult<S> result;
      EXPECT_EQ(fcl::distance(disk1.get(), X_W1, disk2.get(), X_W2, request, result), S(0));
      EXPECT_EQ(result.nearest_points[0], result.nearest_points[1]);
    }
    {
      SCOPED_TRACE("fcl::collide");
      fcl::CollisionRequest<S> collision_request(1, /*enable_contact=*/true);
      collision_request.gjk_solver_type = solver;
      fcl::CollisionResult<S> result;
      EXPECT_EQ(fcl::collide(&object1, &object2, collision_request, result), 1u);
    }
  }
  // A separated pair: the answer is fcl_disk's exact solver's, bit for bit.
  X_W2.translation() = fcl::Vector3<S>(S(0.25), 0, S(2.5));
  const fcl::CollisionObject<S> apart(disk2, X_W2);
  fcl::DistanceRequest<S> request;
  fcl::DistanceResult<S> result;
  EXPECT_EQ(fcl::distance(&object1, &apart, request, result),
            fcl_disk::exactDiskDistance(radius, X_W1, radius, X_W2).distance);
}

GTEST_TEST(FclDiskLoaded, FclAnswersDiskPairsWithFcl_disksHookDouble) {
  expectFclDiskAnswers<double>();
}

GTEST_TEST(FclDiskLoaded, FclAnswersDiskPairsWithFcl_disksHookFloat) {
  expectFclDiskAnswers<float>();
}

}  // namespace

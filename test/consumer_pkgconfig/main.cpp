// A program built with only `pkg-config --cflags --libs fcl_disk` (see Makefile):
// queries Disks through plain fcl::distance / fcl::collide and checks the answers.
// Exits 0 if every check passes, 1 otherwise.
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>
#include <fcl_disk/fcl_disk.h>

#include <cmath>
#include <cstdio>
#include <memory>

namespace {

int failures = 0;
const double kHalfPi = std::acos(0.0);

void check(bool ok, const char* what, double got, double expected) {
  std::printf("[%s] %s: %.17g (expected %.17g)\n", ok ? "PASS" : "FAIL", what, got, expected);
  if (!ok) ++failures;
}

fcl::Transform3d pose(const fcl::Vector3d& centre, const fcl::Vector3d& axis, double angle) {
  fcl::Transform3d X = fcl::Transform3d::Identity();
  X.translation() = centre;
  X.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  return X;
}

double distance(const std::shared_ptr<fcl::CollisionGeometryd>& g1, const fcl::Transform3d& X1,
                const std::shared_ptr<fcl::CollisionGeometryd>& g2, const fcl::Transform3d& X2) {
  fcl::CollisionObjectd o1(g1, X1), o2(g2, X2);
  fcl::DistanceRequestd request;
  request.enable_nearest_points = true;
  fcl::DistanceResultd result;
  fcl::distance(&o1, &o2, request, result);
  return result.min_distance;
}

}  // namespace

int main() {
  auto disk = std::make_shared<fcl_disk::Diskd>(1.0);
  const fcl::Vector3d x = fcl::Vector3d::UnitX();
  const fcl::Transform3d I = fcl::Transform3d::Identity();

  // Two parallel coaxial disks 2 apart, and a disk standing on edge 2 beyond the rim.
  check(std::abs(distance(disk, I, disk, pose({0, 0, 2}, x, 0)) - 2) < 1e-12,
        "coaxial disks", distance(disk, I, disk, pose({0, 0, 2}, x, 0)), 2);
  const fcl::Transform3d X_edge = pose({3, 0, 0}, fcl::Vector3d::UnitY(), kHalfPi);
  check(std::abs(distance(disk, I, disk, X_edge) - 2) < 1e-12, "disk on edge",
        distance(disk, I, disk, X_edge), 2);

  // A tilted pair: fcl::distance must give fcl_disk's exact answer, not GJK's.
  const fcl::Transform3d X_tilted = pose({0.7, 0.4, 1.1}, {1, 2, 0.5}, 1.2);
  const double exact = fcl_disk::exactDiskDistance(1.0, I, 1.0, X_tilted).distance;
  const double through_fcl = distance(disk, I, disk, X_tilted);
  check(std::abs(through_fcl - exact) <= 1e-12 * (1 + exact),
        "tilted pair, fcl::distance == exactDiskDistance", through_fcl, exact);

  // A disk against FCL's sphere, radius 0.5, centre 2 above the disk's centre.
  auto sphere = std::make_shared<fcl::Sphered>(0.5);
  check(std::abs(distance(disk, I, sphere, pose({0, 0, 2}, x, 0)) - 1.5) < 1e-12,
        "disk-sphere", distance(disk, I, sphere, pose({0, 0, 2}, x, 0)), 1.5);

  // Two crossing disks collide.
  fcl::CollisionObjectd a(disk, I), b(disk, pose({0.5, 0, 0}, fcl::Vector3d::UnitY(), kHalfPi));
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  fcl::collide(&a, &b, request, result);
  check(result.isCollision() && result.numContacts() == 1, "crossing disks: one contact",
        result.numContacts(), 1);

  std::printf("%s: %d check(s) failed\n", failures ? "FAILED" : "OK", failures);
  return failures == 0 ? 0 : 1;
}

// Built in a colcon workspace against the fcl_disk package built there (see
// CMakeLists.txt); run from the workspace's install/setup.sh environment by
// scripts/check_packaging.sh. Exits 0 if fcl::distance gives fcl_disk's answers.
#include <fcl/narrowphase/distance.h>
#include <fcl_disk/fcl_disk.h>

#include <cmath>
#include <cstdio>
#include <memory>

int main() {
  auto disk = std::make_shared<fcl_disk::Diskd>(1.0);
  fcl::Transform3d X_W1 = fcl::Transform3d::Identity();
  fcl::Transform3d X_W2 = fcl::Transform3d::Identity();
  X_W2.translation() = fcl::Vector3d(0.7, 0.4, 1.1);
  X_W2.linear() = Eigen::AngleAxisd(1.2, fcl::Vector3d(1, 2, 0.5).normalized()).toRotationMatrix();

  fcl::CollisionObjectd o1(disk, X_W1), o2(disk, X_W2);
  fcl::DistanceRequestd request;
  fcl::DistanceResultd result;
  fcl::distance(&o1, &o2, request, result);
  const double exact = fcl_disk::exactDiskDistance(1.0, X_W1, 1.0, X_W2).distance;

  // Coaxial disks 2 apart: distance 2.
  fcl::Transform3d X_W3 = fcl::Transform3d::Identity();
  X_W3.translation() = fcl::Vector3d(0, 0, 2);
  fcl::CollisionObjectd o3(disk, X_W3);
  fcl::DistanceResultd coaxial;
  fcl::distance(&o1, &o3, request, coaxial);

  const bool ok = std::abs(result.min_distance - exact) <= 1e-12 * (1 + exact) &&
                  std::abs(coaxial.min_distance - 2) < 1e-12;
  std::printf("fcl_disk_consumer: tilted pair %.17g (exactDiskDistance %.17g), coaxial %.17g "
              "(expected 2): %s\n",
              result.min_distance, exact, coaxial.min_distance, ok ? "OK" : "FAILED");
  return ok ? 0 : 1;
}

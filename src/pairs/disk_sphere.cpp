// Disk - fcl::Sphere, closed form: the sphere is its centre inflated by its
// radius, and the disk point nearest the centre (the centre's foot on the disk's
// plane, clamped to the rim) is optimal. A sphere is the same set in every
// rotation of its frame, so the pair is solved in diskAtShapeOrigin's frame (the
// world's axes, the centre as origin). docs/disk_shape_distance.md, section 4.
#include "../disk_shape_pair.h"

namespace fcl_disk {
namespace internal {
namespace {

/// The sphere's centre, the origin of the frame: the core whose support the
/// certificate and the contact use.
struct CentreTarget {
  Vec3 support(const Vec3&) const { return Vec3::Zero(); }
};

template <typename S>
bool isValidSphere(const fcl::Sphere<S>& sphere) {
  return isValidShapeLength(double(sphere.radius));
}

/// p = the disk point nearest the centre; q on the sphere towards p; distance
/// |p| - rho, or 0 with p common when |p| <= rho. Always inlined, so that the
/// disk from diskAtShapeOrigin stays in registers.
[[gnu::always_inline]] inline DiskShapeSolution solveSphere(const DiskInShape& disk, double rho) {
  DiskShapeSolution solution;
  solution.p = disk.point(disk.nearest(Vec3::Zero()));
  const double core_distance = solution.p.norm();
  if (core_distance <= rho) {
    solution.q = solution.p;
    return solution;
  }
  solution.q = (rho / core_distance) * solution.p;
  solution.distance = core_distance - rho;
  // Along p -> centre; and along the disk's normal towards the centre, which is
  // that direction exactly when the foot is inside the rim and which, unlike
  // -p, does not lose its digits when the centre is within rounding of the disk.
  const Vec3 normal_towards_centre = disk.n.dot(solution.p) > 0.0 ? Vec3(-disk.n) : disk.n;
  solution.lower_bound =
      std::max({0.0, certificateAlong(CentreTarget(), disk, rho, Vec3(-solution.p)),
                certificateAlong(CentreTarget(), disk, rho, normal_towards_centre)});
  return solution;
}

}  // namespace

template <typename S>
struct DiskShapePair<fcl::Sphere<S>> {
  static DiskShapeDistanceResult<S> distance(S radius, const fcl::Transform3<S>& X_WD,
                                             const fcl::Sphere<S>& sphere,
                                             const fcl::Transform3<S>& X_WS) {
    if (!isValidDiskAndShapePose(radius, X_WD, X_WS) || !isValidSphere(sphere)) {
      return nanDiskShapeResult<S>();
    }
    return toWorldFromShapeOrigin(
        X_WS, solveSphere(diskAtShapeOrigin(radius, X_WD, X_WS), double(sphere.radius)));
  }

  static bool intersect(S radius, const fcl::Transform3<S>& X_WD, const fcl::Sphere<S>& sphere,
                        const fcl::Transform3<S>& X_WS, DiskContact<S>* contact) {
    if (!isValidDiskAndShapePose(radius, X_WD, X_WS) || !isValidSphere(sphere)) return false;
    const DiskInShape disk = diskAtShapeOrigin(radius, X_WD, X_WS);
    const double rho = double(sphere.radius);
    const DiskShapeSolution solution = solveSphere(disk, rho);
    const double scale = disk.r + rho + disk.c.norm();
    if (!(solution.distance <= kShapeTouchingTolerance * scale)) return false;
    if (contact) {
      const auto depth_along = [&](const Vec3& w) { return disk.support(w) + rho; };
      // Candidates: the disk's normals and the direction from p to the centre.
      *contact = contactFromShapeOrigin<S>(
          X_WS, solution.p,
          shortestSeparation(disk, std::array<Vec3, 1>{-solution.p}, depth_along));
    }
    return true;
  }
};

}  // namespace internal
}  // namespace fcl_disk

FCL_DISK_INSTANTIATE_DISK_SHAPE_PAIR(fcl::Sphere)

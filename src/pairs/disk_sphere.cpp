// Disk - fcl::Sphere, closed form: the disk point nearest the sphere's centre
// (its foot on the disk's plane, clamped to the rim) is optimal, because the
// sphere is its centre inflated by its radius. docs/disk_shape_distance.md,
// section 4.
#include "../disk_shape_pair.h"

namespace fcl_disk {
namespace internal {
namespace {

/// The sphere's centre as a target of the generic solver's certificate and
/// contact: a point, inflated by the radius.
struct PointTarget {
  Vec3 point;
  Vec3 support(const Vec3&) const { return point; }
};

template <typename S>
bool isValidSphere(const fcl::Sphere<S>& sphere) {
  return isValidShapeLength(double(sphere.radius));
}

}  // namespace

template <typename S>
struct DiskShapePair<fcl::Sphere<S>> {
  /// The solution in D: p = nearest disk point to the centre c, q on the sphere
  /// towards p; distance |c - p| - rho, or 0 with p common when |c - p| <= rho.
  static DiskShapeSolution solve(double r, const PointTarget& centre, double rho) {
    const Vec3& c = centre.point;
    const Vec2 foot = nearestOnDisk(c, r);
    DiskShapeSolution solution;
    solution.p = Vec3(foot.x(), foot.y(), 0.0);
    const Vec3 to_centre = c - solution.p;
    const double core_distance = to_centre.norm();
    if (core_distance <= rho) {
      solution.q = solution.p;
      solution.intersecting = true;
      return solution;
    }
    solution.q = c - (rho / core_distance) * to_centre;
    solution.distance = core_distance - rho;
    solution.lower_bound = std::max(0.0, certificateAlong(centre, r, rho, c - solution.p));
    return solution;
  }

  static DiskShapeDistanceResult<S> distance(S radius, const fcl::Transform3<S>& X_WD,
                                             const fcl::Sphere<S>& sphere,
                                             const fcl::Transform3<S>& X_WS) {
    if (!isValidDiskAndShapePose(radius, X_WD, X_WS) || !isValidSphere(sphere)) {
      return nanDiskShapeResult<S>();
    }
    const PointTarget centre{PoseInDisk::of(X_WD, X_WS).c};
    return toWorld(X_WD, solve(double(radius), centre, double(sphere.radius)));
  }

  static bool intersect(S radius, const fcl::Transform3<S>& X_WD, const fcl::Sphere<S>& sphere,
                        const fcl::Transform3<S>& X_WS, DiskContact<S>* contact) {
    if (!isValidDiskAndShapePose(radius, X_WD, X_WS) || !isValidSphere(sphere)) return false;
    const PointTarget centre{PoseInDisk::of(X_WD, X_WS).c};
    const double r = double(radius), rho = double(sphere.radius);
    const DiskShapeSolution solution = solve(r, centre, rho);
    const double scale = r + rho + centre.point.norm();
    if (!(solution.distance <= kShapeTouchingTolerance * scale)) return false;
    if (contact) {
      const auto depth_along = [&](const Vec3& w) {
        return r * std::sqrt(w.x() * w.x() + w.y() * w.y()) - (w.dot(centre.point) - rho);
      };
      // Candidates: the disk's normals and the direction from p to the centre.
      *contact = contactInWorld<S>(X_WD, solution.p,
                                   std::array<Vec3, 1>{centre.point - solution.p}, depth_along);
    }
    return true;
  }
};

}  // namespace internal
}  // namespace fcl_disk

FCL_DISK_INSTANTIATE_DISK_SHAPE_PAIR(fcl::Sphere)

// Disk - fcl::Cylinder (a real, solid one): the side wall as the capsule pair
// and the caps as disk-disk pairs where their certificates close
// (CylinderTraits::closedForm), else the generic solver with the cylinder's
// projection (clamp the height, clamp the radial distance) and support
// (docs/disk_shape_distance.md, section 4); the contact's directions make its
// depth the exact penetration depth (docs/penetration_depth.md, section 7).
#include "../disk_shape_pair.h"
#include "feature_candidates.h"
#include "../leaf_solvers.h"
#include "flat_end_pair.h"

#include <vector>

namespace fcl_disk {
namespace internal {
namespace {

/// The solid cylinder {x^2 + y^2 <= radius^2, |z| <= half_length}, in its frame.
struct CylinderTarget {
  double radius;
  double half_length;

  Projection project(const Vec3& y) const {
    const double z = std::clamp(y.z(), -half_length, half_length);
    const double rho = std::sqrt(y.x() * y.x() + y.y() * y.y());
    // psi's Hessian in the cylinder frame: z z^T beyond an end cap; in the
    // plane, 0 inside the radius, else that of a circle's disk,
    // e e^T + (1 - radius / rho) t t^T (e radial, t tangent).
    FactoredHessian hessian = FactoredHessian::diagonalOf(Vec3(0.0, 0.0, z != y.z() ? 1.0 : 0.0));
    Vec3 q_S(y.x(), y.y(), z);
    if (rho > radius) {
      const double shrink = radius / rho;
      q_S.x() *= shrink, q_S.y() *= shrink;
      const Vec3 e(y.x() / rho, y.y() / rho, 0.0);
      hessian.add(1.0, e).add(1.0 - shrink, Vec3(-e.y(), e.x(), 0.0));
    }
    return Projection{q_S, hessian};
  }

  Vec3 support(const Vec3& w_S) const {
    const double planar = std::sqrt(w_S.x() * w_S.x() + w_S.y() * w_S.y());
    // Ties: w along the axis takes the rim point on +x; w in the plane the + cap.
    const Vec3 rim = planar > 0.0 ? Vec3(radius * w_S.x() / planar, radius * w_S.y() / planar, 0.0)
                                  : Vec3(radius, 0.0, 0.0);
    return rim + Vec3(0.0, 0.0, w_S.z() < 0.0 ? -half_length : half_length);
  }

  /// The caps: candidates where a nearly parallel disk's rim crosses a cap's rim.
  std::array<FlatEnd, 2> flatEnds() const {
    return {FlatEnd{-half_length, radius}, FlatEnd{half_length, radius}};
  }
};

template <typename S>
struct CylinderTraits {
  static bool valid(const fcl::Cylinder<S>& cylinder) {
    return areValidShapeLengths({double(cylinder.radius), double(cylinder.lz)});
  }
  static double boundingRadius(const fcl::Cylinder<S>& cylinder) {
    return Vec2(double(cylinder.radius), 0.5 * double(cylinder.lz)).norm();
  }
  static double inflation(const fcl::Cylinder<S>&) { return 0.0; }
  static CylinderTarget target(const fcl::Cylinder<S>& cylinder) {
    return CylinderTarget{double(cylinder.radius), 0.5 * double(cylinder.lz)};
  }
  /// Two exact cases, each a simpler pair (docs/disk_shape_distance.md,
  /// section 4):
  /// - the side wall: the cylinder lies in the capsule of its radius about
  ///   its axis, and the two share every point with |z| <= half_length. So
  ///   where the capsule's nearest point (solveDiskCapsule) has |z| <=
  ///   half_length, it is on the cylinder, and the capsule's answer and
  ///   certificate are the cylinder's;
  /// - a cap (diskAgainstFlatEnd): where the disk-disk pair of the disk and
  ///   a cap is the cylinder's, the certificate along it closes.
  /// The cap facing the disk's centre is tried first when the centre lies
  /// beyond that cap's plane, then the side wall, then the cap beyond which
  /// the capsule's point lies. What neither settles (an optimum at a cap's
  /// rim seen from the side, where the certificate along one pair can stay
  /// open) goes to the generic solver. `disk`'s axes are orthonormal
  /// (solvedDiskInShape).
  static LeafToDisk closedForm(const DiskInShape& disk, const fcl::Cylinder<S>& cylinder,
                               double scale) {
    const CylinderTarget cylinder_target = target(cylinder);
    const double h = cylinder_target.half_length;
    const auto against_cap = [&](double side) {
      return diskAgainstFlatEnd(disk, cylinder_target, FlatEnd{side * h, cylinder_target.radius},
                                scale);
    };
    const double centre_side = disk.c.z() < 0.0 ? -1.0 : 1.0;
    const bool beyond_cap = std::abs(disk.c.z()) > h;
    if (beyond_cap) {
      const LeafToDisk cap = against_cap(centre_side);
      if (cap.exact) return cap;
    }
    const DiskShapeSolution wall = solveDiskCapsule(disk, cylinder_target.radius, h);
    if (std::abs(wall.q.z()) <= h) return exactLeafOf(wall);
    const double wall_side = wall.q.z() < 0.0 ? -1.0 : 1.0;
    if (!beyond_cap || wall_side != centre_side) return against_cap(wall_side);
    return LeafToDisk{};
  }

  /// The directions among which the shortest separating translation lies
  /// (shortestSeparation adds the disk's normals and both signs), so the contact's
  /// depth is the exact penetration depth. The cylinder's support, h(-w) =
  /// radius |P_z w| + half_length |w_z| - ..., is kinked at w = +-z (its caps'
  /// normals) and on the circle w . z = 0 (its two caps tie). Away from both, one
  /// cap is the support and F is the disk-disk F of the disk against that cap:
  /// its candidates (docs/penetration_depth.md, section 2). On the circle F =
  /// h_disk(w) + radius, stationary where the disk's support is normal to the
  /// axis (section 7).
  template <typename Search>
  static void contactDirections(const CylinderTarget& target, const DiskInShape& disk,
                                Search* directions) {
    directions->push_back(Vec3::UnitZ());
    addEdgeLineCandidates(disk, Vec3::Zero(), Vec3::UnitZ(), directions, target.radius);
    for (const FlatEnd& end : target.flatEnds()) addFlatEndCandidates(disk, end, directions);
  }
};

}  // namespace

template <typename S>
struct DiskShapePair<fcl::Cylinder<S>>
    : GenericDiskShapePair<S, fcl::Cylinder<S>, CylinderTraits<S>> {};

}  // namespace internal
}  // namespace fcl_disk

FCL_DISK_INSTANTIATE_DISK_SHAPE_PAIR(fcl::Cylinder)

// Internal: a disk against a shape's circular flat end (a cylinder's cap, a
// cone's base) by the disk-disk solver, certified for the whole shape
// (docs/disk_shape_distance.md, section 4). The end is a disk, and the shape
// lies on one side of its plane, so where the nearest pair of the disk and the
// end is the shape's, the certificate of section 2 along that pair, with the
// shape's support, closes; and a disk meeting the end meets the shape.
#pragma once

#include "../disk_shape_solver.h"
#include "../environment_bounds.h"

namespace fcl_disk {
namespace internal {

/// The end {x^2 + y^2 <= end.radius^2, z = end.z} of `target` (shape frame)
/// against `disk` (orthonormal axes): exact (LeafToDisk::exact) with the
/// disk-disk pair when the certificate along it closes to kShapeGapTolerance
/// * scale, or at distance 0 when the disk meets the end; else not exact,
/// with that certificate as its bound.
template <typename Target>
LeafToDisk diskAgainstFlatEnd(const DiskInShape& disk, const Target& target, const FlatEnd& end,
                              double scale) {
  const DiskPairAnswer pair = diskPairWithFlatEnd(disk, end);
  if (pair.distance == 0.0) return certifiedOrBound(0.0, 0.0, pair.q, pair.q, scale);
  const Vec3 w = pair.p - pair.q;
  return certifiedOrBoundAlong(leastAlong(target, w) - disk.support(w), w.norm(), pair.distance,
                               pair.q, pair.p, scale);
}

/// `disk` wholly beyond the plane of `end` (on the side away from the shape),
/// for a shape that lies over its end (its projection onto the end's plane is
/// the end: a cylinder's caps, a cone's base). Every point beyond the plane
/// then has its nearest point of the shape on the end (a shape point moved
/// along the plane's normal onto the end comes nearer), so the disk-end
/// pair's distance and its own certificate are the shape's, and no
/// certificate with the shape's support is needed: exact when the pair's
/// closes to kShapeGapTolerance * scale, else not, with it as the bound.
inline LeafToDisk diskBeyondFlatEnd(const DiskInShape& disk, const FlatEnd& end, double scale) {
  const DiskPairAnswer pair = diskPairWithFlatEnd(disk, end);
  return certifiedOrBound(pair.lower_bound, pair.distance, pair.q, pair.p, scale);
}

}  // namespace internal
}  // namespace fcl_disk

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
  const double lower = certificateAlong(target, disk, 0.0, pair.p - pair.q);
  return certifiedOrBound(lower, pair.distance, pair.q, pair.p, scale);
}

}  // namespace internal
}  // namespace fcl_disk

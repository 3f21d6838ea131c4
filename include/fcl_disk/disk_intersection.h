// Closed-form disk-disk intersection test, used by fcl::collide on disk pairs.
#pragma once

#include <fcl_disk/disk_pair.h>

namespace fcl_disk {

/// Contact between two intersecting disks, in the world frame, following FCL's
/// convention for fcl::Contact: `normal` points from disk 1 towards disk 2 and
/// translating disk 2 by penetration_depth * normal (or disk 1 by the opposite)
/// separates them (to touching).
///
/// penetration_depth is the exact penetration depth PD, the length of the
/// shortest separating translation, and normal its direction: diskPenetration()
/// (docs/penetration_depth.md). It is 0 when the disks merely touch, and for
/// coplanar overlapping disks (a shift along the common normal separates
/// them; normal n1 then, a tie-break).
template <typename S>
struct DiskContact {
  fcl::Vector3<S> pos{fcl::Vector3<S>::Zero()};     ///< a point on both disks (see below).
  fcl::Vector3<S> normal{fcl::Vector3<S>::UnitZ()};  ///< unit, from disk 1 towards disk 2.
  S penetration_depth{0};                            ///< >= 0.
};

/// Whether two disks share a point (closed disks: touching counts), and if so a
/// contact. Frames, units and pose convention as in exactDiskDistance().
///
/// pos: crossing planes -> the midpoint of the common segment of the two chords
/// on the planes' intersection line; coplanar -> the midpoint of the overlap of
/// the two disks along the line of centres (the common centre if concentric).
/// Decision tolerance: disks closer than 1e-13 * (r1 + r2 + |c1 - c2|) count as
/// touching (a touching pair built exactly in one frame touches only to rounding
/// in another); such a pair may be reported either way.
/// Returns false (contact untouched) when they are apart or the input describes
/// no disk pair (a radius rejected by isValidDiskRadius(), a pose rejected by
/// isValidDiskPose(): NaN, infinite, out of range, not orthonormal).
template <typename S>
bool intersectDisks(S r1, const fcl::Transform3<S>& X_W1, S r2, const fcl::Transform3<S>& X_W2,
                    DiskContact<S>* contact = nullptr);

// Explicit instantiations, compiled into libfcl_disk (hidden from the API reference).
/// @cond
extern template bool intersectDisks(float, const fcl::Transform3<float>&, float,
                                    const fcl::Transform3<float>&, DiskContact<float>*);
extern template bool intersectDisks(double, const fcl::Transform3<double>&, double,
                                    const fcl::Transform3<double>&, DiskContact<double>*);
/// @endcond

}  // namespace fcl_disk

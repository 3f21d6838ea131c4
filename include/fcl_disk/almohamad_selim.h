// The disk-disk distance algorithm of Almohamad & Selim (1994), as published,
// with the errata of its Appendix A fixed. See docs/almohamad_selim.md.
#pragma once

#include <fcl_disk/disk_pair.h>

namespace fcl_disk {

/// Disk-disk "distance" by Lemma 1 / Section V of Almohamad & Selim, Univ. of
/// Michigan IOE Tech. Report 94-8 (1994), in their formulation (7).
///
/// Frames: disk i is centred at the origin of its frame, lies in the local XY
/// plane with normal +Z, and has pose X_Wi in the world frame W; points are
/// returned in W. Units: the caller's length unit.
///
/// Guarantee: the returned pair lies on the disks and distance = |p_W2 - p_W1|,
/// so distance is an UPPER BOUND on the true distance. It is exact only where
/// Lemma 1 holds (coaxial stacks, coplanar pairs, some perpendicular and
/// interlocked configurations); elsewhere it errs: on random disjoint pairs the
/// relative error has median ~0.3%, 90th percentile ~8% and no bound (worst seen
/// > 200x); docs/almohamad_selim.md has the measurement and counterexamples.
/// lower_bound carries the duality certificate, so certifiedGap() shows the error.
/// Use exactDiskDistance() unless you are measuring the report itself.
///
/// Computed in double (float inputs are promoted, results rounded to S); the
/// distance is measured on the rounded pair. iterations = 0 (closed form).
/// feature is set from where the returned points lie: distance 0 ->
/// intersecting; both on rims -> rim_rim; p_W1 strictly inside disk 1 ->
/// face1_rim2; else rim1_face2. The pair is not optimal in general, so the
/// parallelism to n1 / n2 that the enum describes for the exact solver need
/// not hold.
/// Tie-breaks: a point on a disk's axis takes the in-plane case of Prop. 1/2
/// (nearest point = its projection, no division by zero); Steps 3/4 compare
/// with the report's strict `<`, so an exact tie goes to Step 4.
/// Invalid input (a radius rejected by isValidDiskRadius(), a pose rejected by
/// isValidDiskPose(): NaN, infinite, out of range, not orthonormal) gives NaN
/// distance, lower_bound and points (feature unspecified); it never crashes.
template <typename S>
DiskDistanceResult<S> almohamadSelimDiskDistance(S r1, const fcl::Transform3<S>& X_W1, S r2,
                                                 const fcl::Transform3<S>& X_W2);

// Explicit instantiations, compiled into libfcl_disk (hidden from the API reference).
/// @cond
extern template DiskDistanceResult<float> almohamadSelimDiskDistance(
    float, const fcl::Transform3<float>&, float, const fcl::Transform3<float>&);
extern template DiskDistanceResult<double> almohamadSelimDiskDistance(
    double, const fcl::Transform3<double>&, double, const fcl::Transform3<double>&);
/// @endcond

}  // namespace fcl_disk

// Internal entries of the disk-disk penetration depth: for callers that decided
// the overlap already (the hook, intersectDisks), and the candidate directions
// for the disk-shape pairs whose shape contains disks (a cylinder's caps).
#pragma once

#include <functional>

#include "fcl_disk/disk_penetration.h"
#include "pair_in_frame1.h"

namespace fcl_disk {
namespace internal {

/// Candidates of a pair known to share a point are skipped only when they are
/// certainly worse than the best found plus this many scene sizes: far above
/// the rounding of the bounds that rule them out, far below any depth
/// difference that matters (the depth's promise is 1e-12 of the scene).
constexpr double kPrunedCandidateSlack = 1e-12;

/// Where a bound may rule out arcs of a rim for the roots of a candidate
/// equation, arcs wider than this (radians) are halved before their roots are
/// isolated, so that most of the circle is ruled out whole (on the disk-disk
/// search 0.5 and 1 rad cost the same to 2%, 0.125 and 2 rad 8% more).
constexpr double kPrunedArcWidth = 0.5;

/// diskPenetration() of a valid pair already known to intersect as
/// intersectDisks() decides (intersectDisks() found the common point, or
/// exactDiskDistance() answered `intersecting`): the overlap test is not
/// taken again.
template <typename S>
DiskSignedDistanceResult<S> penetrationOfIntersecting(S r1, const fcl::Transform3<S>& X_W1, S r2,
                                                      const fcl::Transform3<S>& X_W2);

/// Calls visit(w) for every direction of the candidate set of
/// docs/penetration_depth.md section 2 for the pair (disk 1's frame, lengths
/// in scene sizes): the four normals and the directions of every rim pair
/// Q's roots give. A minimiser of F(w) = h1(w) + h2(-w) over the unit sphere
/// is among them (up to sign: callers evaluate both). With `bound` (scene
/// sizes of the unit pair), the caller's F is known to have a minimiser of
/// value >= 0 where it equals this pair's F, and only the rim pairs that may
/// beat bound() are visited (docs/penetration_depth.md, section 2).
void forEachDiskPairPenetrationCandidate(const PairInFrame1& unit_pair,
                                         const std::function<void(const Vec3&)>& visit,
                                         const std::function<double()>* bound = nullptr);

}  // namespace internal
}  // namespace fcl_disk

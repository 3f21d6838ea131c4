// Internal: the candidate directions of the disk-disk penetration depth, for the
// disk-shape pairs whose shape contains disks (a cylinder's caps).
#pragma once

#include <functional>

#include "pair_in_frame1.h"

namespace fcl_disk {
namespace internal {

/// Calls visit(w) for every direction of the candidate set of
/// docs/penetration_depth.md section 2 for the pair (disk 1's frame, lengths
/// in scene sizes): the four normals and the directions of every rim pair
/// Q's roots give. A minimiser of F(w) = h1(w) + h2(-w) over the unit sphere
/// is among them (up to sign: callers evaluate both).
void forEachDiskPairPenetrationCandidate(const PairInFrame1& unit_pair,
                                         const std::function<void(const Vec3&)>& visit);

}  // namespace internal
}  // namespace fcl_disk

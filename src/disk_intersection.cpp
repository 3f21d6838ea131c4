// Closed-form disk-disk intersection test (include/fcl_disk/disk_intersection.h,
// docs/exact_distance.md section 3); the contact's depth and normal are the
// exact penetration (docs/penetration_depth.md).
#include "fcl_disk/disk_intersection.h"

#include <algorithm>
#include <cmath>

#include "disk_penetration_candidates.h"
#include "fcl_disk/disk_penetration.h"
#include "pair_in_frame1.h"

namespace fcl_disk {

template <typename S>
bool intersectDisks(S r1, const fcl::Transform3<S>& X_W1, S r2, const fcl::Transform3<S>& X_W2,
                    DiskContact<S>* contact) {
  const internal::DiskPairCheck check = internal::checkDiskPair(r1, X_W1, r2, X_W2);
  if (!check.valid) return false;
  const internal::Mat3 R_W1 = internal::diskRotationInDouble(X_W1, check.orthonormal1);
  const auto pair = internal::PairInFrame1::fromWorld(r1, X_W1, R_W1, r2, X_W2, check);
  const auto common = internal::commonPoint(pair);
  if (!common) return false;
  if (contact) {
    contact->pos = (X_W1.translation().template cast<double>() + R_W1 * *common).template cast<S>();
    const DiskSignedDistanceResult<S> penetration =
        internal::penetrationOfIntersecting(r1, X_W1, r2, X_W2);
    contact->normal = penetration.direction;
    // A touching pair (common point within the tolerance) may have min F
    // slightly below 0: a separation of rounding size, depth 0.
    contact->penetration_depth = std::max(-penetration.signed_distance, S(0));
  }
  return true;
}

template bool intersectDisks(float, const fcl::Transform3<float>&, float,
                             const fcl::Transform3<float>&, DiskContact<float>*);
template bool intersectDisks(double, const fcl::Transform3<double>&, double,
                             const fcl::Transform3<double>&, DiskContact<double>*);

}  // namespace fcl_disk

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
namespace {
/// The centre-line certificate proves a pair apart beyond this many touching
/// tolerances: commonPoint's slack joins disks up to about 2.2 tolerances
/// apart (nearly coplanar ones: 2 in height, 1 in the plane), and the bound's
/// rounding is a few eps * scale against the tolerance's 450, so at 4 it never
/// decides a pair commonPoint calls touching.
constexpr double kApartTolerances = 4.0;
}  // namespace

template <typename S>
bool intersectDisks(S r1, const fcl::Transform3<S>& X_W1, S r2, const fcl::Transform3<S>& X_W2,
                    DiskContact<S>* contact) {
  const internal::DiskPairCheck check = internal::checkDiskPair(r1, X_W1, r2, X_W2);
  if (!check.valid) return false;
  // Most pairs a broadphase hands over are apart, and the certificate along
  // the centres' line proves it before the frame change, where commonPoint
  // would find no common point either (kApartTolerances).
  const internal::CentreLineBound bound = internal::centreLineBound(r1, X_W1, r2, X_W2);
  if (bound.exceeds(kApartTolerances * internal::kTouchingTolerance * bound.scale)) return false;
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

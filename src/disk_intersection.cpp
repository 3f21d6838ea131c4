// Closed-form disk-disk intersection (see include/fcl_disk/disk_intersection.h
// and docs/exact_distance.md, section 3).
#include "fcl_disk/disk_intersection.h"

#include <algorithm>
#include <cmath>

#include "pair_in_frame1.h"

namespace fcl_disk {

namespace {

using internal::PairInFrame1;
using internal::Vec3;

/// The cheapest translation along a plane normal that takes one disk off the
/// other's plane. In frame 1, disk 2 spans heights [cz - r2 s, cz + r2 s]:
/// moving it up by r2 s - cz or down by cz + r2 s clears plane 1. Seen from
/// disk 2, disk 1 spans [h - r1 s, h + r1 s] over plane 2 with h = -n.c.
/// Returns the depth and the normal (frame 1, from disk 1 towards disk 2).
std::pair<double, Vec3> separatingTranslation(const PairInFrame1& pair) {
  const double cz = pair.c.z();
  const double up = pair.r2 * pair.s - cz, down = cz + pair.r2 * pair.s;
  double depth = std::min(up, down);
  Vec3 normal = up <= down ? Vec3::UnitZ() : Vec3(-Vec3::UnitZ());

  const Vec3 n2 = pair.R.col(2);
  const double h = -n2.dot(pair.c);  // height of disk 1's centre over plane 2
  // Moving disk 1 down (-n2) by h + r1 s puts it below plane 2: normal +n2.
  const double disk1_down = h + pair.r1 * pair.s, disk1_up = pair.r1 * pair.s - h;
  if (disk1_down < depth) depth = disk1_down, normal = n2;
  if (disk1_up < depth) depth = disk1_up, normal = -n2;
  return {std::max(depth, 0.0), normal};
}

}  // namespace

template <typename S>
bool intersectDisks(S r1, const fcl::Transform3<S>& X_W1, S r2, const fcl::Transform3<S>& X_W2,
                    DiskContact<S>* contact) {
  if (!internal::isValidDiskPair(r1, X_W1, r2, X_W2)) return false;
  const PairInFrame1 pair = PairInFrame1::fromWorld(r1, X_W1, r2, X_W2);
  const auto common = internal::commonPoint(pair);
  if (!common) return false;
  if (contact) {
    const internal::Mat3 R_W1 = X_W1.linear().template cast<double>();
    const auto [depth, normal] = separatingTranslation(pair);
    contact->pos = (X_W1.translation().template cast<double>() + R_W1 * *common).template cast<S>();
    // Normalised: with a rotation accepted within kRotationDefectTolerance, a
    // column of R_W1 R is unit only to a few times that defect (|normal| - 1 =
    // 1.8e-7 at a defect of 9e-8; corpus: regression-normal-defect), and
    // FCL's users take contact normals to be unit.
    contact->normal = (R_W1 * normal).normalized().template cast<S>();
    contact->penetration_depth = S(depth);
  }
  return true;
}

template bool intersectDisks(float, const fcl::Transform3<float>&, float,
                             const fcl::Transform3<float>&, DiskContact<float>*);
template bool intersectDisks(double, const fcl::Transform3<double>&, double,
                             const fcl::Transform3<double>&, DiskContact<double>*);

}  // namespace fcl_disk

// Types shared by the disk-disk solvers, and the convexity certificate.
// Notation follows docs/exact_distance.md: disk i has centre c_i, unit normal n_i,
// in-plane unit axes u_i, v_i (the first two columns of its rotation) and radius r_i.
#pragma once

#include <fcl/common/types.h>

#include <algorithm>
#include <cmath>

namespace fcl_disk {

/// Which features of the two disks the nearest points lie on.
enum class DiskPairFeature {
  intersecting,    ///< the disks share a point; distance 0, p_W1 == p_W2.
  face1_rim2,      ///< p_W1 inside disk 1's face, p_W2 on disk 2's rim (or face); p_W2 - p_W1 is parallel to n1.
  rim1_face2,      ///< p_W1 on disk 1's rim, p_W2 inside disk 2's face; p_W2 - p_W1 is parallel to n2.
  rim_rim,         ///< both points on the rims (the circle-circle case).
};

/// Distance between two disks and a pair of nearest points.
template <typename S>
struct DiskDistanceResult {
  S distance{0};                                    ///< |p_W2 - p_W1| >= 0; 0 when the disks intersect.
  fcl::Vector3<S> p_W1{fcl::Vector3<S>::Zero()};    ///< point of disk 1, world frame.
  fcl::Vector3<S> p_W2{fcl::Vector3<S>::Zero()};    ///< point of disk 2, world frame.
  /// A lower bound on the true distance from the duality certificate
  /// (dualLowerBound at w = (p_W2 - p_W1)/distance, or at a face normal). For exact
  /// arithmetic, lower_bound <= true distance <= distance, so certifiedGap() is an
  /// error bar the caller can check; it is 0 up to rounding for the exact solver.
  S lower_bound{0};
  DiskPairFeature feature{DiskPairFeature::intersecting};
  int iterations{0};  ///< Newton iterations used (rim-rim case of the exact solver), else 0.

  S certifiedGap() const { return distance - lower_bound; }
};

/// Length of the projection of w onto the plane of the disk with rotation R
/// (|P w| = sqrt((u.w)^2 + (v.w)^2)), computed from the in-plane axes because
/// sqrt(1 - (n.w)^2) loses all digits when w is nearly parallel to n.
template <typename S>
S inPlaneNorm(const fcl::Matrix3<S>& R, const fcl::Vector3<S>& w) {
  const S a = R.col(0).dot(w);
  const S b = R.col(1).dot(w);
  return std::sqrt(a * a + b * b);
}

/// The convexity (duality) certificate: for any unit direction w,
///   d(K1, K2) >= w.(c2 - c1) - r1 |P1 w| - r2 |P2 w|,
/// because the left-hand side's support-function difference bounds every
/// separation along w (docs/exact_distance.md, section 2). Returns the bound
/// clamped at 0 (distances are non-negative).
/// Frames: X_W1, X_W2 are the poses of the disks in the world frame W; w is in W.
template <typename S>
S dualLowerBound(const fcl::Vector3<S>& w, S r1, const fcl::Transform3<S>& X_W1, S r2,
                 const fcl::Transform3<S>& X_W2) {
  const fcl::Vector3<S> c1_to_c2 = X_W2.translation() - X_W1.translation();
  const S bound = w.dot(c1_to_c2) - r1 * inPlaneNorm<S>(X_W1.linear(), w) -
                  r2 * inPlaneNorm<S>(X_W2.linear(), w);
  return std::max(bound, S(0));
}

}  // namespace fcl_disk

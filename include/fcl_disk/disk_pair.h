// Types shared by the disk-disk solvers, and the convexity certificate.
// Notation follows docs/exact_distance.md: disk i has centre c_i, unit normal n_i,
// in-plane unit axes u_i, v_i (the first two columns of its rotation) and radius r_i.
#pragma once

#include <fcl/common/types.h>

// The headers use C++17 (inline variables, if constexpr). Debian's fcl.pc puts
// -std=c++11 in pkg-config's flags: add -std=c++17 after them.
#if __cplusplus < 201703L
#error "fcl_disk needs C++17 (-std=c++17; with pkg-config, after $(pkg-config --cflags fcl_disk))"
#endif

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

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
  DiskPairFeature feature{DiskPairFeature::intersecting};  ///< where p_W1 and p_W2 lie.
  int iterations{0};  ///< Newton iterations used (rim-rim case of the exact solver), else 0.

  /// distance - lower_bound: how far the returned distance can exceed the true one.
  S certifiedGap() const { return distance - lower_bound; }
};

/// How far a disk pose's rotation may be from orthonormal, max_ij |(R^T R - I)_ij|,
/// and still be accepted. Far above the rounding of any rotation built or composed
/// in S (a few ulps, growing by about an ulp per composition: 1e-6 is ~1e10 double
/// ulps and covers rotations built in float and widened to double; 1e-4 is ~1000
/// float ulps), far below a deliberate scale or shear, which would turn the disk
/// into an ellipse. A disk is its centre, unit normal and radius: the disk-disk
/// solvers (exactDiskDistance, intersectDisks, diskPenetration) answer for the
/// disk with the normal R e_z / |R e_z|, replacing a rotation further than 1e-13
/// from orthonormal (every float rotation widened to double) by the orthonormal
/// frame with that normal. almohamadSelimDiskDistance and the disk-shape solvers
/// use an accepted rotation as given (R^T as its inverse), so their distances
/// may differ by about defect * (r1 + r2 + |c1 - c2|) beyond their stated bounds.
template <typename S>
constexpr S kRotationDefectTolerance = std::is_same<S, float>::value ? S(1e-4) : S(1e-6);

/// The lengths fcl_disk answers for: radii in [kMinDiskRadius, kMaxDiskLength] and
/// pose translations whose coordinates are at most kMaxDiskLength in magnitude.
/// The solvers work in double and square lengths (the distance through
/// |x - q|^2 / 2, tolerances through 1e-13 * scale): within 1e-100..1e100 every
/// square and every tolerance is a normal double, so the relative guarantees
/// hold; beyond, squares overflow to inf or underflow into denormals and the
/// answer would be a made-up inf or 0. In float the limits keep every result
/// (|c1 - c2| + r1 + r2 < 6e37) and point a normal, finite float. Out of range
/// counts as invalid input: NaN distance, no contact (docs/robustness.md).
template <typename S>
constexpr S kMaxDiskLength = std::is_same<S, float>::value ? S(1e37) : S(1e100);
/// The smallest radius fcl_disk answers for (see kMaxDiskLength).
template <typename S>
constexpr S kMinDiskRadius = std::is_same<S, float>::value ? S(1e-37) : S(1e-100);

/// Whether r can be a disk's radius: in [kMinDiskRadius, kMaxDiskLength] (NaN is not).
template <typename S>
constexpr bool isValidDiskRadius(S r) {
  return r >= kMinDiskRadius<S> && r <= kMaxDiskLength<S>;
}

/// @cond
namespace internal {

/// isValidDiskPose's verdict, and whether the rotation is also within
/// `orthonormal_tolerance` of orthonormal (max_ij |(R^T R - I)_ij|): one pass.
struct DiskPoseCheck {
  bool valid;        ///< isValidDiskPose's verdict.
  bool orthonormal;  ///< the rotation is within the tolerance asked of orthonormal.
};

/// isValidDiskPose's rule, one entry at a time: the translation's range and the
/// six distinct entries of R^T R - I, written without branches (NaN fails every
/// comparison). The checks' form wherever SSE2 is missing, and the reference
/// test_robustness compares the two-lane form with.
template <typename S>
inline DiskPoseCheck checkDiskPoseOneByOne(const fcl::Transform3<S>& X_WD,
                                           S orthonormal_tolerance) {
  const auto& M = X_WD.matrix();
  const auto dot = [&M](int i, int j) {
    return M(0, i) * M(0, j) + M(1, i) * M(1, j) + M(2, i) * M(2, j);
  };
  const S defects[6] = {dot(0, 0) - S(1), dot(1, 1) - S(1), dot(2, 2) - S(1),
                        dot(0, 1),        dot(0, 2),        dot(1, 2)};
  bool valid = std::abs(M(0, 3)) <= kMaxDiskLength<S>;
  valid &= std::abs(M(1, 3)) <= kMaxDiskLength<S>;
  valid &= std::abs(M(2, 3)) <= kMaxDiskLength<S>;
  S largest = 0;  // NaN is caught by `valid`; `orthonormal` matters only if valid
  for (const S defect : defects) {
    valid &= std::abs(defect) <= kRotationDefectTolerance<S>;
    largest = std::max(largest, std::abs(defect));
  }
  return {valid, largest <= orthonormal_tolerance};
}

/// checkDiskPose of two poses at once: both valid, and each one's orthonormal
/// verdict (which matters only when both are valid).
struct TwoPoseCheck {
  bool valid;  ///< both poses pass isValidDiskPose's rule.
  bool orthonormal_a, orthonormal_b;
};

#if defined(__SSE2__)
/// SSE2's vectors as checkTwoPosesTwoLanes uses them: lane 0 holds an entry of
/// one pose, lane 1 the same entry of the other (a float vector's lanes 2 and
/// 3 hold 0, which passes every test and is never read).
template <typename S>
struct PoseLanes;
template <>
struct PoseLanes<double> {
  using V = __m128d;
  static V both(const double* a, const double* b) { return _mm_loadh_pd(_mm_load_sd(a), b); }
  static V splat(double x) { return _mm_set1_pd(x); }
  static V mul(V x, V y) { return _mm_mul_pd(x, y); }
  static V add(V x, V y) { return _mm_add_pd(x, y); }
  static V sub(V x, V y) { return _mm_sub_pd(x, y); }
  static V max(V x, V y) { return _mm_max_pd(x, y); }
  static V both_and(V x, V y) { return _mm_and_pd(x, y); }
  static V magnitude(V x) {
    return _mm_and_pd(x, _mm_castsi128_pd(_mm_set1_epi64x(0x7fffffffffffffffLL)));
  }
  static V within(V x, V bound) { return _mm_cmple_pd(x, bound); }  // false on NaN
  static int lanes(V mask) { return _mm_movemask_pd(mask); }       // bit i: lane i
};
template <>
struct PoseLanes<float> {
  using V = __m128;
  static V both(const float* a, const float* b) {
    return _mm_unpacklo_ps(_mm_load_ss(a), _mm_load_ss(b));
  }
  static V splat(float x) { return _mm_set1_ps(x); }
  static V mul(V x, V y) { return _mm_mul_ps(x, y); }
  static V add(V x, V y) { return _mm_add_ps(x, y); }
  static V sub(V x, V y) { return _mm_sub_ps(x, y); }
  static V max(V x, V y) { return _mm_max_ps(x, y); }
  static V both_and(V x, V y) { return _mm_and_ps(x, y); }
  static V magnitude(V x) { return _mm_and_ps(x, _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff))); }
  static V within(V x, V bound) { return _mm_cmple_ps(x, bound); }
  static int lanes(V mask) { return _mm_movemask_ps(mask) & 3; }
};

/// checkTwoPoses with SSE2 (double or float): the lanes hold the two poses,
/// each lane computing the rule of checkDiskPoseOneByOne for its pose in S,
/// with the same products summed in the same order (the same defects to the
/// bit, so the same verdicts: test_robustness compares the two). A query
/// checks both of its poses, and one pass over both takes fewer instructions
/// than a pass over each (a disk-box query 1075 -> 1024 instructions in
/// double, 1327 -> 1239 in float: bench/disk_shape_calls box double|float 5
/// under callgrind).
/// a, b: the 4x4 matrices, column-major (M(k, i) = m[4 i + k]).
template <typename S>
[[gnu::always_inline]] inline TwoPoseCheck checkTwoPosesTwoLanes(const S* a, const S* b,
                                                                 S orthonormal_tolerance) {
  using L = PoseLanes<S>;
  using V = typename L::V;
  const auto both = [a, b](int k) { return L::both(a + k, b + k); };
  const V m00 = both(0), m10 = both(1), m20 = both(2);
  const V m01 = both(4), m11 = both(5), m21 = both(6);
  const V m02 = both(8), m12 = both(9), m22 = both(10);
  // Column i . column j, summed row 0, 1, 2 as the rule sums it.
  const auto dot = [](V x0, V x1, V x2, V y0, V y1, V y2) {
    return L::add(L::add(L::mul(x0, y0), L::mul(x1, y1)), L::mul(x2, y2));
  };
  const V one = L::splat(S(1));
  const V d00 = L::magnitude(L::sub(dot(m00, m10, m20, m00, m10, m20), one));
  const V d11 = L::magnitude(L::sub(dot(m01, m11, m21, m01, m11, m21), one));
  const V d22 = L::magnitude(L::sub(dot(m02, m12, m22, m02, m12, m22), one));
  const V d01 = L::magnitude(dot(m00, m10, m20, m01, m11, m21));
  const V d02 = L::magnitude(dot(m00, m10, m20, m02, m12, m22));
  const V d12 = L::magnitude(dot(m01, m11, m21, m02, m12, m22));
  // Valid: every defect within kRotationDefectTolerance and every translation
  // coordinate within kMaxDiskLength (<= fails on NaN).
  const V rotation_bound = L::splat(kRotationDefectTolerance<S>);
  const V length = L::splat(kMaxDiskLength<S>);
  V valid = L::both_and(L::within(d00, rotation_bound), L::within(d11, rotation_bound));
  valid = L::both_and(valid,
                      L::both_and(L::within(d22, rotation_bound), L::within(d01, rotation_bound)));
  valid = L::both_and(valid,
                      L::both_and(L::within(d02, rotation_bound), L::within(d12, rotation_bound)));
  for (int k = 12; k < 15; ++k) {
    valid = L::both_and(valid, L::within(L::magnitude(both(k)), length));
  }
  // Orthonormal: the largest defect within the tolerance (the maxima are
  // NaN-free where the pose is valid, the only case where they are read).
  const V largest = L::max(L::max(L::max(d00, d11), L::max(d22, d01)), L::max(d02, d12));
  const int orthonormal = L::lanes(L::within(largest, L::splat(orthonormal_tolerance)));
  return {L::lanes(valid) == 3, (orthonormal & 1) != 0, (orthonormal & 2) != 0};
}
#endif

/// isValidDiskPose's verdict and whether the rotation is within
/// `orthonormal_tolerance` of orthonormal, in one pass over the pose: with SSE2
/// checkTwoPosesTwoLanes with the pose in both lanes.
template <typename S>
inline DiskPoseCheck checkDiskPose(const fcl::Transform3<S>& X_WD, S orthonormal_tolerance) {
#if defined(__SSE2__)
  if constexpr (std::is_same_v<S, double> || std::is_same_v<S, float>) {
    using Matrix = std::decay_t<decltype(X_WD.matrix())>;
    static_assert(Matrix::RowsAtCompileTime == 4 && !Matrix::IsRowMajor,
                  "checkTwoPosesTwoLanes reads column-major 4x4 matrices");
    const S* m = X_WD.matrix().data();
    const TwoPoseCheck check = checkTwoPosesTwoLanes(m, m, orthonormal_tolerance);
    return {check.valid, check.orthonormal_a};
  }
#endif
  return checkDiskPoseOneByOne(X_WD, orthonormal_tolerance);
}

/// checkDiskPose of X_A and X_B, in one pass where SSE2 allows.
template <typename S>
[[gnu::always_inline]] inline TwoPoseCheck checkTwoPoses(const fcl::Transform3<S>& X_A,
                                                         const fcl::Transform3<S>& X_B,
                                                         S orthonormal_tolerance) {
#if defined(__SSE2__)
  if constexpr (std::is_same_v<S, double> || std::is_same_v<S, float>) {
    using Matrix = std::decay_t<decltype(X_A.matrix())>;
    static_assert(Matrix::RowsAtCompileTime == 4 && !Matrix::IsRowMajor,
                  "checkTwoPosesTwoLanes reads column-major 4x4 matrices");
    return checkTwoPosesTwoLanes(X_A.matrix().data(), X_B.matrix().data(), orthonormal_tolerance);
  }
#endif
  const DiskPoseCheck a = checkDiskPoseOneByOne(X_A, orthonormal_tolerance);
  const DiskPoseCheck b = checkDiskPoseOneByOne(X_B, orthonormal_tolerance);
  return {a.valid && b.valid, a.orthonormal, b.orthonormal};
}

/// The disk's pose and radius, and another shape's pose (a primitive's, a
/// mesh's, an octree's), describe a pair (the shape's own dimensions are the
/// pair's to check). The other pose obeys the disk pose rule: finite, within
/// kMaxDiskLength, rotation orthonormal to kRotationDefectTolerance. Both poses
/// in one pass (checkTwoPoses). Inlined whole, for the closed forms that need no
/// more (the sphere, the halfspace, the plane): only the verdict they use is
/// then computed.
template <typename S>
[[gnu::always_inline]] inline bool isValidDiskAndShapePose(S radius,
                                                           const fcl::Transform3<S>& X_WD,
                                                           const fcl::Transform3<S>& X_WS) {
  return isValidDiskRadius(radius) && checkTwoPoses(X_WD, X_WS, S(0)).valid;
}
}  // namespace internal
/// @endcond

/// Whether X_WD can be a disk's pose: a translation within kMaxDiskLength in
/// every coordinate (so finite) and a rotation within
/// kRotationDefectTolerance of orthonormal (reflections, det = -1, are accepted:
/// the reflected disk is the same set). Every fcl_disk query on a disk whose pose
/// fails this returns a NaN distance and no contact (docs/robustness.md): NaN or
/// infinite input has no meaningful answer, and a non-orthonormal rotation does
/// not describe a disk.
template <typename S>
inline bool isValidDiskPose(const fcl::Transform3<S>& X_WD) {
  return internal::checkDiskPose(X_WD, S(0)).valid;
}

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

// Internal: a disk pair expressed in disk 1's frame, and the closed-form pieces
// shared by the exact solver and the intersection test. Notation as in
// docs/exact_distance.md: disk 1 is {z = 0, x^2 + y^2 <= r1^2}; disk 2 has centre
// c, rotation R = [u v n] and radius r2; m = (u_z, v_z) and s = |m| = sin(tilt).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <type_traits>

#include "fcl_disk/disk_pair.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace fcl_disk {
namespace internal {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

/// R^T x for a column-major 3x3 rotation R whose column i starts at
/// R + kStride * i (3: a Mat3; 4: a pose's 4x4 matrix), for one or several x:
/// x_0 (row 0 of R) + x_1 (row 1) + x_2 (row 2), the same sums as Eigen's
/// R.transpose() * x. With SSE2 the x and y coordinates take the two lanes,
/// the rows' first two entries loaded once for every x, and z is apart: fewer
/// instructions than Eigen's three dot products, each summed across lanes.
/// Every query turns its poses into one disk's or the shape's frame with it.
template <int kStride>
class TransposedProduct {
 public:
  [[gnu::always_inline]] explicit TransposedProduct(const double* R) : R_(R) {
#if defined(__SSE2__)
    for (int k = 0; k < 3; ++k) rows_[k] = _mm_loadh_pd(_mm_load_sd(R + k), R + kStride + k);
#endif
  }
  [[gnu::always_inline]] Vec3 operator()(double x0, double x1, double x2) const {
    Vec3 out;
#if defined(__SSE2__)
    const __m128d xy = _mm_add_pd(
        _mm_add_pd(_mm_mul_pd(rows_[0], _mm_set1_pd(x0)), _mm_mul_pd(rows_[1], _mm_set1_pd(x1))),
        _mm_mul_pd(rows_[2], _mm_set1_pd(x2)));
    _mm_storeu_pd(out.data(), xy);
#else
    out.x() = (R_[0] * x0 + R_[1] * x1) + R_[2] * x2;
    out.y() = (R_[kStride] * x0 + R_[kStride + 1] * x1) + R_[kStride + 2] * x2;
#endif
    const double* last = R_ + 2 * kStride;
    out.z() = (last[0] * x0 + last[1] * x1) + last[2] * x2;
    return out;
  }
  [[gnu::always_inline]] Vec3 operator()(const Vec3& x) const {
    return (*this)(x.x(), x.y(), x.z());
  }

 private:
  const double* R_;
#if defined(__SSE2__)
  __m128d rows_[3];
#endif
};

/// The answer to input that describes no disk pair: NaN distance, bound and
/// points, never a finite made-up number.
template <typename S>
DiskDistanceResult<S> nanDistanceResult() {
  const S nan = std::numeric_limits<S>::quiet_NaN();
  DiskDistanceResult<S> result;
  result.distance = nan;
  result.lower_bound = nan;
  result.p_W1.setConstant(nan);
  result.p_W2.setConstant(nan);
  return result;
}

/// A disk is its centre, its unit normal and its radius: the in-plane axes of
/// its pose only parameterise it. Rotations closer to orthonormal than this
/// (max_ij |(R^T R - I)_ij|, a few hundred double ulps: any rotation built or
/// composed in double) are used as given; further ones, accepted up to
/// kRotationDefectTolerance (rotations built in float: ~1e-7), are rebuilt by
/// diskRotationInDouble. Used as given, their defect would stay in every
/// certificate (q - x and the duality bound disagree by defect * scale), leave
/// it open and send the query to the fallback searches.
constexpr double kOrthonormalInDouble = 1e-13;

/// The tolerance checkDiskPose is given to decide whether a rotation in S is
/// used as given: kOrthonormalInDouble in double; in float never (-1), a float
/// rotation widened to double being orthonormal only to float's rounding.
template <typename S>
constexpr S kAsGivenRotationTolerance = std::is_same_v<S, double> ? S(kOrthonormalInDouble) : S(-1);

/// Within this of 1, 1 / sqrt(s) is its Taylor polynomial 1 - e/2 + 3e^2/8
/// (e = s - 1), whose error 5|e|^3/16 is then below 4e-16, under double's
/// rounding of the axes; float rotations (|e| ~ 1e-7) are all within it.
constexpr double kTaylorInverseSqrtRange = 1e-5;

/// 1 / sqrt(s) for s near 1 (squared lengths of axes orthonormal to
/// kRotationDefectTolerance), by the Taylor polynomial where it is exact to
/// rounding: it keeps a square root and a division off the query's latency
/// chain when a pose's axes are rebuilt (every query in float).
inline double inverseSqrtNearOne(double s) {
  const double e = s - 1.0;
  return std::abs(e) <= kTaylorInverseSqrtRange ? 1.0 - e * (0.5 - 0.375 * e)
                                                : 1.0 / std::sqrt(s);
}

/// An orthonormal right-handed frame whose third axis is R's normal n = R e_z
/// / |R e_z| (n normalised by inverseSqrtNearOne). A disk is the same set in
/// every frame with its normal, so the in-plane axes are taken from n alone,
/// by the branch-free basis of Duff et al. ("Building an orthonormal basis,
/// revisited", JCGT 6(1), 2017): with sigma = sign(n_z) and a = -1 / (sigma
/// + n_z) (|sigma + n_z| >= 1),
///   u = (1 + sigma n_x^2 a, sigma n_x n_y a, -sigma n_x),
///   v = (n_x n_y a, sigma + n_y^2 a, -n_y),
/// exact to rounding for a unit n. One division, beside nothing else, and a
/// few products: R's own first axis, orthogonalised against n and
/// normalised, would put a second normalisation and a cross product behind
/// the first on the query's chain (the float disk-disk queries of the report
/// take 1.10x the time pooled that way: docs/exact_distance.md, section 5).
/// Checked by test_robustness's RebuiltFrameIsOrthonormalWithTheNormalKept.
inline Mat3 orthonormalFrameWithNormalOf(const Mat3& R) {
  const Vec3 n = R.col(2) * inverseSqrtNearOne(R.col(2).squaredNorm());
  const double sigma = std::copysign(1.0, n.z());
  const double a = -1.0 / (sigma + n.z());
  const double b = n.x() * n.y() * a;
  Mat3 frame;
  frame.col(0) = Vec3(1.0 + sigma * n.x() * n.x() * a, sigma * b, -sigma * n.x());
  frame.col(1) = Vec3(b, sigma + n.y() * n.y() * a, -n.y());
  frame.col(2) = n;
  return frame;
}

/// The rotation of a valid disk pose in double, orthonormal to double rounding:
/// the pose's own if `orthonormal` (checkDiskPose(X_WD,
/// kAsGivenRotationTolerance<S>).orthonormal), else orthonormalFrameWithNormalOf
/// it. The disk, the set of points at most r from c in the plane through c
/// normal to n, is the same either way.
template <typename S>
inline Mat3 diskRotationInDouble(const Eigen::Transform<S, 3, Eigen::Isometry>& X_WD,
                                 bool orthonormal) {
  Mat3 R = X_WD.linear().template cast<double>();
  if (!orthonormal) R = orthonormalFrameWithNormalOf(R);
  return R;
}

/// The same, checking the pose itself.
template <typename S>
Mat3 diskRotationInDouble(const Eigen::Transform<S, 3, Eigen::Isometry>& X_WD) {
  return diskRotationInDouble(X_WD, checkDiskPose(X_WD, kAsGivenRotationTolerance<S>).orthonormal);
}

/// Whether (r1, X_W1, r2, X_W2) describes two disks (radii accepted by
/// isValidDiskRadius(), poses by isValidDiskPose(); the solvers answer anything
/// else with nanDistanceResult()), and whether each rotation is used as given
/// (checkDiskPose with kAsGivenRotationTolerance): one pass over both poses
/// (checkTwoPoses).
struct DiskPairCheck {
  bool valid;
  bool orthonormal1, orthonormal2;
};

template <typename S>
DiskPairCheck checkDiskPair(S r1, const fcl::Transform3<S>& X_W1, S r2,
                            const fcl::Transform3<S>& X_W2) {
  const TwoPoseCheck poses = checkTwoPoses(X_W1, X_W2, kAsGivenRotationTolerance<S>);
  return {isValidDiskRadius(r1) && isValidDiskRadius(r2) && poses.valid, poses.orthonormal_a,
          poses.orthonormal_b};
}

struct PairInFrame1 {
  Vec3 c;     ///< centre of disk 2 in disk 1's frame.
  Mat3 R;     ///< rotation of disk 2 in disk 1's frame: columns u, v, n.
  double r1;  ///< radius of disk 1.
  double r2;  ///< radius of disk 2.
  Vec2 m;     ///< heights over plane 1 of disk 2's in-plane axes: (u_z, v_z).
  double s;   ///< |m| = sine of the angle between the planes.
  Vec3 c1_in_frame2;  ///< disk 1's centre in disk 2's frame: -R^T c = -(u.c, v.c, n.c).

  /// From world poses; all arithmetic in double, relative to c1 (so a common
  /// translation, however large, costs only the rounding of c2 - c1), with the
  /// rotations of diskRotationInDouble: R_W1 that of X_W1 (map points back
  /// with it), `check` checkDiskPair of the same arguments, valid.
  template <typename S>
  static PairInFrame1 fromWorld(S r1, const Eigen::Transform<S, 3, Eigen::Isometry>& X_W1,
                                const Mat3& R_W1, S r2,
                                const Eigen::Transform<S, 3, Eigen::Isometry>& X_W2,
                                const DiskPairCheck& check) {
    const Vec3 c1_to_c2 =
        X_W2.translation().template cast<double>() - X_W1.translation().template cast<double>();
    // R_W2 as given, or rebuilt (diskRotationInDouble's rule for it).
    const Mat3 R_W2 = check.orthonormal2 ? Mat3(X_W2.linear().template cast<double>())
                                         : orthonormalFrameWithNormalOf(
                                               X_W2.linear().template cast<double>());
    const TransposedProduct<3> to_frame1(R_W1.data());
    Mat3 R;
    R << to_frame1(R_W2.col(0)), to_frame1(R_W2.col(1)), to_frame1(R_W2.col(2));
    return make(to_frame1(c1_to_c2), R, double(r1), double(r2));
  }
  /// The same for a valid pair (checkDiskPair(...).valid).
  template <typename S>
  static PairInFrame1 fromWorld(S r1, const Eigen::Transform<S, 3, Eigen::Isometry>& X_W1, S r2,
                                const Eigen::Transform<S, 3, Eigen::Isometry>& X_W2) {
    const DiskPairCheck check = checkDiskPair(r1, X_W1, r2, X_W2);
    return fromWorld(r1, X_W1, diskRotationInDouble(X_W1, check.orthonormal1), r2, X_W2, check);
  }

  /// The pair from disk 2's centre c and rotation R in frame 1. Always
  /// inlined: it is a few products and a square root, and an inline function's
  /// out-of-line copy is whichever translation unit's the linker keeps (with
  /// the cone's, a cylinder query called it through diskPairWithFlatEnd: 35
  /// instructions more, 1.06x the time).
  [[gnu::always_inline]] static PairInFrame1 make(const Vec3& c, const Mat3& R, double r1,
                                                  double r2) {
    PairInFrame1 pair{c, R, r1, r2, Vec2(R(2, 0), R(2, 1)), 0.0, -(R.transpose() * c)};
    pair.s = std::sqrt(pair.m.squaredNorm());
    return pair;
  }

  /// The length every tolerance scales with: r1 + r2 + |c1 - c2| (> 0). The
  /// problem is homogeneous in length, so tolerances relative to it keep the
  /// solvers' accuracy relative at any scale (1e-9 and 1e9 alike).
  double scale() const { return r1 + r2 + c.norm(); }

  /// The same pair seen from disk 2: disk 1 becomes "disk 2" in disk 2's frame.
  PairInFrame1 swapped() const { return make(c1_in_frame2, R.transpose(), r2, r1); }

  /// Maps a point of disk-2-in-plane coordinates (a, b) to frame 1.
  Vec3 pointOfDisk2(const Vec2& ab) const { return c + ab.x() * R.col(0) + ab.y() * R.col(1); }

  /// How far disk 2 stays off plane 1: |c_z| - r2 s (disk 2 spans heights
  /// c_z +- r2 s), > 0 iff it lies wholly on one side, <= 0 iff it crosses.
  double disk2ClearanceOfPlane1() const { return std::abs(c.z()) - r2 * s; }
  /// The same for disk 1 and plane 2 (c1 is at height -n.c over plane 2).
  double disk1ClearanceOfPlane2() const { return std::abs(c1_in_frame2.z()) - r1 * s; }

  /// The rim point of disk 2 extreme towards plane 1 (lowest if c is above
  /// it): direction -sign(c_z) m / s in disk 2's plane. Requires s > 0.
  Vec3 rimPointTowardsPlane1() const {
    const double side = c.z() > 0.0 ? 1.0 : -1.0;
    return pointOfDisk2((-side * r2 / s) * m);
  }

  /// The in-plane point at signed distance t from c1 towards disk 2's centre's
  /// projection (c1 itself if the centres are coaxial): where coplanar or
  /// parallel overlaps are reported.
  Vec2 pointOnCentreLine(double t) const {
    const double D = std::sqrt(c.x() * c.x() + c.y() * c.y());
    if (D == 0.0) return Vec2::Zero();
    return Vec2(c.x() / D * t, c.y() / D * t);
  }

  /// |P1 w| and |P2 w| (lengths of w's components in the planes), from the axes.
  double inPlane1(const Vec3& w) const { return std::sqrt(w.x() * w.x() + w.y() * w.y()); }
  double inPlane2(const Vec3& w) const {
    const double a = R.col(0).dot(w), b = R.col(1).dot(w);
    return std::sqrt(a * a + b * b);
  }
};

/// Overlap, along the unit direction `dir` through the origin, of disk 1's
/// diameter [-r1, r1] and disk 2's diameter [D - r2, D + r2] (both disks in one
/// plane, disk 2's centre at D * dir): the midpoint parameter, if they overlap.
inline std::optional<double> coplanarOverlapMidpoint(double D, double r1, double r2) {
  const double lo = std::max(-r1, D - r2);
  const double hi = std::min(r1, D + r2);
  if (!(lo <= hi)) return std::nullopt;
  return 0.5 * (lo + hi);
}

/// Disks closer than this many scene sizes count as touching: a touching pair
/// (rim on rim, rim on face) built exactly in some frame is only touching to
/// within rounding in any other, and the rim-rim iteration converges slowly at
/// such degenerate optima. 1e-13 keeps the answer 10x inside the solver's 1e-12
/// promise; the common point is then on both disks to this tolerance.
constexpr double kTouchingTolerance = 1e-13;

/// The certificate of section 2 along the centres' line w = c2 - c1 of a
/// valid pair (checkDiskPair), in the world frame, before any frame change:
/// d >= |w| - (r1 |n1 x w| / |n1| + r2 |n2 x w| / |n2|) / |w|, the disks'
/// supports taken from their normals alone (n_i = R_i e_z), as the solvers
/// take each disk. Kept as its parts so that callers compare it without a
/// division: `length` = |w|, `reach` = the bracket, `scale` = r1 + r2 + |w|.
struct CentreLineBound {
  double length, reach, scale;
  /// Whether the bound exceeds `distance`: |w|^2 - reach > distance |w|.
  bool exceeds(double distance) const { return length * length - reach > distance * length; }
};

template <typename S>
CentreLineBound centreLineBound(S r1, const fcl::Transform3<S>& X_W1, S r2,
                                const fcl::Transform3<S>& X_W2) {
  const Vec3 w =
      X_W2.translation().template cast<double>() - X_W1.translation().template cast<double>();
  const Vec3 n1 = X_W1.linear().col(2).template cast<double>();
  const Vec3 n2 = X_W2.linear().col(2).template cast<double>();
  const double length = w.norm();
  const double reach = double(r1) * std::sqrt(n1.cross(w).squaredNorm() / n1.squaredNorm()) +
                       double(r2) * std::sqrt(n2.cross(w).squaredNorm() / n2.squaredNorm());
  return {length, reach, double(r1) + double(r2) + length};
}

/// The chord where disk 2 meets plane 1: X(tau) = X0 + tau T for |tau| <=
/// half_length, T horizontal and unit to rounding (frame 1).
struct ChordOnPlane1 {
  Vec3 X0;                ///< the chord's midpoint.
  Vec3 T;                 ///< its direction.
  double half_length;
  double tau_nearest_c1;  ///< parameter of the chord's line's point nearest c1.
};

/// For s > 0 and disk 2 crossing plane 1 (|c_z| <= r2 s, up to a slack that
/// the clamping below absorbs). In disk 2's (a, b) coordinates the chord's line
/// is m.(a, b) = -c_z: foot f = -c_z m / s^2 (clamped to the disk), direction
/// perp(m) / s.
inline ChordOnPlane1 chordOfDisk2OnPlane1(const PairInFrame1& pair) {
  Vec2 foot = (-pair.c.z() / (pair.s * pair.s)) * pair.m;
  const double foot_norm = foot.norm();
  if (foot_norm > pair.r2) foot *= pair.r2 / foot_norm;
  const Vec2 along(-pair.m.y() / pair.s, pair.m.x() / pair.s);
  ChordOnPlane1 chord;
  chord.half_length =
      std::sqrt(std::max(0.0, (pair.r2 - foot_norm) * (pair.r2 + foot_norm)));
  chord.X0 = pair.pointOfDisk2(foot);
  chord.T = along.x() * pair.R.col(0) + along.y() * pair.R.col(1);
  const Vec2 T_xy(chord.T.x(), chord.T.y());
  chord.tau_nearest_c1 = -Vec2(chord.X0.x(), chord.X0.y()).dot(T_xy) / T_xy.squaredNorm();
  return chord;
}

/// A point shared by both disks (frame 1), or nullopt if they are apart by more
/// than kTouchingTolerance * pair.scale().
/// Crossing planes: the two chords on the planes' intersection line; parallel
/// planes (s == 0): coplanar overlap along the line of centres.
inline std::optional<Vec3> commonPoint(const PairInFrame1& pair) {
  const double slack = kTouchingTolerance * pair.scale();
  // Each disk lies in the ball of its radius about its centre: centres farther
  // apart than r1 + r2 (+ slack) leave no common point, at the cost of a dot
  // product (squares of lengths stay in double's range over the length range).
  const double reach = pair.r1 + pair.r2 + slack;
  if (!(pair.c.squaredNorm() <= reach * reach)) return std::nullopt;  // also NaN
  const double cz = pair.c.z();
  // Disk 2 spans heights [cz - r2 s, cz + r2 s] over plane 1.
  if (!(std::abs(cz) <= pair.r2 * pair.s + slack)) return std::nullopt;  // also NaN
  // Parallel to within the tolerance (|tilt| * radius <= slack): coplanar. The
  // chord construction below divides by s and is meaningless at rounding level.
  if (!(pair.s * std::max(pair.r1, pair.r2) > slack)) {
    const double D = std::sqrt(pair.c.x() * pair.c.x() + pair.c.y() * pair.c.y());
    const auto t = coplanarOverlapMidpoint(D, pair.r1 + slack, pair.r2);
    if (!t) return std::nullopt;
    const Vec2 point = pair.pointOnCentreLine(std::clamp(*t, -pair.r1, pair.r1));
    return Vec3(point.x(), point.y(), 0.5 * cz);
  }
  // Disk 1 must cross plane 2 too: plane 2 meets plane 1 in a line at
  // distance |n2.c| / s from c1, so a line farther than r1 misses disk 1. This
  // rejects most pairs before the chord's divisions and square roots (the
  // test below, with its slack scaled by s <= 1, is the stricter one).
  if (!(std::abs(pair.c1_in_frame2.z()) <= pair.r1 * pair.s + slack)) return std::nullopt;
  const ChordOnPlane1 chord = chordOfDisk2OnPlane1(pair);
  const Vec2 X0_xy(chord.X0.x(), chord.X0.y());
  const Vec2 T_xy(chord.T.x(), chord.T.y());
  const double offset1 = (X0_xy + chord.tau_nearest_c1 * T_xy).norm();  // line's distance to c1
  if (offset1 > pair.r1 + slack) return std::nullopt;
  const double h1 =
      std::sqrt(std::max(0.0, (pair.r1 - offset1) * (pair.r1 + offset1))) / T_xy.norm();
  const double lo = std::max(-chord.half_length, chord.tau_nearest_c1 - h1);
  const double hi = std::min(chord.half_length, chord.tau_nearest_c1 + h1);
  if (!(lo <= hi + slack)) return std::nullopt;
  const double mid = std::clamp(0.5 * (lo + hi), -chord.half_length, chord.half_length);
  return chord.X0 + mid * chord.T;
}

/// exactDiskDistance's answer for a valid pair given in disk 1's frame (its
/// rotation orthonormal to double rounding): p on disk 1, q on disk 2, both in
/// frame 1; distance |q - p| (0 with p == q where the disks meet) and the
/// certified lower_bound. For the pairs whose other shape has disks for faces
/// (a cylinder's caps). Defined in src/exact_distance.cpp.
struct DiskPairAnswer {
  Vec3 p, q;
  double distance;
  double lower_bound;
};
DiskPairAnswer solveDiskPairInFrame1(const PairInFrame1& pair);

}  // namespace internal
}  // namespace fcl_disk

// What the fuzz targets share besides the decoder: reporting a violated
// invariant, describing the decoded input, and the geometry and tolerances the
// checks are written in (docs/fuzzing.md lists the invariants).
#pragma once

#include <fcl_disk/fcl_disk.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>

#include "fuzz_input.h"
#include "test_tolerances.h"

namespace fcl_disk_fuzz {

using fcl_disk_test::Eps;
using Vector3d = Eigen::Vector3d;
using Pose3d = fcl::Transform3<double>;

/// Every bound the checks take from a header (or from test_tolerances.h, which
/// holds the same bounds with their reasons) is multiplied by this before a
/// result counts as wrong. The headers state their bounds as "about" and "a few
/// ulps"; 2x keeps the checks honest to the documented scale (an O(1) error is
/// still 1e11x over) without reporting the rounding of our own evaluation.
constexpr double kBoundSafetyFactor = 2.0;

/// Rounding of a point stored in S in world coordinates, in ulps of its largest
/// coordinate: each point is within sqrt(3)/2 ulp of its double value, two
/// points within 1.8 ulps of their distance.
constexpr double kStorageUlps = 4.0;

template <typename S>
constexpr bool kIsFloat = std::is_same<S, float>::value;

template <typename S>
const char* scalarName() {
  return kIsFloat<S> ? "float" : "double";
}

// ----------------------------------------------------------------------------
// Describing inputs and reporting violations.

/// max_ij |(R^T R - I)_ij|, evaluated in double (only for finite R).
template <typename S>
double rotationDefect(const fcl::Transform3<S>& X) {
  const Eigen::Matrix3d R = X.linear().template cast<double>();
  return (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
}

inline std::string numberText(double x) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", x);
  return buffer;
}

template <typename Derived>
std::string vectorText(const Eigen::MatrixBase<Derived>& v) {
  std::string out = "(";
  for (int i = 0; i < v.size(); ++i) out += (i ? ", " : "") + numberText(double(v(i)));
  return out + ")";
}

template <typename S>
std::string poseText(const fcl::Transform3<S>& X) {
  std::string out = "R = [";
  for (int row = 0; row < 3; ++row) out += (row ? "; " : "") + vectorText(X.linear().row(row));
  return out + "], c = " + vectorText(X.translation());
}

/// The decoded input, every number in %.17g (exact for double and float).
template <typename S>
std::string describe(const DiskPairInput<S>& in) {
  std::string out = std::string(scalarName<S>()) + ", mode " + modeName(in.mode) +
                    ": r1 = " + numberText(in.r1) + ", X_W1: " + poseText(in.X_W1) +
                    "; r2 = " + numberText(in.r2) + ", X_W2: " + poseText(in.X_W2);
  if (in.known_distance) out += "; known distance " + numberText(*in.known_distance);
  if (!in.rotations_orthonormal && in.posesFinite()) {
    const double defect = std::max(rotationDefect(in.X_W1), rotationDefect(in.X_W2));
    out += "; rotation defect " + numberText(defect) + " (tolerance " +
           numberText(fcl_disk::kRotationDefectTolerance<S>) + ")";
  }
  return out;
}

/// A violated invariant: print it with the decoded input and abort, which
/// libFuzzer records as a crash and saves the input as the reproducer.
/// `details` is a callable returning a string, evaluated only on failure.
template <typename S, typename Details>
void require(bool holds, const char* invariant, const DiskPairInput<S>& in, Details&& details) {
  if (holds) return;
  std::fprintf(stderr, "\nfcl_disk fuzz: invariant violated: %s\n  input: %s\n  %s\n", invariant,
               describe(in).c_str(), std::string(details()).c_str());
  std::fflush(stderr);
  std::abort();
}

template <typename S>
void require(bool holds, const char* invariant, const DiskPairInput<S>& in) {
  require(holds, invariant, in, [] { return std::string(); });
}

/// Bit-for-bit equality (NaNs with equal payloads compare equal).
template <typename S>
bool sameBits(S a, S b) {
  return std::memcmp(&a, &b, sizeof(S)) == 0;
}

template <typename S>
bool sameBits(const fcl::Vector3<S>& a, const fcl::Vector3<S>& b) {
  return sameBits(a.x(), b.x()) && sameBits(a.y(), b.y()) && sameBits(a.z(), b.z());
}

// ----------------------------------------------------------------------------
// Geometry, in double (float inputs are promoted exactly).

template <typename S>
Pose3d toDouble(const fcl::Transform3<S>& X) {
  return X.template cast<double>();
}

/// How far p_W is from the disk (radius r, pose X_WD): max(|local z|, radial excess).
inline double offDisk(const Vector3d& p_W, double r, const Pose3d& X_WD) {
  const Vector3d p_D = X_WD.linear().transpose() * (p_W - X_WD.translation());
  return std::max(std::abs(p_D.z()), std::max(0.0, std::hypot(p_D.x(), p_D.y()) - r));
}

/// Largest |dualLowerBound| over the returned direction (when the points differ)
/// and the four face normals: the certificate the exact solver says it
/// returns, recomputed here from the public formula, independently of the
/// solver's own lower_bound.
inline double independentLowerBound(double r1, const Pose3d& X_W1, double r2, const Pose3d& X_W2,
                                    const Vector3d& p, const Vector3d& q) {
  double bound = 0.0;
  const Vector3d separation = q - p;
  if (separation.norm() > 0)
    bound = fcl_disk::dualLowerBound<double>(separation.normalized(), r1, X_W1, r2, X_W2);
  for (const Vector3d& n : {Vector3d(X_W1.linear().col(2)), Vector3d(X_W2.linear().col(2))}) {
    if (!(n.norm() > 0)) continue;
    for (const double sign : {1.0, -1.0})
      bound = std::max(bound, fcl_disk::dualLowerBound<double>(sign * n.normalized(), r1, X_W1,
                                                               r2, X_W2));
  }
  return bound;
}

/// The lengths the documented bounds scale with, for one input.
struct Scales {
  /// r1 + r2 + |c1 - c2|: the scale of the double guarantees, relative at
  /// every length scale (exact_distance.h; far from the origin costs nothing).
  double pair;
  /// max(pair, |c1|, |c2|): where the rounding of world coordinates enters
  /// (storing points, building and rounding poses).
  double scene;
  /// The scale of S's distance guarantee: pair in double; in float, whose
  /// documented bound is "a few float ulps of max(r1 + r2 + |c1 - c2|, |c_i|)"
  /// (no floor), the scene.
  double distance;
};

template <typename S>
Scales scalesOf(const DiskPairInput<S>& in) {
  const Vector3d c1 = in.X_W1.translation().template cast<double>();
  const Vector3d c2 = in.X_W2.translation().template cast<double>();
  Scales scales;
  scales.pair = double(in.r1) + double(in.r2) + (c2 - c1).norm();
  scales.scene = std::max({scales.pair, c1.norm(), c2.norm()});
  scales.distance = kIsFloat<S> ? scales.scene : scales.pair;
  return scales;
}

/// kStorageUlps ulps (of S) of the largest coordinate among `points`.
template <typename S>
double storageRounding(std::initializer_list<Vector3d> points) {
  double largest = 0.0;
  for (const Vector3d& p : points) largest = std::max(largest, p.cwiseAbs().maxCoeff());
  return kStorageUlps * double(std::numeric_limits<S>::epsilon()) * largest;
}

// ----------------------------------------------------------------------------
// The bad-input policy (disk_pair.h, isValidDiskRadius, isValidDiskPose): a
// radius outside [kMinDiskRadius, kMaxDiskLength], a non-finite pose entry, a
// translation beyond kMaxDiskLength, or a rotation further than
// kRotationDefectTolerance<S> from orthonormal describes no disk pair and gets
// NaN distance, lower_bound and points and no contact; a rotation within the
// tolerance is used as given, at a cost of about defect * (r1 + r2 + |c1 - c2|)
// in distance (defectCost below).

/// The larger rotation defect of the two poses: ~1e-16 for our constructed
/// rotations, up to the tolerance for raw perturbed ones.
template <typename S>
double maxDefect(const DiskPairInput<S>& in) {
  return std::max(rotationDefect(in.X_W1), rotationDefect(in.X_W2));
}

/// The library evaluates the defect in S, we in double: within this fraction of
/// the tolerance either verdict is acceptable (float R^T R rounds by ~1e-7,
/// 1/1000 of its 1e-4 tolerance; double by ~1e-16).
constexpr double kPolicyMargin = 0.01;

enum class Verdict {
  no_disk_pair,  ///< must get NaN everywhere and no contact.
  borderline,    ///< rotation defect within kPolicyMargin of the tolerance: either.
  accepted,      ///< a disk pair: answered.
};

template <typename S>
Verdict verdictOf(const DiskPairInput<S>& in) {
  if (!in.radiiValid() || !in.posesFinite() || !in.translationsInRange())
    return Verdict::no_disk_pair;
  const double defect = maxDefect(in);
  const double tolerance = fcl_disk::kRotationDefectTolerance<S>;
  if (!(defect <= (1 + kPolicyMargin) * tolerance)) return Verdict::no_disk_pair;  // also NaN
  if (defect >= (1 - kPolicyMargin) * tolerance) return Verdict::borderline;
  return Verdict::accepted;
}

/// Accepted (not borderline): every guarantee applies, at any magnitude in range.
template <typename S>
bool fullyChecked(const DiskPairInput<S>& in) {
  return verdictOf(in) == Verdict::accepted;
}

/// Spectral norm of a symmetric 3x3 matrix per unit of its largest entry
/// (norm <= Frobenius norm <= 3 max |entry|): turns the defect, an entry
/// bound of R^T R - I, into a bound on how far R R^T moves a vector.
constexpr double kDefectNormFactor = 3.0;

/// What an accepted rotation's defect may cost in distance and in points,
/// beyond the solvers' bounds: disk_pair.h, "about defect * (r1 + r2 +
/// |c1 - c2|)" (R^T is used as the inverse, so disk 2 mapped into disk 1's
/// frame and back moves by (R_W1 R_W1^T - I)(c2 - c1), so defect * (r1 + r2) alone is
/// not enough: corpus/*/regression-defect-times-centre-distance). "About": the defect
/// bounds entries, kDefectNormFactor turns it into a norm.
template <typename S>
double defectCost(const DiskPairInput<S>& in) {
  const Vector3d c1 = in.X_W1.translation().template cast<double>();
  const Vector3d c2 = in.X_W2.translation().template cast<double>();
  return kDefectNormFactor * maxDefect(in) * (double(in.r1) + double(in.r2) + (c2 - c1).norm());
}

template <typename S>
bool allNaN(const fcl_disk::DiskDistanceResult<S>& r) {
  return std::isnan(r.distance) && std::isnan(r.lower_bound) && r.p_W1.array().isNaN().all() &&
         r.p_W2.array().isNaN().all();
}

/// Runs `check(pair, reader)` on the input decoded as double and as float (the
/// reader then points past the pair, at the target's own option bytes);
/// returns 0, or -1 (libFuzzer: keep it out of the corpus) if neither decoding
/// was accepted.
template <typename Check>
int forBothScalars(const std::uint8_t* data, std::size_t size, Check&& check) {
  bool accepted = false;
  auto run = [&](auto scalar) {
    using S = decltype(scalar);
    ByteReader in(data, size);
    const auto pair = decodeDiskPair<S>(in);
    if (printInputs())
      std::fprintf(stderr, "%s\n", pair ? describe(*pair).c_str() : "rejected (near-zero quaternion)");
    if (!pair) return;
    check(*pair, in);
    accepted = true;
  };
  run(double());
  run(float());
  return accepted ? 0 : -1;
}

}  // namespace fcl_disk_fuzz

// libFuzzer target: fcl_disk::exactDiskDistance, double and float.
//
// A disk pair (radii and translations in the library's range, rotations within
// the defect tolerance): a finite pair of points on the disks whose
// distance is the returned one, certified within the bound exact_distance.h
// documents (by the solver's own lower_bound, and by the certificate
// recomputed here), equal to the closed-form distance where the mode knows it,
// and symmetric under swapping the disks; an accepted non-orthonormal rotation
// adds its documented cost. Input describing no disk pair (radius or
// translation out of range, NaN/inf, rotation beyond the tolerance): NaN
// distance, lower_bound and points.
#include <fcl_disk/exact_distance.h>

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "fuzz_checks.h"

namespace fcl_disk_fuzz {
namespace {

template <typename S>
void checkExactDistance(const DiskPairInput<S>& in) {
  using E = Eps<S>;
  const auto result = fcl_disk::exactDiskDistance<S>(in.r1, in.X_W1, in.r2, in.X_W2);
  const double d = result.distance;
  const Vector3d p = result.p_W1.template cast<double>(), q = result.p_W2.template cast<double>();
  const auto resultText = [&] {
    return "distance " + numberText(d) + ", p_W1 " + vectorText(p) + ", p_W2 " + vectorText(q) +
           ", lower_bound " + numberText(result.lower_bound) + ", iterations " +
           std::to_string(result.iterations);
  };

  switch (verdictOf(in)) {
    case Verdict::no_disk_pair:
      require(allNaN(result), "exact: input describing no disk pair gives NaN distance, "
              "lower_bound and points", in, resultText);
      return;
    case Verdict::borderline:
      require(std::isnan(d) || d >= 0, "exact: NaN or a distance >= 0", in, resultText);
      return;
    case Verdict::accepted:
      break;
  }

  const double r1 = in.r1, r2 = in.r2;
  const Pose3d X_W1 = toDouble(in.X_W1), X_W2 = toDouble(in.X_W2);
  const Scales scale = scalesOf(in);
  const double defect_cost = defectCost(in);
  require(std::isfinite(d) && d >= 0 && p.allFinite() && q.allFinite() &&
              std::isfinite(double(result.lower_bound)),
          "exact: a disk pair gets a finite distance >= 0 and finite points", in, resultText);

  // Points on their disks: the distance bound plus the rounding of storing
  // them in world coordinates (exact_distance.h).
  const double on_disk =
      kBoundSafetyFactor *
      (E::kOnDiskRelative * scale.distance + defect_cost +
       storageRounding<S>({X_W1.translation(), X_W2.translation(), p, q}));
  require(offDisk(p, r1, X_W1) <= on_disk, "exact: p_W1 lies on disk 1", in, resultText);
  require(offDisk(q, r2, X_W2) <= on_disk, "exact: p_W2 lies on disk 2", in, resultText);
  require(std::abs((q - p).norm() - d) <=
              kBoundSafetyFactor * (E::kExactDistanceRelative * scale.distance + defect_cost +
                                    storageRounding<S>({p, q})),
          "exact: |p_W2 - p_W1| == distance", in, resultText);

  // The certificate, as exact_distance.h bounds it: 1e-14 scale when well
  // conditioned, and next to degenerate configurations the Lipschitz constant
  // r1 + r2 of g at its kinks times the error of its direction, sqrt(eps) or
  // eps scale / d: (r1 + r2)(sqrt(eps) + 8 eps scale / d), eps of S
  // (test_tolerances.h). In these units the bound holds at every scale; the
  // form with scale and scale^2 / d (a length squared) is 1e5x too small at
  // scale 1e-5 (corpus/fuzz_exact_distance/regression-certificate-small-scale).
  const double conditioning =
      d > 0 ? (r1 + r2) * (E::kCertificateFlatOptimum +
                           E::kCertificateSmallDistance * scale.distance / d)
            : 0.0;
  const double documented_gap = E::kCertifiedGapRelative * scale.distance + conditioning;
  require(double(result.certifiedGap()) <= kBoundSafetyFactor * (documented_gap + defect_cost),
          "exact: certifiedGap() within the documented bound", in, resultText);
  // The same certificate recomputed from the returned points: proves the
  // distance optimal whatever the solver's lower_bound says. Extra terms: a
  // float rotation is orthonormal only to rounding (kPoseRounding, twice: both
  // disks), and rounding the returned points by e tilts the direction by up to
  // 4e/d, against a Lipschitz constant |c2 - c1| + r1 + r2 of the bound.
  if (d > 0) {
    const double lower = independentLowerBound(r1, X_W1, r2, X_W2, p, q);
    const double lipschitz = (X_W2.translation() - X_W1.translation()).norm() + r1 + r2;
    const double direction_error = 4 * on_disk / d;
    require(d - lower <= kBoundSafetyFactor * (documented_gap + defect_cost +
                                               2 * E::kPoseRoundingRelative * scale.scene) +
                             lipschitz * direction_error,
            "exact: the recomputed certificate proves the distance", in,
            [&] { return "recomputed lower bound " + numberText(lower) + "; " + resultText(); });
  }

  // Closed-form distance of the structured configuration. It was built in
  // double and stored in S, which moves disk 2 by a few ulps of the scene.
  if (in.known_distance) {
    const double tolerance = kBoundSafetyFactor * (E::kExactDistanceRelative * scale.distance +
                                                   E::kPoseRoundingRelative * scale.scene);
    require(std::abs(d - *in.known_distance) <= tolerance,
            "exact: distance equals the configuration's closed-form distance", in, [&] {
              return "tolerance " + numberText(tolerance) + "; " + resultText();
            });
  }

  // Swapping the disks: the same problem, so both answers are within the
  // bound of the true distance.
  const auto swapped = fcl_disk::exactDiskDistance<S>(in.r2, in.X_W2, in.r1, in.X_W1);
  require(std::abs(double(swapped.distance) - d) <=
              kBoundSafetyFactor * 2 * (E::kExactDistanceRelative * scale.distance + defect_cost),
          "exact: swapping the disks keeps the distance", in, [&] {
            return "swapped distance " + numberText(swapped.distance) + "; " + resultText();
          });
}

}  // namespace
}  // namespace fcl_disk_fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fcl_disk_fuzz::forBothScalars(data, size, [](const auto& pair, fcl_disk_fuzz::ByteReader&) {
    fcl_disk_fuzz::checkExactDistance(pair);
  });
}

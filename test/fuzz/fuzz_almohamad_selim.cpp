// libFuzzer target: fcl_disk::almohamadSelimDiskDistance, double and float.
//
// The 1994 algorithm is not exact (almohamad_selim.h), so the invariants are
// what its header promises: a real pair of points on the disks with distance
// |p_W2 - p_W1|, hence an upper bound on the exact distance, and a lower_bound
// that is a sound certificate. Input describing no disk pair (invalid radius,
// NaN/inf, rotation beyond the defect tolerance): NaN distance, lower_bound and
// points.
#include <fcl_disk/almohamad_selim.h>
#include <fcl_disk/exact_distance.h>

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "fuzz_checks.h"

namespace fcl_disk_fuzz {
namespace {

template <typename S>
void checkAlmohamadSelim(const DiskPairInput<S>& in) {
  using E = Eps<S>;
  const auto report = fcl_disk::almohamadSelimDiskDistance<S>(in.r1, in.X_W1, in.r2, in.X_W2);
  const double d = report.distance;
  const Vector3d p = report.p_W1.template cast<double>(), q = report.p_W2.template cast<double>();
  const auto reportText = [&] {
    return "Almohamad-Selim distance " + numberText(d) + ", p_W1 " + vectorText(p) + ", p_W2 " +
           vectorText(q) + ", lower_bound " + numberText(report.lower_bound);
  };

  switch (verdictOf(in)) {
    case Verdict::no_disk_pair:
      require(allNaN(report), "Almohamad-Selim: input describing no disk pair gives NaN "
              "distance, lower_bound and points", in, reportText);
      return;
    case Verdict::borderline:
      require(std::isnan(d) || d >= 0, "Almohamad-Selim: NaN or a distance >= 0", in, reportText);
      return;
    case Verdict::accepted:
      break;
  }

  const double r1 = in.r1, r2 = in.r2;
  const Pose3d X_W1 = toDouble(in.X_W1), X_W2 = toDouble(in.X_W2);
  const Scales scale = scalesOf(in);
  require(std::isfinite(d) && d >= 0 && p.allFinite() && q.allFinite(),
          "Almohamad-Selim: a disk pair gets a finite distance >= 0 and finite points", in,
          reportText);

  // Closed forms, no iteration: only rounding (test_tolerances.h), plus
  // storing the points in world coordinates and an accepted rotation's defect.
  const double consistency =
      kBoundSafetyFactor * (E::kAlmohamadSelimConsistencyRelative * scale.distance +
                            defectCost(in) +
                            storageRounding<S>({X_W1.translation(), X_W2.translation(), p, q}));
  require(offDisk(p, r1, X_W1) <= consistency, "Almohamad-Selim: p_W1 lies on disk 1", in,
          reportText);
  require(offDisk(q, r2, X_W2) <= consistency, "Almohamad-Selim: p_W2 lies on disk 2", in,
          reportText);
  require(std::abs((q - p).norm() - d) <= consistency,
          "Almohamad-Selim: |p_W2 - p_W1| == distance", in, reportText);

  // A real pair bounds the distance from above; the certificate from below.
  const auto exact = fcl_disk::exactDiskDistance<S>(in.r1, in.X_W1, in.r2, in.X_W2);
  const double both_solvers =
      consistency + kBoundSafetyFactor * E::kExactDistanceRelative * scale.distance;
  const auto withExact = [&] {
    return "exact distance " + numberText(exact.distance) + "; " + reportText();
  };
  require(double(exact.distance) - d <= both_solvers,
          "Almohamad-Selim: distance >= exact distance (an upper bound)", in, withExact);
  require(double(report.lower_bound) - double(exact.distance) <= both_solvers,
          "Almohamad-Selim: lower_bound <= exact distance (a sound certificate)", in, withExact);
}

}  // namespace
}  // namespace fcl_disk_fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fcl_disk_fuzz::forBothScalars(data, size, [](const auto& pair, fcl_disk_fuzz::ByteReader&) {
    fcl_disk_fuzz::checkAlmohamadSelim(pair);
  });
}

// libFuzzer target: fcl_disk::intersectDisks, double and float.
//
// Valid input: the verdict is the exact solver's "distance == 0", except
// within the touching band (a translation of disk 2 by at most the band flips
// the exact verdict), where either answer is acceptable; the contact point lies
// on both disks, the normal is unit, the depth finite and >= 0, and translating
// disk 2 by (depth + a small step) along the normal separates the disks and
// leaves them no further apart than that translation, a step less does not,
// and no direction separates sooner (depth <= F(w) on 68 directions: the
// depth is the exact penetration depth, disk_intersection.h).
// Asking for the contact does not change the verdict. Input describing no disk
// pair (invalid radius, NaN/inf, rotation beyond the defect tolerance): false.
#include <fcl_disk/disk_intersection.h>
#include <fcl_disk/exact_distance.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fuzz_checks.h"

namespace fcl_disk_fuzz {
namespace {

/// Whether translating disk 2 by `band` (either sign) along either normal, the
/// planes' common line, the line of centres or the nearest direction changes
/// the exact solver's intersecting/apart verdict: then the pose is within the
/// band of touching, and either verdict is acceptable (as test_properties.cpp).
template <typename S>
bool exactVerdictFlipsWithin(const DiskPairInput<S>& in,
                             const fcl_disk::DiskDistanceResult<S>& exact, double band) {
  const bool verdict_intersecting = exact.distance <= 0;
  const Pose3d X_W1 = toDouble(in.X_W1), X_W2 = toDouble(in.X_W2);
  const Vector3d n1 = X_W1.linear().col(2), n2 = X_W2.linear().col(2);
  std::vector<Vector3d> directions = {n1.normalized(), n2.normalized()};
  const Vector3d common_line = n1.cross(n2);
  if (common_line.norm() > 0) directions.push_back(common_line.normalized());
  const Vector3d centres = X_W2.translation() - X_W1.translation();
  if (centres.norm() > 0) directions.push_back(centres.normalized());
  const Vector3d nearest = (exact.p_W2 - exact.p_W1).template cast<double>();
  if (nearest.norm() > 0) directions.push_back(nearest.normalized());
  for (const Vector3d& direction : directions) {
    for (const double sign : {1.0, -1.0}) {
      fcl::Transform3<S> moved_X_W2 = in.X_W2;
      moved_X_W2.translation() = (X_W2.translation() + sign * band * direction).template cast<S>();
      const auto moved = fcl_disk::exactDiskDistance<S>(in.r1, in.X_W1, in.r2, moved_X_W2);
      if ((moved.distance <= 0) != verdict_intersecting) return true;
    }
  }
  return false;
}

template <typename S>
void checkIntersection(const DiskPairInput<S>& in) {
  using E = Eps<S>;
  fcl_disk::DiskContact<S> contact;
  const bool intersects = fcl_disk::intersectDisks<S>(in.r1, in.X_W1, in.r2, in.X_W2, &contact);
  const bool verdict_only = fcl_disk::intersectDisks<S>(in.r1, in.X_W1, in.r2, in.X_W2);
  const Vector3d pos = contact.pos.template cast<double>();
  const Vector3d normal = contact.normal.template cast<double>();
  const double depth = contact.penetration_depth;
  const auto contactText = [&] {
    return std::string("intersectDisks ") + (intersects ? "true" : "false") + ", contact pos " +
           vectorText(pos) + ", normal " + vectorText(normal) + ", depth " + numberText(depth);
  };
  require(intersects == verdict_only, "intersection: asking for the contact keeps the verdict", in,
          contactText);

  if (verdictOf(in) == Verdict::no_disk_pair) {
    require(!intersects, "intersection: input describing no disk pair gives false", in,
            contactText);
    return;
  }
  if (!fullyChecked(in)) return;  // borderline defect or huge: no crash is all that is promised

  const Scales scale = scalesOf(in);
  const auto exact = fcl_disk::exactDiskDistance<S>(in.r1, in.X_W1, in.r2, in.X_W2);
  const bool exact_says_intersecting = exact.distance <= 0;
  // The touching band: test_tolerances.h (10x the exact solver's zero/non-zero
  // resolution in double, 64 float ulps of the scene in float), at least a few
  // ulps of the coordinates (a smaller move of disk 2 would not be
  // representable), plus an accepted rotation's defect.
  const double band =
      E::kIntersectionBandRelative * scale.distance + defectCost(in) +
      storageRounding<S>({in.X_W1.translation().template cast<double>(),
                          in.X_W2.translation().template cast<double>()});
  if (intersects != exact_says_intersecting) {
    require(exactVerdictFlipsWithin(in, exact, band),
            "intersection: verdict == (exact distance == 0) outside the touching band", in, [&] {
              return "exact distance " + numberText(exact.distance) + ", band " +
                     numberText(band) + "; " + contactText();
            });
  }
  if (!intersects) return;

  const Pose3d X_W1 = toDouble(in.X_W1), X_W2 = toDouble(in.X_W2);
  const double on_disk =
      kBoundSafetyFactor * (E::kOnDiskRelative * scale.distance + defectCost(in) +
                            storageRounding<S>({X_W1.translation(), X_W2.translation(), pos}));
  require(offDisk(pos, in.r1, X_W1) <= on_disk, "intersection: contact pos lies on disk 1", in,
          contactText);
  require(offDisk(pos, in.r2, X_W2) <= on_disk, "intersection: contact pos lies on disk 2", in,
          contactText);
  // Normalised by the library even for rotations accepted within their defect
  // tolerance (corpus: regression-normal-defect).
  require(std::abs(normal.norm() - 1.0) <= kBoundSafetyFactor * E::kUnitNormal,
          "intersection: |normal| == 1", in, contactText);
  require(std::isfinite(depth) && depth >= 0, "intersection: depth finite and >= 0", in,
          contactText);

  // The depth's meaning: one step past depth * normal the disks are apart, and
  // no further apart than the translation (they shared a point, and the
  // distance is 1-Lipschitz in translations). The step is test_tolerances.h's
  // (100x the band: decided robustly, yet small).
  const double step = E::kSeparationStepRelative / E::kIntersectionBandRelative * band;
  fcl::Transform3<S> separated_X_W2 = in.X_W2;
  separated_X_W2.translation() =
      (X_W2.translation() + (depth + step) * normal.normalized()).template cast<S>();
  require(!fcl_disk::intersectDisks<S>(in.r1, in.X_W1, in.r2, separated_X_W2),
          "intersection: moving disk 2 by (depth + step) normal separates", in, contactText);
  // The depth is the shortest separating translation (docs/penetration_depth.md):
  // no direction w separates sooner, F(w) = h1(w) + h2(-w) >= depth for every
  // unit w (F(w) is a separating length along w), here on the disks' normals
  // and a Fibonacci sphere of directions; and a step short of the depth along
  // the normal the disks still intersect.
  const double depth_slack =
      kBoundSafetyFactor * ((E::kExactDistanceRelative + E::kPoseRoundingRelative) * scale.scene +
                            defectCost(in));
  const auto separating_length = [&](const Vector3d& w) {
    const auto in_plane = [&](const Pose3d& X) {
      return std::hypot(X.linear().col(0).dot(w), X.linear().col(1).dot(w));
    };
    return (X_W1.translation() - X_W2.translation()).dot(w) + double(in.r1) * in_plane(X_W1) +
           double(in.r2) * in_plane(X_W2);
  };
  std::vector<Vector3d> directions = {X_W1.linear().col(2), -X_W1.linear().col(2),
                                      X_W2.linear().col(2), -X_W2.linear().col(2)};
  constexpr int kSphereDirections = 64;
  for (int k = 0; k < kSphereDirections; ++k) {
    const double z = 1.0 - (2.0 * k + 1.0) / kSphereDirections;
    const double ring = std::sqrt(1.0 - z * z), angle = k * 2.399963229728653;  // golden angle
    directions.emplace_back(ring * std::cos(angle), ring * std::sin(angle), z);
  }
  for (const Vector3d& w : directions) {
    require(depth <= separating_length(w.normalized()) + depth_slack,
            "intersection: depth <= F(w) for every direction w (the shortest translation)", in,
            [&] { return "F(w) " + numberText(separating_length(w.normalized())) + " along " +
                         vectorText(w) + "; " + contactText(); });
  }
  if (depth > 2 * step) {
    fcl::Transform3<S> short_X_W2 = in.X_W2;
    short_X_W2.translation() =
        (X_W2.translation() + (depth - step) * normal.normalized()).template cast<S>();
    require(fcl_disk::intersectDisks<S>(in.r1, in.X_W1, in.r2, short_X_W2),
            "intersection: moving disk 2 by (depth - step) normal leaves them intersecting", in,
            contactText);
  }
  const auto after = fcl_disk::exactDiskDistance<S>(in.r1, in.X_W1, in.r2, separated_X_W2);
  require(double(after.distance) <=
              depth + step +
                  kBoundSafetyFactor *
                      ((E::kExactDistanceRelative + E::kPoseRoundingRelative) *
                           std::max(scale.scene, depth) +
                       defectCost(in)),
          "intersection: ... and leaves them at distance <= depth + step", in, [&] {
            return "distance after the move " + numberText(after.distance) + ", step " +
                   numberText(step) + "; " + contactText();
          });
}

}  // namespace
}  // namespace fcl_disk_fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fcl_disk_fuzz::forBothScalars(data, size, [](const auto& pair, fcl_disk_fuzz::ByteReader&) {
    fcl_disk_fuzz::checkIntersection(pair);
  });
}

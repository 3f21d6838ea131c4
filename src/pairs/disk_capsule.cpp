// Disk - fcl::Capsule: the capsule is its axis segment inflated by its radius.
// Apart, the segment's nearest pair (segmentToDisk) less the radius, certified
// along it; else the generic solver on the segment (projection: clamping along
// the axis), the radius subtracted (docs/disk_shape_distance.md, section 4); the
// contact's directions make its depth the exact penetration depth
// (docs/penetration_depth.md, section 7).
#include "../disk_shape_pair.h"
#include "feature_candidates.h"
#include "../environment_bounds.h"
#include "../leaf_solvers.h"
#include "../segment_to_disk.h"

#include <vector>

namespace fcl_disk {
namespace internal {
namespace {

/// The segment {(0, 0, z) : |z| <= half_length} of the capsule frame.
struct SegmentTarget {
  double half_length;

  Projection project(const Vec3& y) const {
    const double z = std::clamp(y.z(), -half_length, half_length);
    // Inside the segment's span psi's Hessian is I - z z^T, beyond an end I.
    return Projection{Vec3(0.0, 0.0, z),
                      FactoredHessian::diagonalOf(Vec3(1.0, 1.0, z == y.z() ? 0.0 : 1.0))};
  }

  Vec3 support(const Vec3& w) const {  // ties take the + end
    return Vec3(0.0, 0.0, w.z() < 0.0 ? -half_length : half_length);
  }
};

/// The capsule of radius `radius` about {(0, 0, z) : |z| <= half_length}: the
/// axis segment's nearest pair (segmentToDisk), moved by the radius along w
/// (from the disk's point to the segment's), certified along the pair's
/// certificateDirection: min over the capsule of w.y - h_K(w), its core's
/// support less the radius. A disk point within the radius of the segment is
/// a common point (distance 0, that point as both); pairs apart by less than
/// touching are left to the generic solver (not exact). `scale` as
/// solveInShapeFrame's.
[[gnu::flatten]] LeafToDisk capsuleClosedForm(const DiskInShape& disk, double radius,
                                              double half_length, double scale) {
  const SegmentToDisk axis =
      segmentToDisk(disk, Vec3(0.0, 0.0, -half_length), Vec3(0.0, 0.0, half_length));
  const double upper = axis.distance - radius;
  if (upper <= 0.0) return meetingAt(axis.p_disk);
  if (!(upper > kShapeTouchingTolerance * scale)) return LeafToDisk{};
  const SegmentTarget segment{half_length};
  return certifiedSegmentPair(
      disk, [&](const Vec3& v) { return v.dot(segment.support(-v)); }, axis, scale,
      /*mismatch=*/0.0, /*inflation=*/radius);
}

template <typename S>
struct CapsuleTraits {
  static bool valid(const fcl::Capsule<S>& capsule) {
    return areValidShapeLengths({double(capsule.radius), double(capsule.lz)});
  }
  static double boundingRadius(const fcl::Capsule<S>& capsule) {
    return 0.5 * double(capsule.lz) + double(capsule.radius);
  }
  static double inflation(const fcl::Capsule<S>& capsule) { return double(capsule.radius); }
  /// capsuleClosedForm (below), inlined with the segment solver: its ends are
  /// constants of the axis, which takes less time than the call
  /// (docs/performance.md, "A Disk against FCL's primitives").
  [[gnu::flatten]] static LeafToDisk closedForm(const DiskInShape& disk,
                                                const fcl::Capsule<S>& capsule, double scale) {
    return capsuleClosedForm(disk, double(capsule.radius), 0.5 * double(capsule.lz), scale);
  }
  static SegmentTarget target(const fcl::Capsule<S>& capsule) {
    return SegmentTarget{0.5 * double(capsule.lz)};
  }
  /// The directions among which the shortest separating translation lies
  /// (shortestSeparation adds the disk's normals and both signs), so the contact's
  /// depth is the exact penetration depth: F(w) = h_disk(w) + h_segment(-w) +
  /// rho is smooth but at the disk's normals and on the circle w . z = 0 where
  /// the segment's two ends tie. Away from both, a minimiser has the segment's
  /// end s as support point and the disk's rim point b along b - s, so b is
  /// the rim point nearest or farthest s (addVertexCandidates). On the circle,
  /// F = h_disk(w) + rho with w horizontal, stationary where the disk's support
  /// point b has its horizontal part along w and normal to the rim tangent
  /// (addEdgeLineCandidates on the axis; docs/penetration_depth.md, section 7).
  template <typename Search>
  static void contactDirections(const SegmentTarget& target, const DiskInShape& disk,
                                Search* directions) {
    for (const double end : {-target.half_length, target.half_length}) {
      addVertexCandidates(disk, Vec3(0.0, 0.0, end), directions);
    }
    addEdgeLineCandidates(disk, Vec3::Zero(), Vec3::UnitZ(), directions);
  }
};

}  // namespace

template <typename S>
struct DiskShapePair<fcl::Capsule<S>>
    : GenericDiskShapePair<S, fcl::Capsule<S>, CapsuleTraits<S>> {};

DiskShapeSolution solveDiskCapsule(const DiskInShape& disk, double radius, double half_length) {
  // solveInShapeFrame on fcl::Capsule(radius, 2 half_length), whose
  // boundingRadius is half_length + radius. The capsule is built only for the
  // generic solver: building it for every query adds ~100 instructions (12%)
  // to the side wall's solve on the report's cylinder cases.
  const double scale = disk.r + (half_length + radius) + disk.c.norm();
  const LeafToDisk closed = capsuleClosedForm(disk, radius, half_length, scale);
  if (closed.exact) {
    DiskShapeSolution solution;
    solution.p = closed.p_disk;
    solution.q = closed.p_leaf;
    solution.distance = closed.distance;
    solution.lower_bound = closed.certified;
    return solution;
  }
  return DiskShapePair<fcl::Capsule<double>>::solveInShapeFrame(
      disk, fcl::Capsule<double>(radius, 2.0 * half_length), /*try_closed_form=*/false);
}

}  // namespace internal
}  // namespace fcl_disk

FCL_DISK_INSTANTIATE_DISK_SHAPE_PAIR(fcl::Capsule)

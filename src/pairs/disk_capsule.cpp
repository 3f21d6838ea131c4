// Disk - fcl::Capsule: the capsule is its axis segment inflated by its radius, so
// the generic solver runs on the segment (projection: clamping along the axis)
// and the radius is subtracted. docs/disk_shape_distance.md, section 4.
#include "../disk_shape_pair.h"

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

template <typename S>
struct CapsuleTraits {
  static bool valid(const fcl::Capsule<S>& capsule) {
    return areValidShapeLengths({double(capsule.radius), double(capsule.lz)});
  }
  static double boundingRadius(const fcl::Capsule<S>& capsule) {
    return 0.5 * double(capsule.lz) + double(capsule.radius);
  }
  static double inflation(const fcl::Capsule<S>& capsule) { return double(capsule.radius); }
  static SegmentTarget target(const fcl::Capsule<S>& capsule) {
    return SegmentTarget{0.5 * double(capsule.lz)};
  }
  /// The axis and the capsule frame's two other axes.
  static std::array<Vec3, 3> contactDirections(const SegmentTarget&) {
    return {Vec3::UnitZ(), Vec3::UnitX(), Vec3::UnitY()};
  }
};

}  // namespace

template <typename S>
struct DiskShapePair<fcl::Capsule<S>>
    : GenericDiskShapePair<S, fcl::Capsule<S>, CapsuleTraits<S>> {};

}  // namespace internal
}  // namespace fcl_disk

FCL_DISK_INSTANTIATE_DISK_SHAPE_PAIR(fcl::Capsule)

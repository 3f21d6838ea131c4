// Disk - fcl::Capsule: the capsule is its axis segment inflated by its radius, so
// the generic solver runs on the segment (projection: clamping along the axis)
// and the radius is subtracted. docs/disk_shape_distance.md, section 4.
#include "../disk_shape_pair.h"

namespace fcl_disk {
namespace internal {
namespace {

/// The segment {(0, 0, z) : |z| <= half_length} of the capsule frame, posed in D.
struct SegmentTarget {
  PoseInDisk pose;
  double half_length;

  Projection project(const Vec3& x) const {
    const Vec3 axis = pose.R.col(2);
    const double along = axis.dot(x - pose.c);
    const double clamped = std::clamp(along, -half_length, half_length);
    // Inside the segment's span psi's Hessian is I - a a^T, beyond an end I.
    Mat3 hessian = Mat3::Identity();
    if (clamped == along) hessian -= axis * axis.transpose();
    return Projection{pose.c + clamped * axis, hessian};
  }

  Vec3 support(const Vec3& w) const {
    const Vec3 axis = pose.R.col(2);
    return pose.c + (axis.dot(w) < 0.0 ? -half_length : half_length) * axis;
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
  static SegmentTarget target(const fcl::Capsule<S>& capsule, const PoseInDisk& pose) {
    return SegmentTarget{pose, 0.5 * double(capsule.lz)};
  }
  /// The axis and the capsule frame's two other axes.
  static std::array<Vec3, 3> contactDirections(const SegmentTarget& segment) {
    return {segment.pose.R.col(2), segment.pose.R.col(0), segment.pose.R.col(1)};
  }
};

}  // namespace

template <typename S>
struct DiskShapePair<fcl::Capsule<S>>
    : GenericDiskShapePair<S, fcl::Capsule<S>, CapsuleTraits<S>> {};

}  // namespace internal
}  // namespace fcl_disk

FCL_DISK_INSTANTIATE_DISK_SHAPE_PAIR(fcl::Capsule)

// Disk - fcl::Box: the generic solver with the box's projection (clamping in the
// box frame) and support (a vertex). docs/disk_shape_distance.md, section 4.
#include "../disk_shape_pair.h"

namespace fcl_disk {
namespace internal {
namespace {

/// The solid box {|y_i| <= half_i} posed in the disk's frame.
struct BoxTarget {
  PoseInDisk pose;
  Vec3 half;

  Projection project(const Vec3& x) const {
    const Vec3 y = pose.toShape(x);
    Vec3 q_S;
    Vec3 outside;  // psi's Hessian in the box frame: 1 along each clamped axis
    for (int i = 0; i < 3; ++i) {
      q_S[i] = std::clamp(y[i], -half[i], half[i]);
      outside[i] = q_S[i] != y[i] ? 1.0 : 0.0;
    }
    return Projection{pose.fromShape(q_S), pose.hessianFromShape(outside.asDiagonal())};
  }

  Vec3 support(const Vec3& w) const {
    const Vec3 w_S = pose.directionToShape(w);
    // Ties (w_S perpendicular to an axis) take the + side.
    return pose.fromShape(Vec3(w_S.x() < 0.0 ? -half.x() : half.x(),
                               w_S.y() < 0.0 ? -half.y() : half.y(),
                               w_S.z() < 0.0 ? -half.z() : half.z()));
  }
};

template <typename S>
struct BoxTraits {
  static bool valid(const fcl::Box<S>& box) {
    return areValidShapeLengths({double(box.side.x()), double(box.side.y()), double(box.side.z())});
  }
  static double boundingRadius(const fcl::Box<S>& box) {
    return 0.5 * box.side.template cast<double>().norm();
  }
  static double inflation(const fcl::Box<S>&) { return 0.0; }
  static BoxTarget target(const fcl::Box<S>& box, const PoseInDisk& pose) {
    return BoxTarget{pose, 0.5 * box.side.template cast<double>()};
  }
  /// The face normals.
  static std::array<Vec3, 3> contactDirections(const BoxTarget& box) {
    return {box.pose.R.col(0), box.pose.R.col(1), box.pose.R.col(2)};
  }
};

}  // namespace

template <typename S>
struct DiskShapePair<fcl::Box<S>> : GenericDiskShapePair<S, fcl::Box<S>, BoxTraits<S>> {};

}  // namespace internal
}  // namespace fcl_disk

FCL_DISK_INSTANTIATE_DISK_SHAPE_PAIR(fcl::Box)

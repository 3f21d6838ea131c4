// Disk - fcl::Cone: the generic solver with the cone's projection, computed in the
// meridian half-plane (a right triangle) and turned about the axis, and its
// support (apex or base rim). docs/disk_shape_distance.md, section 4.
#include "../disk_shape_pair.h"

namespace fcl_disk {
namespace internal {
namespace {

/// The solid cone of FCL: base disk of radius `radius` at z = -half_length, apex
/// at z = +half_length; posed in D. In the meridian half-plane (rho, z), rho >= 0
/// the distance from the axis, it is the triangle O = (0, -h), B = (radius, -h),
/// A = (0, h).
struct ConeTarget {
  PoseInDisk pose;
  double radius;
  double half_length;

  /// Nearest point of the segment from `from` to `to` to `point` (meridian
  /// coordinates), and the 2x2 Jacobian of that projection (e e^T inside, 0 at
  /// an end).
  static void nearestOnEdge(const Vec2& point, const Vec2& from, const Vec2& to, Vec2* nearest,
                            Eigen::Matrix2d* jacobian) {
    const Vec2 edge = to - from;
    const double length_squared = edge.squaredNorm();
    double t = length_squared > 0.0 ? edge.dot(point - from) / length_squared : 0.0;
    if (t <= 0.0 || t >= 1.0 || !(length_squared > 0.0)) {
      t = std::clamp(t, 0.0, 1.0);
      jacobian->setZero();
    } else {
      *jacobian = edge * edge.transpose() / length_squared;
    }
    *nearest = from + t * edge;
  }

  Projection project(const Vec3& x) const {
    const Vec3 y = pose.toShape(x);
    const double h = half_length;
    const double rho = std::sqrt(y.x() * y.x() + y.y() * y.y());
    const Vec2 m(rho, y.z());
    // Inside: above the base, under the slant side A-B (written without a
    // division so that degenerate cones, radius or height 0, stay exact).
    if (y.z() >= -h && y.z() <= h && rho <= radius &&
        2.0 * h * rho + radius * (y.z() - h) <= 0.0) {
      return Projection{x, Mat3::Zero()};
    }
    // Outside, the nearest point is on the slant side A-B or on the base O-B.
    // (The base's end O lies on the axis, inside the base disk: no corner.)
    Vec2 on_side;
    Eigen::Matrix2d jacobian_side;
    nearestOnEdge(m, Vec2(0.0, h), Vec2(radius, -h), &on_side, &jacobian_side);
    const Vec2 on_base(std::min(rho, radius), -h);
    Eigen::Matrix2d jacobian_base = Eigen::Matrix2d::Zero();
    jacobian_base(0, 0) = rho <= radius ? 1.0 : 0.0;
    const bool side = (m - on_side).squaredNorm() <= (m - on_base).squaredNorm();
    const Vec2 nearest = side ? on_side : on_base;
    const Eigen::Matrix2d J = side ? jacobian_side : jacobian_base;
    // Back to 3-D: the radial direction e (any, on the axis) and the tangent t;
    // turning about the axis scales by nearest_rho / rho.
    const Vec3 e = rho > 0.0 ? Vec3(y.x() / rho, y.y() / rho, 0.0) : Vec3::UnitX();
    const Vec3 t(-e.y(), e.x(), 0.0);
    const Vec3 z = Vec3::UnitZ();
    const double turn = rho > 0.0 ? nearest.x() / rho : J(0, 0);
    const Mat3 Dq = J(0, 0) * e * e.transpose() + J(1, 1) * z * z.transpose() +
                    J(0, 1) * (e * z.transpose() + z * e.transpose()) + turn * t * t.transpose();
    const Vec3 q_S = nearest.x() * e + nearest.y() * z;
    return Projection{pose.fromShape(q_S), pose.hessianFromShape(Mat3::Identity() - Dq)};
  }

  Vec3 support(const Vec3& w) const {
    const Vec3 w_S = pose.directionToShape(w);
    const double planar = std::sqrt(w_S.x() * w_S.x() + w_S.y() * w_S.y());
    const Vec3 apex(0.0, 0.0, half_length);
    const Vec3 rim = planar > 0.0 ? Vec3(radius * w_S.x() / planar, radius * w_S.y() / planar,
                                         -half_length)
                                  : Vec3(radius, 0.0, -half_length);
    // Ties take the apex.
    return pose.fromShape(w_S.dot(rim) > w_S.dot(apex) ? rim : apex);
  }
};

template <typename S>
struct ConeTraits {
  static bool valid(const fcl::Cone<S>& cone) {
    return areValidShapeLengths({double(cone.radius), double(cone.lz)});
  }
  static double boundingRadius(const fcl::Cone<S>& cone) {
    return std::hypot(double(cone.radius), 0.5 * double(cone.lz));
  }
  static double inflation(const fcl::Cone<S>&) { return 0.0; }
  static ConeTarget target(const fcl::Cone<S>& cone, const PoseInDisk& pose) {
    return ConeTarget{pose, double(cone.radius), 0.5 * double(cone.lz)};
  }
  /// The axis and the frame's two other axes.
  static std::array<Vec3, 3> contactDirections(const ConeTarget& cone) {
    return {cone.pose.R.col(2), cone.pose.R.col(0), cone.pose.R.col(1)};
  }
};

}  // namespace

template <typename S>
struct DiskShapePair<fcl::Cone<S>> : GenericDiskShapePair<S, fcl::Cone<S>, ConeTraits<S>> {};

}  // namespace internal
}  // namespace fcl_disk

FCL_DISK_INSTANTIATE_DISK_SHAPE_PAIR(fcl::Cone)

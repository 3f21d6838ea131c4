// fcl_disk: a zero-thickness circular disk shape for FCL 0.7.
#pragma once

#include <fcl/geometry/shape/cylinder.h>

#include <fcl_disk/disk_pair.h>
// Disks are queried through fcl::distance / fcl::collide; in float those come
// precompiled from libfcl_disk instead of being instantiated per file.
#include <fcl_disk/fcl_templates.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace fcl_disk {
namespace detail {
/// Installs fcl_disk's functions into FCL's dispatch tables once (default method
/// on first call); defined in src/fcl_hook.cpp. Throws std::runtime_error if the
/// hook cannot take effect in this process.
void ensureDiskFunctionsRegistered();
}  // namespace detail

/// A closed circular disk of zero thickness.
///
/// Local frame D: centre at the origin, lying in the XY plane, unit normal +Z.
/// Units are the caller's length unit. The set is {(x, y, 0) : x^2 + y^2 <= radius^2}.
///
/// Disk derives from fcl::Cylinder with lz = 0 so that FCL's dispatch (whose node
/// types are a closed enum) routes it through the GEOM_CYLINDER entries, which
/// fcl_disk replaces with wrappers that answer disk-disk pairs analytically and
/// forward every other pair (real cylinders included) to FCL's own function.
/// A Disk against FCL's primitives is answered by diskShapeDistance() and
/// diskShapeIntersect() (disk_shape_distance.h); against meshes and octrees by FCL
/// (GJK on the flat cylinder, which is
/// exactly the disk).
///
/// fcl_disk's functions are installed when the library is loaded (default method:
/// exact); constructing a Disk checks that they are (throws std::runtime_error,
/// saying why, if the hook could not take effect in this process).
/// @throws std::invalid_argument if radius is outside [kMinDiskRadius,
/// kMaxDiskLength] (disk_pair.h: 1e-100..1e100 in double, 1e-37..1e37 in float),
/// NaN, infinite, zero and negative radii included.
template <typename S>
class Disk final : public fcl::Cylinder<S> {
 public:
  /// A disk of radius `radius` in its frame D (see above); throws as stated above.
  explicit Disk(S radius) : fcl::Cylinder<S>(checkedRadius(radius), S(0)) {
    detail::ensureDiskFunctionsRegistered();
  }

  /// The unit normal of the disk in the world frame, for the pose X_WD.
  static fcl::Vector3<S> normal(const fcl::Transform3<S>& X_WD) {
    return X_WD.linear().col(2);
  }

  /// FCL's local box [-r, r]^2 x {0}, padded by identityTiltPad() r on every
  /// side. fcl::CollisionObject::computeAABB() takes any rotation Eigen's
  /// isIdentity() accepts (entries within p = 1e-5 of I in float, 1e-12 in
  /// double) as exactly I and translates this box; such a rotation moves the
  /// disk's extent along x and y by at most p r and lifts its rim by at most
  /// sqrt(2) p r, so the padded box still holds the disk (unpadded, a float
  /// disk tilted by 1e-6 stuck out of its box and FCL's managers missed its
  /// pairs). Elsewhere FCL uses the cube of half-width aabb_radius, which grows
  /// with the pad.
  void computeLocalAABB() override {
    fcl::Cylinder<S>::computeLocalAABB();
    const fcl::Vector3<S> pad = fcl::Vector3<S>::Constant(identityTiltPad() * this->radius);
    this->aabb_local.min_ -= pad;
    this->aabb_local.max_ += pad;
    this->aabb_center = this->aabb_local.center();
    this->aabb_radius = (this->aabb_local.min_ - this->aabb_center).norm();
  }

 private:
  /// The pad of the local box, relative to the radius: 2 p (p = Eigen's
  /// dummy precision for S, isIdentity()'s default) plus rounding, which
  /// covers the sqrt(2) p tilt and the p stretch of a rotation within p of I.
  static S identityTiltPad() {
    return S(2) * Eigen::NumTraits<S>::dummy_precision() + S(8) * std::numeric_limits<S>::epsilon();
  }

  static S checkedRadius(S radius) {
    if (!isValidDiskRadius(radius)) {
      std::ostringstream message;
      message << "fcl_disk::Disk: radius must be in [" << kMinDiskRadius<S> << ", "
              << kMaxDiskLength<S> << "], got " << radius;
      throw std::invalid_argument(message.str());
    }
    return radius;
  }
};

using Diskd = Disk<double>;  ///< A Disk in double.
using Diskf = Disk<float>;   ///< A Disk in float.

}  // namespace fcl_disk

// Disk's tight bounding volumes for fcl::computeBV: declared with the class, so
// that every use of computeBV on a Disk sees them.
#include <fcl_disk/disk_bv.h>

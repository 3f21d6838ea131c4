// Tight world-frame bounding boxes for disks, for FCL's broadphase managers.
//
// FCL 0.7's CollisionObject::computeAABB() bounds a rotated shape by a cube of
// half-width aabb_radius around its centre; for a disk (a Cylinder(r, 0)) that is
// sqrt(2) r on every axis, whatever the disk's orientation. A horizontal coin or a
// vertical plate is much thinner than that along its normal, and a broadphase
// manager fed such cubes hands the narrowphase many pairs whose disks are far apart.
// The helpers here give the smallest axis-aligned box instead.
#pragma once

#include <fcl/math/bv/AABB.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl_disk/disk.h>

#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <utility>

namespace fcl_disk {

/// The smallest axis-aligned box, in the world frame W, that contains the disk of
/// the given radius with pose X_WD (Disk's convention: centre at the origin of D,
/// in D's XY plane). Units: the caller's length unit.
///
/// A disk point is c + r cos(t) u + r sin(t) v (u, v: the first two columns of
/// X_WD's rotation), so its extent along world axis i is r sqrt(u_i^2 + v_i^2),
/// the maximum of r (cos(t) u_i + sin(t) v_i) over t. That equals
/// r sqrt(1 - n_i^2) for an orthonormal rotation, but written with u and v it
/// keeps its digits when n_i is close to +-1 (no cancellation), and it is exact for
/// the rotation as stored even if that is orthonormal only to rounding.
///
/// Guarantee: the box contains every point of the disk (computed exactly from the
/// stored radius and pose), and exceeds the smallest such box, per face, by at most
/// 2 * kDiskAabbExtentPadUlps * eps * extent_i + 2 ulp(|c_i| + extent_i) (eps, ulp
/// of S): a few ulps, see kDiskAabbExtentPadUlps. FCL's own box is a cube of
/// half-width sqrt(2) r (1 + 2 p) (rounded to nearest), so this one lies inside
/// it up to those ulps; for a rotation Eigen's isIdentity() accepts (entries
/// within p = 1e-12 of I in double, 1e-5 in float) FCL translates the Disk's
/// local box instead, padded by 2 p r so that it still holds the tilted disk
/// (Disk::computeLocalAABB). Non-finite input gives a non-finite box.
template <typename S>
fcl::AABB<S> diskWorldAABB(S radius, const fcl::Transform3<S>& X_WD);

/// Rounding never leaves a disk point outside diskWorldAABB's box. Rounding to
/// nearest errs by at most eps/2 relative per operation: u_i^2 + v_i^2 (two
/// products and a sum), its sqrt and the product with r give the extent to within
/// about 3 eps relative, so the extent is enlarged by kDiskAabbExtentPadUlps = 4 eps
/// relative (which itself rounds by eps/2). The faces c_i -+ extent then round by at
/// most half an ulp, so each is moved one ulp outward (std::nextafter). A pad in
/// units of eps * |c_i| would do as well but is wider (~16 ulps of |c_i|) and would
/// make tiny disks far from the origin exceed FCL's cube.
inline constexpr int kDiskAabbExtentPadUlps = 4;

/// Replaces the world box that `object` stores (and broadphase managers read
/// through getAABB()) with diskWorldAABB() of its current pose, if its geometry is
/// a fcl_disk::Disk; otherwise leaves it untouched. Works on any CollisionObject,
/// also one a planner created itself. Returns whether the object holds a Disk.
///
/// Call it where FCL code calls computeAABB(): after every setTransform() and
/// before the manager's update(). Calling object.computeAABB() afterwards
/// restores FCL's loose cube (see diskWorldAABB() for how it compares).
template <typename S>
bool updateDiskAABB(fcl::CollisionObject<S>& object);

/// A CollisionObject for a Disk that keeps the tight box of diskWorldAABB().
///
/// Tight box after: construction, setPoseAndUpdateAABB(), computeTightAABB(), and
/// computeAABB() called on a DiskCollisionObject (this class hides the base
/// function). FCL 0.7's CollisionObject::computeAABB() is NOT virtual, so calling
/// it through a fcl::CollisionObject<S>* or & runs FCL's own code and stores FCL's
/// loose cube again (less selective; see diskWorldAABB()). Like the base class,
/// setTransform() alone does not update the box.
///
/// Broadphase managers only read getAABB() (DynamicAABBTreeCollisionManager:
/// registerObject(s), update() and update(obj) copy it into the tree), so to move
/// disks: setPoseAndUpdateAABB() on each, then manager.update().
template <typename S>
class DiskCollisionObject : public fcl::CollisionObject<S> {
 public:
  /// @throws std::invalid_argument if disk is null.
  explicit DiskCollisionObject(std::shared_ptr<Disk<S>> disk,
                               const fcl::Transform3<S>& X_WD = fcl::Transform3<S>::Identity())
      : fcl::CollisionObject<S>(checkedDisk(disk), X_WD), disk_(std::move(disk)) {
    computeTightAABB();
  }

  /// Sets the pose X_WD and the tight box for it.
  void setPoseAndUpdateAABB(const fcl::Transform3<S>& X_WD) {
    this->setTransform(X_WD);
    computeTightAABB();
  }

  /// Sets the tight box for the current pose (after setTransform() and friends).
  void computeTightAABB() { this->aabb = diskWorldAABB(disk_->radius, this->getTransform()); }

  /// Hides CollisionObject::computeAABB() so that FCL's usual
  /// "setTransform(); computeAABB();" keeps the tight box when the static type is
  /// DiskCollisionObject. Not virtual: see the class comment.
  void computeAABB() { computeTightAABB(); }

  /// The disk this object holds.
  const Disk<S>& disk() const { return *disk_; }

 private:
  static std::shared_ptr<fcl::CollisionGeometry<S>> checkedDisk(
      const std::shared_ptr<Disk<S>>& disk) {
    if (!disk) throw std::invalid_argument("fcl_disk::DiskCollisionObject: disk is null");
    return disk;
  }

  std::shared_ptr<Disk<S>> disk_;
};

using DiskCollisionObjectd = DiskCollisionObject<double>;  ///< A DiskCollisionObject in double.
using DiskCollisionObjectf = DiskCollisionObject<float>;   ///< A DiskCollisionObject in float.

// ---- implementation ------------------------------------------------------------

template <typename S>
fcl::AABB<S> diskWorldAABB(S radius, const fcl::Transform3<S>& X_WD) {
  const auto& R = X_WD.linear();
  const fcl::Vector3<S>& centre = X_WD.translation();
  constexpr S kExtentPad = 1 + kDiskAabbExtentPadUlps * std::numeric_limits<S>::epsilon();
  constexpr S kInfinity = std::numeric_limits<S>::infinity();
  fcl::AABB<S> box;
  for (int i = 0; i < 3; ++i) {
    const S extent = kExtentPad * radius * std::sqrt(R(i, 0) * R(i, 0) + R(i, 1) * R(i, 1));
    box.min_[i] = std::nextafter(centre[i] - extent, -kInfinity);
    box.max_[i] = std::nextafter(centre[i] + extent, kInfinity);
  }
  return box;
}

namespace detail {
/// Reaches CollisionObject's protected `aabb` of any object: a pointer to a
/// protected member may be formed in a derived class and applied to any base.
template <typename S>
struct CollisionObjectAabbAccess : fcl::CollisionObject<S> {
  static fcl::AABB<S>& of(fcl::CollisionObject<S>& object) {
    return object.*(&CollisionObjectAabbAccess::aabb);
  }
};
}  // namespace detail

template <typename S>
bool updateDiskAABB(fcl::CollisionObject<S>& object) {
  const auto* disk = dynamic_cast<const Disk<S>*>(object.collisionGeometry().get());
  if (disk == nullptr) return false;
  detail::CollisionObjectAabbAccess<S>::of(object) =
      diskWorldAABB(disk->radius, object.getTransform());
  return true;
}

}  // namespace fcl_disk

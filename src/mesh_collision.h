// Internal: fcl::collide between a disk and a triangle mesh (fcl::BVHModel of
// any bounding volume FCL has) without cost sources, in the mesh's frame M.
// docs/meshes_and_octrees.md, "Collision traversal".
//
// FCL's traversal (collisionRecurse over a MeshShapeCollisionTraversalNode)
// with its rules kept and its volume test replaced: the model's hierarchy
// depth first, the first child before the second; a leaf tested only if the
// mesh and the disk are both occupied; a contact per triangle the disk meets
// (the certified disk-triangle intersection, src/leaf_solvers.h), while there
// is room; stop once the request is satisfied. FCL tests the disk's bounding
// volume against each node's (for an OBB, 15 axes after a product of the two
// rotations); here a lower bound on the distance from the disk to the node's
// volume as a box (diskBoxSeparation / diskAlignedBoxSeparation) prunes it,
// when it exceeds the intersection test's touching tolerance for any triangle
// inside (kShapeTouchingTolerance of that triangle's scene, bounded by the
// node's) plus the bounds' rounding pad, so no triangle that
// intersectDiskTriangle would call intersecting is ever skipped.
//
// Frame, units: M and its lengths; the disk as a DiskInShape in M. Contacts are
// FCL's: o1 the mesh, o2 the disk, b1 the triangle's index, b2 NONE; with
// enable_contact, pos in M, normal and depth as FCL's shape-triangle contacts
// (the normal negated, depth >= 0). Thread safety: nothing is shared.
#pragma once

#include <algorithm>
#include <limits>

#include "environment_bounds.h"
#include "leaf_contact.h"
#include "leaf_solvers.h"
#include "mesh_distance.h"  // isLeaf, primitiveId, vertexIds

namespace fcl_disk {
namespace internal {

/// A node's volume as a box for diskBoxSeparation: the box itself (AABB, OBB,
/// and the OBB of OBBRSS and kIOS), a k-DOP's first three slab pairs (FCL's
/// coordinate axes), an RSS's rectangle, the gaps less its radius.
/// With the separation: the volume's magnitude (boxBoundMagnitude, for the
/// rounding pad) and `reach`, a bound on the 1-norm of its points.
struct BoxSeparation {
  double separation;
  double magnitude;
  double reach;
};
inline BoxSeparation alignedSeparation(const DiskInShape& disk, const Vec3& disk_extents,
                                       const Vec3& o, const Vec3& e) {
  return {diskAlignedBoxSeparation(disk, disk_extents, o, e), boxBoundMagnitude(o, e),
          o.cwiseAbs().sum() + e.sum()};
}
/// `separation` with the magnitude and reach of the oriented box of centre o
/// and half-extents e: its points lie within |e|_1 of o along each of the
/// frame's axes.
inline BoxSeparation withOrientedBox(double separation, const Vec3& o, const Vec3& e) {
  return {separation, boxBoundMagnitude(o, e), o.cwiseAbs().sum() + 3.0 * e.sum()};
}
inline BoxSeparation orientedSeparation(const DiskInShape& disk, const Vec3& o, const Mat3& axes,
                                        const Vec3& e) {
  return withOrientedBox(diskBoxSeparation(disk, o, axes.transpose(), e), o, e);
}
/// An AABB, and a k-DOP as its first three slab pairs (alignedBoxOf).
template <typename AlignedVolume>
BoxSeparation volumeSeparation(const DiskInShape& disk, const Vec3& disk_extents,
                               const AlignedVolume& volume) {
  const AlignedBox box = alignedBoxOf(volume);
  return alignedSeparation(disk, disk_extents, box.o, box.e);
}
template <typename S>
BoxSeparation volumeSeparation(const DiskInShape& disk, const Vec3&, const fcl::OBB<S>& obb) {
  return orientedSeparation(disk, obb.To.template cast<double>(), obb.axis.template cast<double>(),
                            obb.extent.template cast<double>());
}
/// An RSS, the rectangle swept by a ball of radius r: along every axis its
/// support is the rectangle's plus r, so the gaps are the rectangle's less r.
/// Its magnitude and reach are those of the rectangle grown by r on every side.
template <typename S>
BoxSeparation volumeSeparation(const DiskInShape& disk, const Vec3&, const fcl::RSS<S>& rss) {
  const auto& axes = rss.axis.template cast<double>();
  const double half0 = 0.5 * double(rss.l[0]), half1 = 0.5 * double(rss.l[1]);
  const double radius = double(rss.r);
  const Vec3 o = rss.To.template cast<double>() + half0 * axes.col(0) + half1 * axes.col(1);
  return withOrientedBox(diskBoxSeparation(disk, o, axes.transpose(), Vec3(half0, half1, 0.0)) -
                             radius,
                         o, Vec3(half0 + radius, half1 + radius, radius));
}
template <typename S>
BoxSeparation volumeSeparation(const DiskInShape& disk, const Vec3& disk_extents,
                               const fcl::OBBRSS<S>& obbrss) {
  return volumeSeparation(disk, disk_extents, obbrss.obb);
}
template <typename S>
BoxSeparation volumeSeparation(const DiskInShape& disk, const Vec3& disk_extents,
                               const fcl::kIOS<S>& kios) {
  return volumeSeparation(disk, disk_extents, kios.obb);
}

template <typename BV>
class DiskMeshCollision {
 public:
  using S = typename BV::S;

  DiskMeshCollision(const DiskInShape& disk, const fcl::BVHModel<BV>& model,
                    const fcl::CollisionGeometry<S>& disk_geometry,
                    const fcl::CollisionRequest<S>& request, fcl::CollisionResult<S>& result)
      : disk_(disk),
        model_(model),
        disk_geometry_(disk_geometry),
        request_(request),
        result_(result),
        disk_extents_(diskAxisExtents(disk)),
        disk_magnitude_(diskBoundMagnitude(disk)),
        disk_reach_(disk.r + disk.c.cwiseAbs().sum()) {}

  /// Adds the contacts to `result` (frame M).
  void run() {
    if (model_.getNumBVs() <= 0) return;
    visit(0);
  }

 private:
  /// A volume fitted in S holds its triangles to S's rounding (the distance
  /// traversal's pad).
  static constexpr double kPad = kEnvironmentBoundPadUlps * double(std::numeric_limits<S>::epsilon());

  /// collisionRecurse; true once the request is satisfied.
  bool visit(int node_index) {
    const auto& node = model_.getBV(node_index);
    const BoxSeparation volume = volumeSeparation(disk_, disk_extents_, node.bv);
    // The tolerance is positive: most volumes near the disk need none. A
    // triangle inside has vertices within volume.reach (1-norm) of M's
    // origin: its scene, r + |vertex| + |c|, is at most disk_reach_ + that.
    if (volume.separation > 0.0) {  // NaN volumes are searched
      const double tolerance = kShapeTouchingTolerance * (disk_reach_ + volume.reach) +
                               kPad * (disk_magnitude_ + volume.magnitude);
      if (volume.separation > tolerance) return false;
    }
    if (isLeaf(node)) return testLeaf(primitiveId(node));
    if (visit(node.first_child)) return true;
    return visit(node.first_child + 1);
  }

  bool testLeaf(int triangle) {
    if (!(model_.isOccupied() && disk_geometry_.isOccupied())) return false;
    const auto& ids = vertexIds(model_, triangle);
    const Vec3 a = model_.vertices[ids[0]].template cast<double>();
    const Vec3 b = model_.vertices[ids[1]].template cast<double>();
    const Vec3 c = model_.vertices[ids[2]].template cast<double>();
    return addLeafContact(
        [&](FrameContact* contact) { return intersectDiskTriangle(disk_, a, b, c, contact); },
        Vec3::Zero(), model_, disk_geometry_, triangle, request_, result_);
  }

  const DiskInShape& disk_;
  const fcl::BVHModel<BV>& model_;
  const fcl::CollisionGeometry<S>& disk_geometry_;
  const fcl::CollisionRequest<S>& request_;
  fcl::CollisionResult<S>& result_;
  const Vec3 disk_extents_;  ///< diskAxisExtents
  const double disk_magnitude_;
  const double disk_reach_;  ///< r + |c|_1
};

/// The disk against the mesh (a triangle model), contacts into `result`
/// (frame M), for a request without enable_cost.
template <typename BV>
void diskMeshCollide(const DiskInShape& disk, const fcl::BVHModel<BV>& model,
                     const fcl::CollisionGeometry<typename BV::S>& disk_geometry,
                     const fcl::CollisionRequest<typename BV::S>& request,
                     fcl::CollisionResult<typename BV::S>& result) {
  DiskMeshCollision<BV>(disk, model, disk_geometry, request, result).run();
}

}  // namespace internal
}  // namespace fcl_disk

// Internal: fcl::collide between a disk and an octree (fcl::OcTree) without
// cost sources, in the octree's frame O. docs/meshes_and_octrees.md,
// "Collision traversal".
//
// FCL's traversal (OcTreeSolver::OcTreeShapeIntersectRecurse) with its rules
// kept and its overlap test replaced: the same cells (getRootBV,
// computeChildBV: src/octree_cells.h), visited in the same order (depth first,
// children 0..7); an inner cell's subtree entered only if that cell is neither
// free nor uncertain and the disk is neither, a leaf tested only if it is
// occupied and the disk is too; a contact per leaf the disk meets (the
// certified disk-box intersection, src/leaf_solvers.h), while there is room;
// stop once the request is satisfied. FCL tests the disk's bounding square, as
// an OBB, against each cell's box (15 axes); here a lower bound on the distance
// from the disk to the cell prunes it (diskAlignedBoxSeparation: the gaps along
// O's axes and the disk's normal, with the disk's exact extents) when it
// exceeds the intersection test's touching tolerance for any leaf inside the
// cell (kShapeTouchingTolerance of that leaf's scene, bounded by the cell's)
// plus the bounds' rounding pad, so no leaf that intersectDiskBox would call
// intersecting is ever skipped.
//
// Frame, units: O and its lengths; the disk as a DiskInShape in O. Contacts are
// FCL's: o1 the octree, o2 the disk, b1 the leaf's offset from the root node,
// b2 NONE; with enable_contact, pos in O, the normal from the cell into the
// disk's side negated as FCL's box-shape contacts have it, depth >= 0. Thread
// safety: nothing is shared.
#pragma once

#include <fcl/geometry/octree/octree.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "environment_bounds.h"
#include "leaf_contact.h"
#include "leaf_solvers.h"
#include "octree_cells.h"

namespace fcl_disk {
namespace internal {

template <typename S>
class DiskOcTreeCollision {
 public:
  using Node = typename fcl::OcTree<S>::OcTreeNode;

  DiskOcTreeCollision(const DiskInShape& disk, const fcl::OcTree<S>& tree,
                      const fcl::CollisionGeometry<S>& disk_geometry,
                      const fcl::CollisionRequest<S>& request, fcl::CollisionResult<S>& result)
      : disk_(disk),
        tree_(tree),
        disk_geometry_(disk_geometry),
        request_(request),
        result_(result),
        disk_extents_(diskAxisExtents(disk)),
        disk_magnitude_(diskBoundMagnitude(disk)),
        disk_occupied_(disk_geometry.isOccupied()),
        disk_enterable_(!disk_geometry.isFree() && !disk_geometry.isUncertain()) {}

  /// Adds the contacts to `result` (frame O).
  void run() {
    const OcTreeCell<S> root_cell = rootCell(tree_);
    if (tree_.getRoot() == nullptr || !mayMeet(root_cell)) return;
    visit(tree_.getRoot(), root_cell);
  }

 private:
  /// The cells' boxes are FCL's, computed in S, so the bounds hold to S's
  /// rounding (as the distance traversal's).
  static constexpr double kPad = kEnvironmentBoundPadUlps * double(std::numeric_limits<S>::epsilon());

  /// Whether the disk may meet the cell (centre o, half-extents h) within the
  /// touching tolerance of a leaf inside it: no leaf there has a scene larger
  /// than r + 2 |h| + |c - o| (|.| <= the 1-norm), nor a touching tolerance
  /// larger than kShapeTouchingTolerance of that.
  bool mayMeet(const OcTreeCell<S>& cell) const {
    const AlignedBox box = alignedBoxOf(cell);
    const Vec3 &o = box.o, &h = box.e;
    const double separation = diskAlignedBoxSeparation(disk_, disk_extents_, o, h);
    // The tolerance is positive: most cells near the disk need none.
    if (!(separation > 0.0)) return true;  // NaN: searched
    const double tolerance =
        kShapeTouchingTolerance * (disk_.r + 2.0 * h.sum() + (o - disk_.c).cwiseAbs().sum()) +
        kPad * (disk_magnitude_ + boxBoundMagnitude(o, h));
    return !(separation > tolerance);
  }

  /// FCL's recursion on a cell the disk may meet; true once the request is
  /// satisfied.
  bool visit(const Node* node, const OcTreeCell<S>& cell) {
    if (!tree_.nodeHasChildren(node)) {
      return tree_.isNodeOccupied(node) && disk_occupied_ && testLeaf(node, cell);
    }
    if (tree_.isNodeFree(node) || tree_.isNodeUncertain(node) || !disk_enterable_) return false;
    for (unsigned int i = 0; i < 8; ++i) {
      if (!tree_.nodeChildExists(node, i)) continue;
      const OcTreeCell<S> child = childCell(cell, i);
      if (mayMeet(child) && visit(tree_.getNodeChild(node, i), child)) return true;
    }
    return false;
  }

  bool testLeaf(const Node* node, const OcTreeCell<S>& cell) {
    const AlignedBox box = alignedBoxOf(cell);
    const Vec3 &o = box.o, &h = box.e;
    const DiskInShape in_cell{disk_.c - o, disk_.u, disk_.v, disk_.n, disk_.r};
    return addLeafContact(
        [&](FrameContact* contact) { return intersectDiskBox(in_cell, h, contact); }, o, tree_,
        disk_geometry_, node - tree_.getRoot(), request_, result_);
  }

  const DiskInShape& disk_;
  const fcl::OcTree<S>& tree_;
  const fcl::CollisionGeometry<S>& disk_geometry_;
  const fcl::CollisionRequest<S>& request_;
  fcl::CollisionResult<S>& result_;
  const Vec3 disk_extents_;  ///< diskAxisExtents
  const double disk_magnitude_;
  const bool disk_occupied_;   ///< a leaf is tested only if the disk is occupied
  const bool disk_enterable_;  ///< a subtree entered only if the disk is neither free nor uncertain
};

/// The disk against the tree, contacts into `result` (frame O), for a request
/// without enable_cost.
template <typename S>
void diskOcTreeCollide(const DiskInShape& disk, const fcl::OcTree<S>& tree,
                       const fcl::CollisionGeometry<S>& disk_geometry,
                       const fcl::CollisionRequest<S>& request, fcl::CollisionResult<S>& result) {
  DiskOcTreeCollision<S>(disk, tree, disk_geometry, request, result).run();
}

}  // namespace internal
}  // namespace fcl_disk

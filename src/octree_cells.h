// Internal: an octree's cells as FCL forms them (fcl::OcTree::getRootBV,
// fcl::computeChildBV), computed inline for the traversals of
// src/octree_distance.h and src/octree_collision.h.
//
// FCL instantiates computeChildBV and the AABB constructors in libfcl, so each
// child cell it forms costs calls into the library; a traversal forms one per
// existing child it looks at. childCell repeats computeChildBV's arithmetic in
// S, so the cells, and the ids and bounds derived from them, are FCL's to the bit.
#pragma once

#include <fcl/geometry/octree/octree.h>

#include "environment_bounds.h"

namespace fcl_disk {
namespace internal {

/// An octree cell: the box [low, high] in the octree's frame, in S.
template <typename S>
struct OcTreeCell {
  fcl::Vector3<S> low, high;
};

/// The root's cell (fcl::OcTree::getRootBV).
template <typename S>
OcTreeCell<S> rootCell(const fcl::OcTree<S>& tree) {
  const fcl::AABB<S> root = tree.getRootBV();
  return {root.min_, root.max_};
}

/// Child i's cell: along axis k the upper half when bit k of i is set, else
/// the lower, split at (low + high) * 0.5 as fcl::computeChildBV splits it.
template <typename S>
OcTreeCell<S> childCell(const OcTreeCell<S>& cell, unsigned int i) {
  OcTreeCell<S> child;
  for (int k = 0; k < 3; ++k) {
    const S middle = (cell.low[k] + cell.high[k]) * S(0.5);
    const bool upper = ((i >> k) & 1u) != 0;
    child.low[k] = upper ? middle : cell.low[k];
    child.high[k] = upper ? cell.high[k] : middle;
  }
  return child;
}

/// The cell's centre and half-extents, formed in S as alignedBoxOf forms an
/// fcl::AABB's.
template <typename S>
AlignedBox alignedBoxOf(const OcTreeCell<S>& cell) {
  return {((cell.low + cell.high) / 2).template cast<double>(),
          ((cell.high - cell.low) / 2).template cast<double>()};
}

}  // namespace internal
}  // namespace fcl_disk

// Internal: the distance between a disk and the occupied cells of an octree
// (fcl::OcTree), in the octree's frame O. docs/meshes_and_octrees.md,
// "Distance traversal".
//
// Best-first search of the tree, as the mesh traversal (src/mesh_distance.h):
// cells queued by a lower bound on their distance to the disk (an inner cell's
// cube by diskAlignedBoxLowerBound; an occupied leaf by alignedBoxToDisk,
// which answers exactly for many cells, the others running the certified
// disk-box solver, src/leaf_solvers.h, when popped), popped until the least
// bound cannot beat the best distance (FCL's stop rule with the request's
// rel_err and abs_err); the nearest child of the cell just opened is opened
// next without passing through the queue when nothing queued is nearer.
// Which cells count is FCL's (OcTreeSolver::OcTreeShapeDistanceRecurse): a
// leaf if occupied, an inner cell's subtree only if that cell is occupied
// (octomap keeps an inner cell's occupancy the largest of its children's);
// the cells are FCL's (getRootBV, computeChildBV: src/octree_cells.h).
//
// Frame, units: O and its lengths; the disk as a DiskInShape in O. Guarantee:
// the least certified disk-cell distance over the cells counted, less at most
// the bounds' rounding pad. Ties: the cell found first keeps the answer. The
// cell's id is FCL's: its node's offset from the root node. Overlap: distance 0
// with a common point, and the search stops. Thread safety: thread-local
// scratch only.
#pragma once

#include <fcl/geometry/octree/octree.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "best_first_search.h"
#include "environment_bounds.h"
#include "leaf_solvers.h"
#include "octree_cells.h"

namespace fcl_disk {
namespace internal {

struct OcTreeDistanceAnswer {
  double distance = std::numeric_limits<double>::infinity();
  bool found = false;     ///< false: nothing closer than the starting best
  std::intptr_t cell = 0;  ///< FCL's id (the node's offset from the root node: any sign)
  Vec3 p_disk{Vec3::Zero()}, p_cell{Vec3::Zero()};  ///< frame O
};

template <typename S>
OcTreeDistanceAnswer diskOcTreeDistance(const DiskInShape& disk, const fcl::OcTree<S>& tree,
                                        double best, double rel_err, double abs_err) {
  using Node = typename fcl::OcTree<S>::OcTreeNode;
  // The cells' bounds are computed in S (FCL's), so they hold to S's rounding.
  const double pad = kEnvironmentBoundPadUlps * double(std::numeric_limits<S>::epsilon());
  OcTreeDistanceAnswer answer;
  answer.distance = best;
  const Node* root = tree.getRoot();
  if (root == nullptr) return answer;

  struct Entry {
    double bound;
    const Node* node;
    OcTreeCell<S> cell;
    bool operator>(const Entry& other) const { return bound > other.bound; }
  };
  std::vector<Entry>& scratch = scratchQueue<Entry>();
  const double disk_magnitude = diskBoundMagnitude(disk);
  const auto consider = [&](const Node* node, const Vec3& p_disk, const Vec3& p_cell,
                            double distance) {
    if (distance < answer.distance) {
      answer.distance = distance;
      answer.found = true;
      answer.cell = node - root;
      answer.p_disk = p_disk;
      answer.p_cell = p_cell;
    }
  };
  // The bound of a cell worth opening, or -1 (free, pruned, or a leaf settled
  // here).
  const auto evaluate = [&](const Node* node, const OcTreeCell<S>& cell) -> double {
    if (!tree.isNodeOccupied(node)) return -1.0;
    const AlignedBox box = alignedBoxOf(cell);
    const Vec3 &centre = box.o, &half = box.e;
    double bound;
    if (!tree.nodeHasChildren(node)) {
      const LeafToDisk leaf =
          alignedBoxToDisk(disk, centre, half, disk.r + half.norm() + (disk.c - centre).norm(),
                           answer.distance);
      if (leaf.exact) {
        consider(node, leaf.p_disk, leaf.p_leaf, leaf.distance);
        return -1.0;
      }
      bound = leaf.distance;
    } else {
      bound = diskAlignedBoxLowerBound(disk, centre, half);
    }
    bound -= pad * (disk_magnitude + boxBoundMagnitude(centre, half));
    if (!(bound > 0.0)) bound = 0.0;  // NaN cells are searched, never pruned
    if (cannotImprove(bound, answer.distance, rel_err, abs_err)) return -1.0;
    return bound;
  };
  const OcTreeCell<S> root_cell = rootCell(tree);
  const double root_bound = evaluate(root, root_cell);
  if (!(root_bound >= 0.0)) return answer;
  bestFirstSearch(
      scratch, Entry{root_bound, root, root_cell},
      [&](const Entry& entry, auto&& offer) {
        if (!tree.nodeHasChildren(entry.node)) {
          const AlignedBox box = alignedBoxOf(entry.cell);
          const Vec3 &centre = box.o, &half = box.e;
          const DiskShapeSolution solution =
              solveDiskBox(DiskInShape{disk.c - centre, disk.u, disk.v, disk.n, disk.r}, half);
          consider(entry.node, solution.p + centre, solution.q + centre, solution.distance);
          return;
        }
        for (unsigned int i = 0; i < 8; ++i) {  // FCL's order
          if (!tree.nodeChildExists(entry.node, i)) continue;
          const Node* child = tree.getNodeChild(entry.node, i);
          const OcTreeCell<S> cell = childCell(entry.cell, i);
          const double bound = evaluate(child, cell);
          if (bound >= 0.0) offer(Entry{bound, child, cell});
        }
      },
      [&](double bound) { return cannotImprove(bound, answer.distance, rel_err, abs_err); },
      [&] { return answer.distance <= 0.0; });  // an overlap: nothing is closer
  return answer;
}

}  // namespace internal
}  // namespace fcl_disk

// Internal: the distance between a disk and a triangle mesh (fcl::BVHModel of
// any bounding volume FCL has), in the mesh's frame M. docs/meshes_and_octrees.md,
// "Distance traversal".
//
// Best-first search of the model's hierarchy: a queue of nodes ordered by a
// lower bound on the distance from the disk to what they hold, popped until the
// least bound cannot beat the best distance found (FCL's stop rule, with the
// request's rel_err and abs_err). An opened node's nearer child is opened next
// without passing through the queue when nothing queued is nearer. Bounds
// (src/environment_bounds.h): an inner node's volume as an oriented box
// (diskBoxLowerBound; two sibling volumes at once where
// src/paired_volume_bounds.h pairs them); a leaf's triangle by triangleToDisk, which answers
// exactly when the triangle projects into the disk or its certificate closes
// (a vertex or the face nearest a disk point), so that leaf never reaches the
// solver; a leaf bounded at or above the best distance is dropped; other
// leaves run the certified disk-triangle solver (src/leaf_solvers.h) when
// popped.
//
// Frame, units: M and its lengths; the disk as a DiskInShape in M. Guarantee:
// the distance is the least over the triangles of their certified distances,
// less at most the bounds' rounding pad (kEnvironmentBoundPadUlps), i.e. within
// the leaf solver's 1e-12 of the scene. Ties: the triangle found first keeps
// the answer (a later one must be strictly closer), as FCL. Overlap: distance
// 0 with a common point, and the search stops there. Triangles with NaN or
// out-of-range vertices answer NaN and are skipped, as FCL skips them.
// Thread safety: the queue is thread-local scratch; nothing else is shared.
#pragma once

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/bv/RSS.h>
#include <fcl/math/bv/kDOP.h>
#include <fcl/math/bv/kIOS.h>

#include <algorithm>
#include <cstddef>
#include <limits>
#include <type_traits>
#include <vector>

#include "best_first_search.h"
#include "environment_bounds.h"
#include "leaf_solvers.h"
#include "paired_volume_bounds.h"

namespace fcl_disk {
namespace internal {

/// An AABB, and a k-DOP as its first three slab pairs (alignedBoxOf).
template <typename AlignedVolume>
VolumeBound volumeBound(const DiskInShape& disk, const AlignedVolume& volume) {
  const AlignedBox box = alignedBoxOf(volume);
  return {diskAlignedBoxLowerBound(disk, box.o, box.e), boxBoundMagnitude(box.o, box.e)};
}
template <typename S>
VolumeBound volumeBound(const DiskInShape& disk, const fcl::OBB<S>& obb) {
  // Read in place: for S = double the casts are the members themselves.
  const auto& o = obb.To.template cast<double>();
  const auto& e = obb.extent.template cast<double>();
  return {diskBoxLowerBound(disk, o, obb.axis.template cast<double>().transpose(), e),
          boxBoundMagnitude(o, e)};
}
/// An RSS: the rectangle To + [0, l0] axis_0 + [0, l1] axis_1 swept by a
/// sphere of radius r: the rectangle's bound (a box of zero thickness) less r,
/// the box bound raised to the gap along the rectangle's normal axis_2 (the
/// rectangle's extent along it is 0, the disk's r |(u.axis_2, v.axis_2)|):
/// the meshes' flat patches are often nearer to parallel with the disk than
/// the box bound's directions, and the gap opens fewer volumes (1.3% fewer
/// instructions per docs/scenes.md mesh_rss distance query; along an OBB's
/// least axis it costs more than it saves there).
/// Flattened: GCC kept the box bound out of line here, and inlined it saves
/// ~40 instructions a volume (callgrind).
template <typename S>
[[gnu::flatten]] VolumeBound volumeBound(const DiskInShape& disk, const fcl::RSS<S>& rss) {
  const auto& axes = rss.axis.template cast<double>();
  const double half0 = 0.5 * double(rss.l[0]), half1 = 0.5 * double(rss.l[1]);
  const Vec3 o = rss.To.template cast<double>() + half0 * axes.col(0) + half1 * axes.col(1);
  const Vec3 e(half0, half1, 0.0);
  const Vec3 normal = axes.col(2);
  const double u_n = disk.u.dot(normal), v_n = disk.v.dot(normal);
  const double normal_gap =
      std::abs(normal.dot(o - disk.c)) - disk.r * std::sqrt(u_n * u_n + v_n * v_n);
  return {std::max(diskBoxLowerBound(disk, o, axes.transpose(), e), normal_gap) - double(rss.r),
          boxBoundMagnitude(o, e) + double(rss.r)};
}
template <typename S>
VolumeBound volumeBound(const DiskInShape& disk, const fcl::OBBRSS<S>& obbrss) {
  return volumeBound(disk, obbrss.obb);
}
template <typename S>
VolumeBound volumeBound(const DiskInShape& disk, const fcl::kIOS<S>& kios) {
  return volumeBound(disk, kios.obb);
}

/// A hierarchy node's encoding (fcl/geometry/bvh/BV_node_base.h): first_child
/// >= 0 is the first of two adjacent children, < 0 is -(triangle index + 1).
/// Read inline: FCL defines isLeaf() and the like out of line.
inline bool isLeaf(const fcl::BVNodeBase& node) { return node.first_child < 0; }
inline int primitiveId(const fcl::BVNodeBase& node) { return -(node.first_child + 1); }

/// Asks for a queued node's two children to be brought into cache: they are
/// read when it is popped, and the hierarchy (~250 bytes a node for OBBRSS) is
/// far larger than the cache for meshes of 1e4 triangles, so without it each
/// pop waits on memory.
template <typename BV>
void prefetchChildren(const fcl::BVHModel<BV>& model, const fcl::BVNodeBase& node) {
  const char* first = reinterpret_cast<const char*>(&model.getBV(node.first_child));
  constexpr std::size_t kBytes = 2 * sizeof(fcl::BVNode<BV>), kLine = 64;
  for (std::size_t offset = 0; offset < kBytes; offset += kLine) {
    __builtin_prefetch(first + offset);
  }
}

/// The vertex indices of the model's triangle, read in place: fcl::Triangle's
/// operator[] is defined out of line in libfcl (a call per index), and the
/// class is standard-layout with the index array its only member, so its
/// address is the array's.
using VertexIds = std::size_t[3];
template <typename BV>
const VertexIds& vertexIds(const fcl::BVHModel<BV>& model, int triangle) {
  static_assert(std::is_standard_layout_v<fcl::Triangle> &&
                sizeof(fcl::Triangle) == sizeof(VertexIds));
  return *reinterpret_cast<const VertexIds*>(&model.tri_indices[triangle]);
}

struct MeshDistanceAnswer {
  double distance = std::numeric_limits<double>::infinity();
  int triangle = -1;  ///< -1: nothing closer than the starting best
  Vec3 p_disk{Vec3::Zero()}, p_triangle{Vec3::Zero()};  ///< frame M
};

/// The disk against the mesh, only triangles closer than `best` (the result's
/// distance so far) counted.
template <typename BV>
MeshDistanceAnswer diskMeshDistance(const DiskInShape& disk, const fcl::BVHModel<BV>& model,
                                    double best, double rel_err, double abs_err) {
  using S = typename BV::S;
  // The volumes of a float mesh hold its triangles to float rounding.
  const double volume_pad =
      kEnvironmentBoundPadUlps * double(std::numeric_limits<S>::epsilon());
  const double triangle_pad = kEnvironmentBoundPadUlps * std::numeric_limits<double>::epsilon();
  MeshDistanceAnswer answer;
  answer.distance = best;
  if (model.getNumBVs() <= 0) return answer;

  const auto vertex = [&model](std::size_t index) -> Vec3 {
    return model.vertices[index].template cast<double>();
  };
  const auto consider = [&](int triangle, const Vec3& p_disk, const Vec3& p_triangle,
                            double distance) {
    if (distance < answer.distance) {
      answer.distance = distance;
      answer.triangle = triangle;
      answer.p_disk = p_disk;
      answer.p_triangle = p_triangle;
    }
  };

  // A node and its bound; a leaf is queued only when its triangle needs the
  // solver. Ordered by the bound alone (a tie-break on the node costs more
  // than it orders): equal bounds leave in the heap's order, the same on every
  // run.
  struct Entry {
    double bound;
    int node;
    bool operator>(const Entry& other) const { return bound > other.bound; }
  };
  std::vector<Entry>& scratch = scratchQueue<Entry>();
  const double disk_magnitude = diskBoundMagnitude(disk);
  const double disk_scale = disk.r + disk.c.norm();  // the leaf solver's share
  // The padded bound of an inner node worth opening, or -1 (pruned).
  const auto settleVolume = [&](const fcl::BVNode<BV>& node, const VolumeBound& volume) {
    double bound = volume.bound - volume_pad * (disk_magnitude + volume.magnitude);
    if (!(bound > 0.0)) bound = 0.0;  // NaN volumes are searched, never pruned
    if (cannotImprove(bound, answer.distance, rel_err, abs_err)) return -1.0;
    prefetchChildren(model, node);
    return bound;
  };
  // The bound of a node worth opening, or -1 (pruned, or a leaf settled here).
  const auto evaluate = [&](int node_index) -> double {
    const auto& node = model.getBV(node_index);
    double bound;
    if (isLeaf(node)) {
      const int triangle = primitiveId(node);
      const auto& ids = vertexIds(model, triangle);
      const Vec3 p0 = vertex(ids[0]), p1 = vertex(ids[1]), p2 = vertex(ids[2]);
      const double triangle_radius =
          std::sqrt(std::max({p0.squaredNorm(), p1.squaredNorm(), p2.squaredNorm()}));
      const LeafToDisk leaf =
          triangleToDisk(disk, p0, p1, p2, disk_scale + triangle_radius, answer.distance);
      if (leaf.exact) {
        consider(triangle, leaf.p_disk, leaf.p_leaf, leaf.distance);
        return -1.0;
      }
      if (leaf.distance >= answer.distance) return -1.0;
      bound = leaf.distance -
              triangle_pad * (disk_magnitude + triangleBoundMagnitude(p0, p1, p2));
    } else {
      return settleVolume(node, volumeBound(disk, node.bv));
    }
    if (!(bound > 0.0)) bound = 0.0;  // the pad can take a near triangle's bound below 0
    if (cannotImprove(bound, answer.distance, rel_err, abs_err)) return -1.0;
    return bound;
  };
  const double root_bound = evaluate(0);
  if (!(root_bound >= 0.0)) return answer;
  bestFirstSearch(
      scratch, Entry{root_bound, 0},
      [&](const Entry& entry, auto&& offer) {
        const auto& node = model.getBV(entry.node);
        if (isLeaf(node)) {
          const int triangle = primitiveId(node);
          const auto& ids = vertexIds(model, triangle);
          const DiskShapeSolution solution =
              solveDiskTriangle(disk, vertex(ids[0]), vertex(ids[1]), vertex(ids[2]));
          consider(triangle, solution.p, solution.q, solution.distance);
          return;
        }
        const int first = node.first_child;
        if constexpr (kPairedVolumeBounds<BV>) {
#if FCL_DISK_PAIRED_VOLUME_BOUNDS
          const auto& first_node = model.getBV(first);
          const auto& second_node = model.getBV(first + 1);
          if (!isLeaf(first_node) && !isLeaf(second_node)) {
            const auto volumes = volumeBounds(disk, first_node.bv, second_node.bv);
            const double first_bound = settleVolume(first_node, volumes[0]);
            if (first_bound >= 0.0) offer(Entry{first_bound, first});
            const double second_bound = settleVolume(second_node, volumes[1]);
            if (second_bound >= 0.0) offer(Entry{second_bound, first + 1});
            return;
          }
#endif
        }
        for (const int child : {first, first + 1}) {
          const double bound = evaluate(child);
          if (bound >= 0.0) offer(Entry{bound, child});
        }
      },
      [&](double bound) { return cannotImprove(bound, answer.distance, rel_err, abs_err); },
      [&] { return answer.distance <= 0.0; });  // an overlap: nothing is closer
  return answer;
}

}  // namespace internal
}  // namespace fcl_disk

// Disk - fcl::TriangleP (the leaf of meshes): closed forms where they certify,
// else the generic solver with the triangle's projection (its face, else its
// nearest edge) and support (a vertex).
// docs/disk_shape_distance.md, section 4.
#include "../disk_shape_pair.h"
#include "feature_candidates.h"
#include "polygon_projection.h"
#include "../leaf_solvers.h"

#include <limits>
#include <vector>

namespace fcl_disk {
namespace internal {
namespace {

/// The closed flat triangle a, b, c, in its frame (a zero-area triangle is the
/// union of its edges): TriangleProjection (polygon_projection.h) and a vertex
/// as support.
struct TriangleTarget {
  TriangleProjection triangle;

  Projection project(const Vec3& x) const { return triangle.project(x); }

  /// The centroid (the frame's origin is the mesh's, anywhere).
  Vec3 centre() const {
    return (triangle.vertices[0] + triangle.vertices[1] + triangle.vertices[2]) / 3.0;
  }

  Vec3 support(const Vec3& w) const {
    const auto& vertices = triangle.vertices;
    int best = 0;  // ties take the first vertex
    for (int i = 1; i < 3; ++i) {
      if (w.dot(vertices[i]) > w.dot(vertices[best])) best = i;
    }
    return vertices[best];
  }

  /// The face, for the nearly-parallel candidates (none when degenerate).
  template <typename Visit>
  void forEachFace(Visit&& visit) const {
    if (!(triangle.unit_normal.squaredNorm() > 0.0)) return;
    visit(triangle.unit_normal, 3, [this](int i) { return triangle.vertices[i]; });
  }
};

template <typename S>
struct TriangleTraits {
  static bool valid(const fcl::TriangleP<S>& triangle) {
    bool valid = true;
    for (const auto* v : {&triangle.a, &triangle.b, &triangle.c}) {
      valid &= (v->array().abs() <= kMaxDiskLength<S>).all();
    }
    return valid;
  }
  static double boundingRadius(const fcl::TriangleP<S>& triangle) {
    return std::sqrt(std::max({triangle.a.template cast<double>().squaredNorm(),
                               triangle.b.template cast<double>().squaredNorm(),
                               triangle.c.template cast<double>().squaredNorm()}));
  }
  static double inflation(const fcl::TriangleP<S>&) { return 0.0; }
  /// A vertex, an edge or the face nearest a disk point, or a triangle over
  /// the disk, certified without the generic solver (triangleToDisk,
  /// src/environment_bounds.h). Flattened: its helpers are inlined here,
  /// which takes fewer instructions and less time than the calls
  /// (docs/performance.md, "A Disk against FCL's primitives").
  [[gnu::flatten]] static LeafToDisk closedForm(const DiskInShape& disk,
                                                const fcl::TriangleP<S>& triangle, double scale) {
    return triangleToDisk(disk, triangle.a.template cast<double>(),
                          triangle.b.template cast<double>(), triangle.c.template cast<double>(),
                          scale);
  }
  static TriangleTarget target(const fcl::TriangleP<S>& triangle) {
    return TriangleTarget{TriangleProjection(triangle.a.template cast<double>(),
                                             triangle.b.template cast<double>(),
                                             triangle.c.template cast<double>())};
  }
  /// The directions among which the shortest separating translation lies
  /// (shortestSeparation adds the disk's normals and both signs), so the contact's
  /// depth is the exact penetration depth: the triangle's normal (zero when
  /// degenerate, then skipped), and the candidates of its vertices and edge
  /// lines (feature_candidates.h; docs/penetration_depth.md, section 7).
  template <typename Search>
  static void contactDirections(const TriangleTarget& target, const DiskInShape& disk,
                                Search* directions) {
    const auto& vertices = target.triangle.vertices;
    directions->push_back(target.triangle.unit_normal);
    for (int i = 0; i < 3; ++i) addVertexCandidates(disk, vertices[i], directions);
    for (int i = 0; i < 3; ++i) {
      const Vec3 along = vertices[(i + 1) % 3] - vertices[i];
      const double length = along.norm();
      if (length > 0.0) addEdgeLineCandidates(disk, vertices[i], along / length, directions);
    }
  }
};

}  // namespace

template <typename S>
struct DiskShapePair<fcl::TriangleP<S>>
    : GenericDiskShapePair<S, fcl::TriangleP<S>, TriangleTraits<S>> {};

DiskShapeSolution solveDiskTriangle(const DiskInShape& disk, const Vec3& a, const Vec3& b,
                                    const Vec3& c) {
  const fcl::TriangleP<double> triangle(a, b, c);
  if (!TriangleTraits<double>::valid(triangle)) {
    DiskShapeSolution nan;
    nan.distance = nan.lower_bound = std::numeric_limits<double>::quiet_NaN();
    return nan;
  }
  return DiskShapePair<fcl::TriangleP<double>>::solveInShapeFrame(disk, triangle,
                                                                   /*try_closed_form=*/false);
}

bool intersectDiskTriangle(const DiskInShape& disk, const Vec3& a, const Vec3& b, const Vec3& c,
                           FrameContact* contact) {
  const fcl::TriangleP<double> triangle(a, b, c);
  return TriangleTraits<double>::valid(triangle) &&
         DiskShapePair<fcl::TriangleP<double>>::intersectInShapeFrame(disk, triangle, contact,
                                                                      /*try_early_exit=*/false);
}

}  // namespace internal
}  // namespace fcl_disk

FCL_DISK_INSTANTIATE_DISK_SHAPE_PAIR(fcl::TriangleP)

// Disk - fcl::Convex: the generic solver with the polytope's projection (the
// nearest of the faces whose planes see the point) and support (a vertex).
// docs/disk_shape_distance.md, section 4.
#include "../disk_shape_pair.h"
#include "polygon_projection.h"

#include <vector>

namespace fcl_disk {
namespace internal {
namespace {

/// Faces whose normals are within this sine of one line are parallel: a Convex
/// whose faces are all parallel (or of zero area) is flat, a polygon, and its
/// plane tests cannot tell its inside. Far above the rounding of Newell normals
/// (a few eps), far below any real dihedral angle.
constexpr double kParallelFaceSine = 1e-12;

/// FCL's Convex: vertices, and faces encoded [k, i_1..i_k, k', ...], each listed
/// counter-clockwise seen from outside. Projection works in the shape frame.
template <typename S>
struct ConvexTarget {
  const fcl::Convex<S>* convex;

  Vec3 vertex(int index) const { return convex->getVertices()[index].template cast<double>(); }

  /// Calls visit(count, first_index_position, normal) for each face; normal by
  /// Newell's formula (outward, |normal| = twice the area; zero if degenerate).
  template <typename Visit>
  void forEachFace(Visit visit) const {
    const std::vector<int>& faces = convex->getFaces();
    std::size_t at = 0;
    for (int f = 0; f < convex->getFaceCount(); ++f) {
      const int count = faces[at];
      const int* index = &faces[at + 1];
      Vec3 normal = Vec3::Zero();
      for (int i = 0; i < count; ++i) normal += vertex(index[i]).cross(vertex(index[(i + 1) % count]));
      visit(count, index, normal);
      at += count + 1;
    }
  }

  Projection project(const Vec3& y) const {
    Projection best{y, FactoredHessian()};
    double best_squared = std::numeric_limits<double>::infinity();
    bool outside = false;
    Vec3 first_normal = Vec3::Zero(), largest_normal = Vec3::Zero();
    const int* largest_face = nullptr;
    int largest_count = 0;
    bool flat = true;
    forEachFace([&](int count, const int* index, const Vec3& normal) {
      const double area_squared = normal.squaredNorm();
      if (area_squared > largest_normal.squaredNorm()) {
        largest_normal = normal, largest_face = index, largest_count = count;
      }
      if (area_squared > 0.0) {
        if (first_normal.squaredNorm() == 0.0) first_normal = normal;
        flat &= first_normal.cross(normal).norm() <=
                kParallelFaceSine * first_normal.norm() * normal.norm();
      }
      // Only faces whose plane has y strictly outside can hold the nearest point.
      if (!(normal.dot(y - vertex(index[0])) > 0.0)) return;
      outside = true;
      const Projection on_face =
          projectOntoPolygon(y, count, [&](int i) { return vertex(index[i]); }, normal);
      const double squared = (y - on_face.q).squaredNorm();
      if (squared < best_squared) best = on_face, best_squared = squared;
    });
    if (!outside && flat && largest_face) {  // on the polygon's plane: the polygon decides
      best = projectOntoPolygon(y, largest_count, [&](int i) { return vertex(largest_face[i]); },
                                largest_normal);
    } else if (!outside) {
      return Projection{y, FactoredHessian()};
    }
    return best;
  }

  Vec3 support(const Vec3& w_S) const {
    const auto& vertices = convex->getVertices();
    std::size_t best = 0;  // ties take the first vertex
    for (std::size_t i = 1; i < vertices.size(); ++i) {
      if (w_S.dot(vertices[i].template cast<double>()) >
          w_S.dot(vertices[best].template cast<double>())) {
        best = i;
      }
    }
    return vertices[best].template cast<double>();
  }
};

template <typename S>
struct ConvexTraits {
  /// Vertices finite and in range; faces well encoded (at least three in-range
  /// indices each, exactly filling the face list).
  static bool valid(const fcl::Convex<S>& convex) {
    const auto& vertices = convex.getVertices();
    if (vertices.empty() || convex.getFaceCount() < 1) return false;
    for (const auto& v : vertices) {
      if (!((v.array().abs() <= kMaxDiskLength<S>).all())) return false;
    }
    const std::vector<int>& faces = convex.getFaces();
    std::size_t at = 0;
    for (int f = 0; f < convex.getFaceCount(); ++f) {
      if (at >= faces.size()) return false;
      const int count = faces[at];
      if (count < 3 || at + 1 + std::size_t(count) > faces.size()) return false;
      for (int i = 1; i <= count; ++i) {
        if (faces[at + i] < 0 || std::size_t(faces[at + i]) >= vertices.size()) return false;
      }
      at += count + 1;
    }
    return true;
  }
  static double boundingRadius(const fcl::Convex<S>& convex) {
    double largest = 0.0;
    for (const auto& v : convex.getVertices()) {
      largest = std::max(largest, v.template cast<double>().squaredNorm());
    }
    return std::sqrt(largest);
  }
  static double inflation(const fcl::Convex<S>&) { return 0.0; }
  static ConvexTarget<S> target(const fcl::Convex<S>& convex) { return ConvexTarget<S>{&convex}; }
  /// The face normals.
  static std::vector<Vec3> contactDirections(const ConvexTarget<S>& target) {
    std::vector<Vec3> normals;
    target.forEachFace([&](int, const int*, const Vec3& normal) {
      normals.push_back(normal);
    });
    return normals;
  }
};

}  // namespace

template <typename S>
struct DiskShapePair<fcl::Convex<S>>
    : GenericDiskShapePair<S, fcl::Convex<S>, ConvexTraits<S>> {};

}  // namespace internal
}  // namespace fcl_disk

FCL_DISK_INSTANTIATE_DISK_SHAPE_PAIR(fcl::Convex)

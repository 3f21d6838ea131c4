// Disk - fcl::Convex: the generic solver with the polytope's projection (the
// nearest of the faces whose planes see the point) and support (a vertex).
// docs/disk_shape_distance.md, section 4.
#include "../disk_shape_pair.h"
#include "feature_candidates.h"
#include "polygon_projection.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace fcl_disk {
namespace internal {
namespace {

/// Faces whose normals are within this sine of one line are parallel: a Convex
/// whose faces are all parallel (or of zero area) is flat, a polygon, and its
/// plane tests cannot tell its inside. Far above the rounding of Newell normals
/// (a few eps), far below any real dihedral angle.
constexpr double kParallelFaceSine = 1e-12;

/// A face of the polytope: where its vertex indices start in FCL's face list,
/// how many, its outward unit normal (zero for a face of zero area), the
/// plane's offset (normal . vertex), and a ball holding the polygon (centre the
/// vertices' mean), whose distance bounds the polygon's from below.
struct ConvexFace {
  std::size_t start;  ///< the face's first vertex index in FCL's face list
  int count;
  Vec3 unit_normal;
  double offset;
  Vec3 centre;
  double radius;
};

/// What a query needs of a Convex beyond FCL's lists, computed from them: the
/// face planes and balls (Newell's normals), whether the polytope is flat, and
/// its largest face.
struct ConvexGeometry {
  bool valid = false;  ///< ConvexTraits::valid's verdict on the lists
  std::vector<ConvexFace> faces;
  /// Per face: its triangle projection when it is a triangle (most hulls).
  std::vector<TriangleProjection> triangles;
  /// The face planes again, one column per coordinate (n_x, n_y, n_z, offset),
  /// so that the height scan of every projection runs vectorised.
  Eigen::Matrix<double, Eigen::Dynamic, 4> planes;
  /// The vertices in double, one column per coordinate: the support's scan
  /// runs vectorised.
  Eigen::Matrix<double, Eigen::Dynamic, 3> points;
  int largest_face = -1;  ///< the face of largest area
  bool flat = true;       ///< every face parallel or of zero area: a polygon
  double bounding_radius = 0.0;  ///< the largest vertex norm
  /// The largest spread of a face's vertices along its normal: 0 for planar
  /// faces up to rounding; ~1e-7 of the size for quadrilaterals whose
  /// vertices were rounded to float, or data planar only to its precision.
  double face_thickness = 0.0;
};

/// The geometry of the Convex queried last on this thread, with a copy of the
/// lists it was computed from: a planner queries the same hull many times in a
/// row, and computing the planes costs more than the query's projections
/// (76 faces: ~14k instructions). A hit needs the lists equal value for value,
/// so a hull destroyed and another built at the same address is recomputed.
template <typename S>
struct ConvexGeometryCache {
  std::vector<fcl::Vector3<S>> vertices;
  std::vector<int> face_list;
  int face_count = -1;
  ConvexGeometry geometry;
  const void* verified = nullptr;  ///< the hull whose lists geometryOf() compared last
};

/// FCL's Convex: vertices, and faces encoded [k, i_1..i_k, k', ...], each listed
/// counter-clockwise seen from outside. Projection works in the shape frame,
/// with the face planes of ConvexGeometry (computed once per hull and thread,
/// not per projection). One query at a time per thread holds the geometry.
template <typename S>
struct ConvexTarget {
  const fcl::Convex<S>* convex;
  const int* list;                   ///< FCL's face list
  const std::vector<ConvexFace>& faces;
  const std::vector<TriangleProjection>& triangles;
  const Eigen::Matrix<double, Eigen::Dynamic, 4>& planes;
  const Eigen::Matrix<double, Eigen::Dynamic, 3>& points;
  int largest_face;
  bool flat;
  double face_thickness;

  explicit ConvexTarget(const fcl::Convex<S>& shape, const ConvexGeometry& geometry)
      : convex(&shape),
        list(shape.getFaces().data()),
        faces(geometry.faces),
        triangles(geometry.triangles),
        planes(geometry.planes),
        points(geometry.points),
        largest_face(geometry.largest_face),
        flat(geometry.flat),
        face_thickness(geometry.face_thickness) {}

  static ConvexGeometryCache<S>& cache() {
    thread_local ConvexGeometryCache<S> cache;
    return cache;
  }

  /// This thread's geometry of `shape`, from the cache when its lists are
  /// unchanged (compared value for value); `shape` is then the cache's
  /// verified hull.
  static const ConvexGeometry& geometryOf(const fcl::Convex<S>& shape) {
    ConvexGeometryCache<S>& cached = cache();
    const auto& vertices = shape.getVertices();
    const auto& face_list = shape.getFaces();
    if (!(cached.face_count == shape.getFaceCount() && cached.vertices == vertices &&
          cached.face_list == face_list)) {
      cached.face_count = -1;  // invalid while rebuilt
      cached.verified = nullptr;
      cached.vertices = vertices;
      cached.face_list = face_list;
      cached.geometry = computeGeometry(shape);
      cached.face_count = shape.getFaceCount();
    }
    cached.verified = &shape;
    return cached.geometry;
  }

  /// The geometry of the hull geometryOf() verified last on this thread, when
  /// that is `shape`: within one query (ConvexTraits::valid first, then
  /// boundingRadius and target) the lists are compared once.
  static const ConvexGeometry& verifiedGeometryOf(const fcl::Convex<S>& shape) {
    const ConvexGeometryCache<S>& cached = cache();
    return cached.verified == &shape ? cached.geometry : geometryOf(shape);
  }

  /// |v| without overflow or underflow: the plain square root where the
  /// square is a normal double (almost always), stableNorm otherwise.
  static double safeNorm(const Vec3& v) {
    const double squared = v.squaredNorm();
    if (squared >= std::numeric_limits<double>::min() && squared <= std::numeric_limits<double>::max()) {
      return std::sqrt(squared);
    }
    return v.stableNorm();
  }

  static ConvexGeometry computeGeometry(const fcl::Convex<S>& shape) {
    ConvexGeometry geometry;
    geometry.valid = listsAreValid(shape);
    if (!geometry.valid) return geometry;
    const auto vertex = [&](int index) { return shape.getVertices()[index].template cast<double>(); };
    geometry.points.resize(Eigen::Index(shape.getVertices().size()), 3);
    for (std::size_t i = 0; i < shape.getVertices().size(); ++i) {
      const Vec3 v = vertex(int(i));
      geometry.points.row(Eigen::Index(i)) = v.transpose();
      geometry.bounding_radius = std::max(geometry.bounding_radius, safeNorm(v));
    }
    const std::vector<int>& list = shape.getFaces();
    std::vector<ConvexFace>& faces = geometry.faces;
    int& largest_face = geometry.largest_face;
    bool& flat = geometry.flat;
    faces.reserve(shape.getFaceCount());
    geometry.triangles.resize(shape.getFaceCount());
    geometry.planes.resize(shape.getFaceCount(), 4);
    std::size_t at = 0;
    double largest_area = -1.0;
    Vec3 first_normal = Vec3::Zero();
    for (int f = 0; f < shape.getFaceCount(); ++f) {
      const int count = list[at];
      const int* index = &list[at + 1];
      // Newell's normal; for a triangle it is the one cross product (b - a) x (c - a).
      Vec3 normal;
      if (count == 3) {
        const Vec3 a = vertex(index[0]);
        normal = (vertex(index[1]) - a).cross(vertex(index[2]) - a);
        geometry.triangles[f] = TriangleProjection(a, vertex(index[1]), vertex(index[2]));
      } else {
        normal = vertex(index[count - 1]).cross(vertex(index[0]));
        for (int i = 0; i + 1 < count; ++i) normal += vertex(index[i]).cross(vertex(index[i + 1]));
      }
      // |normal| is a squared length and the cross product of two normals a
      // fourth power, beyond double at 1e100: safeNorm and unit normals.
      const double area = safeNorm(normal);
      if (area > largest_area) largest_area = area, largest_face = f;
      const Vec3 unit = area > 0.0 ? Vec3(normal / area) : Vec3::Zero();
      if (area > 0.0) {
        if (first_normal.squaredNorm() == 0.0) first_normal = unit;
        flat &= first_normal.cross(unit).norm() <= kParallelFaceSine;
      }
      Vec3 centre = Vec3::Zero();
      for (int i = 0; i < count; ++i) centre += vertex(index[i]);
      centre /= count;
      double radius = 0.0, lowest = 0.0, highest = 0.0;
      for (int i = 0; i < count; ++i) {
        radius = std::max(radius, safeNorm(vertex(index[i]) - centre));
        const double height = unit.dot(vertex(index[i]) - centre);
        lowest = std::min(lowest, height), highest = std::max(highest, height);
      }
      geometry.face_thickness = std::max(geometry.face_thickness, highest - lowest);
      faces.push_back(ConvexFace{at + 1, count, unit, unit.dot(vertex(index[0])), centre, radius});
      geometry.planes.row(f) << unit.transpose(), faces.back().offset;
      at += count + 1;
    }
    return geometry;
  }

  /// The edges of the faces, each once (vertex indices, the smaller first):
  /// only the penetration candidates need them, so they are not part of the
  /// per-hull geometry every distance query pays for.
  static std::vector<std::array<int, 2>> edgesOf(const fcl::Convex<S>& shape) {
    std::vector<std::uint64_t> keys;
    const std::vector<int>& list = shape.getFaces();
    std::size_t at = 0;
    for (int f = 0; f < shape.getFaceCount(); ++f) {
      const int count = list[at];
      for (int i = 0; i < count; ++i) {
        const auto from = std::uint32_t(list[at + 1 + i]);
        const auto to = std::uint32_t(list[at + 1 + (i + 1) % count]);
        keys.push_back(std::uint64_t(std::min(from, to)) << 32 | std::max(from, to));
      }
      at += count + 1;
    }
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    std::vector<std::array<int, 2>> edges;
    edges.reserve(keys.size());
    for (const std::uint64_t key : keys) edges.push_back({int(key >> 32), int(key & 0xffffffffu)});
    return edges;
  }

  /// Vertices finite and in range; faces well encoded (at least three in-range
  /// indices each, exactly filling the face list).
  static bool listsAreValid(const fcl::Convex<S>& convex) {
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

  Vec3 vertex(int index) const { return convex->getVertices()[index].template cast<double>(); }

  Projection ontoFace(const Vec3& y, const ConvexFace& face) const {
    if (face.count == 3) return triangles[&face - faces.data()].project(y);
    return projectOntoPolygon(y, face.count, [&](int i) { return vertex(list[face.start + i]); },
                              face.unit_normal);
  }

  /// Only faces whose planes have y strictly outside can hold the nearest point,
  /// and a face's plane distance bounds its polygon's distance from below: the
  /// face whose plane is farthest first (usually the answer: y's foot on it lies
  /// inside it), then the others whose plane distance can still beat the best.
  Projection project(const Vec3& y) const {
    // Every plane's height of y, in one vectorised pass over the plane columns.
    thread_local Eigen::VectorXd heights;
    const std::size_t face_count = faces.size();
    heights.noalias() = planes.col(0) * y.x() + planes.col(1) * y.y() + planes.col(2) * y.z() -
                        planes.col(3);
    const double* height_of = heights.data();
    Eigen::Index farthest_index = 0;
    const double farthest_height = heights.maxCoeff(&farthest_index);
    const int farthest = farthest_height > 0.0 ? int(farthest_index) : -1;
    if (farthest < 0) {
      // Inside every face plane: inside the solid, or on a flat polytope's plane,
      // where its largest face (the polygon) decides; when every face has zero
      // area (a polytope collapsed to a segment or a point) the nearest of the
      // faces' edges does.
      if (!flat || largest_face < 0) return Projection{y, FactoredHessian()};
      if (faces[largest_face].unit_normal.squaredNorm() > 0.0) {
        return ontoFace(y, faces[largest_face]);
      }
      Projection best = ontoFace(y, faces[0]);
      for (std::size_t f = 1; f < faces.size(); ++f) {
        const Projection on_face = ontoFace(y, faces[f]);
        if ((y - on_face.q).squaredNorm() < (y - best.q).squaredNorm()) best = on_face;
      }
      return best;
    }
    Projection best = ontoFace(y, faces[farthest]);
    double best_distance = (y - best.q).norm();
    // The farthest plane's distance bounds the polytope's: reached, it is optimal.
    if (best_distance <= farthest_height) return best;
    // q is the polytope's point nearest y iff no vertex lies beyond q along
    // y - q (the optimality condition (y - q).(v - q) <= 0 for every point v of
    // the hull, checked at its vertices): mostly q is on the farthest face's
    // boundary and this one support scan settles it.
    const Vec3 away = y - best.q;
    if (supportValue(away) <= away.dot(best.q)) return best;
    for (std::size_t f = 0; f < face_count; ++f) {
      if (int(f) == farthest) continue;
      const double height = height_of[f];
      if (!(height > 0.0) || !(height < best_distance)) continue;
      const double reach = best_distance + faces[f].radius;
      if (!((y - faces[f].centre).squaredNorm() < reach * reach)) continue;
      const Projection on_face = ontoFace(y, faces[f]);
      const double distance = (y - on_face.q).norm();
      if (distance < best_distance) best = on_face, best_distance = distance;
    }
    return best;
  }

  /// w.v for every vertex v, in one vectorised pass (this thread's buffer,
  /// valid until the next call).
  const Eigen::VectorXd& alongVertices(const Vec3& w) const {
    thread_local Eigen::VectorXd along;
    along.noalias() = points.col(0) * w.x() + points.col(1) * w.y() + points.col(2) * w.z();
    return along;
  }

  /// How far apart the polytope of the face planes (project) and the hull of
  /// the vertices (support) may be: the faces' thickness, by which a
  /// certificate comparing the two cannot close (supportMismatch in
  /// disk_shape_solver.h).
  double supportMismatch() const { return face_thickness; }

  /// max over the vertices of w.v.
  double supportValue(const Vec3& w) const { return alongVertices(w).maxCoeff(); }

  Vec3 support(const Vec3& w) const {
    Eigen::Index best = 0;  // ties take the first vertex
    alongVertices(w).maxCoeff(&best);
    return points.row(best).transpose();
  }

  /// The faces of nonzero area, for the nearly-parallel candidates.
  template <typename Visit>
  void forEachFace(Visit&& visit) const {
    for (const ConvexFace& face : faces) {
      if (!(face.unit_normal.squaredNorm() > 0.0)) continue;
      visit(face.unit_normal, face.count, [&](int i) { return vertex(list[face.start + i]); });
    }
  }
};

template <typename S>
struct ConvexTraits {
  /// Vertices finite and in range; faces well encoded (ConvexTarget::listsAreValid),
  /// decided once per hull and thread with its geometry.
  static bool valid(const fcl::Convex<S>& convex) {
    return ConvexTarget<S>::geometryOf(convex).valid;
  }
  static double boundingRadius(const fcl::Convex<S>& convex) {
    return ConvexTarget<S>::verifiedGeometryOf(convex).bounding_radius;
  }
  static double inflation(const fcl::Convex<S>&) { return 0.0; }
  static ConvexTarget<S> target(const fcl::Convex<S>& convex) {
    return ConvexTarget<S>(convex, ConvexTarget<S>::verifiedGeometryOf(convex));
  }
  /// The directions among which the shortest separating translation lies
  /// (shortestSeparation adds the disk's normals and both signs), so the contact's
  /// depth is the exact penetration depth of a Convex whose faces bound the
  /// hull of its vertices: the face normals, and the vertices' and edge lines'
  /// candidates (feature_candidates.h; docs/penetration_depth.md, section 7).
  template <typename Search>
  static void contactDirections(const ConvexTarget<S>& target, const DiskInShape& disk,
                                Search* directions) {
    const auto& vertices = target.convex->getVertices();
    for (const ConvexFace& face : target.faces) directions->push_back(face.unit_normal);
    for (const auto& vertex : vertices) {
      addVertexCandidates(disk, vertex.template cast<double>(), directions);
    }
    for (const auto& edge : ConvexTarget<S>::edgesOf(*target.convex)) {
      const Vec3 from = vertices[edge[0]].template cast<double>();
      const Vec3 along = vertices[edge[1]].template cast<double>() - from;
      const double length = ConvexTarget<S>::safeNorm(along);
      if (length > 0.0) addEdgeLineCandidates(disk, from, along / length, directions);
    }
  }
};

}  // namespace

template <typename S>
struct DiskShapePair<fcl::Convex<S>>
    : GenericDiskShapePair<S, fcl::Convex<S>, ConvexTraits<S>> {};

}  // namespace internal
}  // namespace fcl_disk

FCL_DISK_INSTANTIATE_DISK_SHAPE_PAIR(fcl::Convex)

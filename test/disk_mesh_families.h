// Meshes, octrees and disk poses for the Disk-against-mesh and Disk-against-
// octree tests. Meshes and octrees are kept as plain data (vertices and
// triangles; occupied cells) so that the FCL geometries and the long-double
// reference are built from the same numbers; the pose families are written
// against a "surface" (the points, faces and size of a mesh or an octree), so
// both get the same families.
#pragma once

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/geometric_shape_to_BVH_model.h>
#include <fcl/geometry/octree/octree.h>
#include <fcl/math/bv/OBBRSS.h>

#include <octomap/OcTree.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "test_random.h"

namespace fcl_disk_test {
namespace mesh_families {

using Vector3d = Eigen::Vector3d;
using Transform3d = fcl::Transform3<double>;

// ---- meshes ---------------------------------------------------------------------

/// A triangle mesh in its own frame M: vertices and index triples (a triangle's
/// id is its position here; FCL's BVHModel keeps that order).
struct Mesh {
  std::string name;
  std::vector<Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;

  const Vector3d& vertex(int triangle, int k) const { return vertices[triangles[triangle][k]]; }
  /// max |v| over the vertices: the mesh's bounding radius about its frame origin.
  double boundingRadius() const {
    double r = 0;
    for (const Vector3d& v : vertices) r = std::max(r, v.norm());
    return r;
  }
  /// Twice the triangle's area (0 for a degenerate one).
  double doubleArea(int t) const {
    return (vertex(t, 1) - vertex(t, 0)).cross(vertex(t, 2) - vertex(t, 0)).norm();
  }
};

/// The mesh of an FCL shape, as fcl::generateBVHModel triangulates it.
template <typename Shape, typename... Args>
Mesh generatedMesh(const std::string& name, const Shape& shape, Args... args) {
  fcl::BVHModel<fcl::OBBRSS<double>> model;
  fcl::generateBVHModel(model, shape, Transform3d::Identity(), args...);
  Mesh mesh;
  mesh.name = name;
  for (int i = 0; i < model.num_vertices; ++i) mesh.vertices.push_back(model.vertices[i]);
  for (int t = 0; t < model.num_tris; ++t) {
    const fcl::Triangle& tri = model.tri_indices[t];
    mesh.triangles.push_back({int(tri[0]), int(tri[1]), int(tri[2])});
  }
  return mesh;
}

/// A closed box surface (12 triangles).
inline Mesh boxMesh() { return generatedMesh("box", fcl::Box<double>(1.2, 0.8, 0.6)); }

/// A closed sphere surface of radius 1, `seg` segments by `ring` rings.
inline Mesh sphereMesh(unsigned seg, unsigned ring) {
  return generatedMesh("sphere", fcl::Sphere<double>(1.0), seg, ring);
}

/// `count` independent triangles of size ~0.7 with centres in the unit ball
/// (no shared vertices; they cross and overlap each other).
inline Mesh triangleSoup(int count, std::uint64_t seed) {
  Random rng(seed);
  Mesh mesh;
  mesh.name = "soup";
  for (int t = 0; t < count; ++t) {
    const Vector3d centre = rng.inBall(1.0);
    const int base = int(mesh.vertices.size());
    for (int k = 0; k < 3; ++k) mesh.vertices.push_back(centre + rng.inBall(0.35));
    mesh.triangles.push_back({base, base + 1, base + 2});
  }
  return mesh;
}

/// A soup of degenerate triangles among ordinary ones: zero area (a repeated
/// vertex, three collinear vertices, all three vertices equal) and slivers (the
/// third vertex 1e-14..1e-6 off the opposite edge), in rotation.
inline Mesh degenerateMesh(int count, std::uint64_t seed) {
  Random rng(seed);
  Mesh mesh;
  mesh.name = "degenerate";
  for (int t = 0; t < count; ++t) {
    const Vector3d a = rng.inBall(1.0);
    Vector3d b = a + rng.inBall(0.5);
    Vector3d c;
    switch (t % 6) {
      case 0: c = a + rng.inBall(0.4); break;  // ordinary
      case 1: c = a; break;                   // repeated vertex: the segment ab
      case 2: c = a + rng.uniform(-0.5, 1.5) * (b - a); break;  // collinear
      case 3: c = b = a; break;               // a point
      default: {                              // sliver
        const Vector3d off = (b - a).cross(rng.unitVector()).normalized();
        c = a + rng.uniform01() * (b - a) + std::pow(10.0, rng.uniform(-14, -6)) * off;
      }
    }
    const int base = int(mesh.vertices.size());
    mesh.vertices.insert(mesh.vertices.end(), {a, b, c});
    mesh.triangles.push_back({base, base + 1, base + 2});
  }
  return mesh;
}

/// A height field over [-1, 1]^2, n x n squares split into 2 n^2 triangles: an
/// open surface that disks cut through.
inline Mesh terrainMesh(int n) {
  Mesh mesh;
  mesh.name = "terrain";
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      const double x = -1 + 2.0 * i / n, y = -1 + 2.0 * j / n;
      mesh.vertices.emplace_back(x, y, 0.2 * std::sin(2.1 * x + 0.3) * std::cos(1.7 * y));
    }
  }
  const auto id = [n](int i, int j) { return i * (n + 1) + j; };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      mesh.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      mesh.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return mesh;
}

inline Mesh scaledMesh(Mesh mesh, double k) {
  for (Vector3d& v : mesh.vertices) v *= k;
  return mesh;
}

/// The mesh with its vertices rounded to S (as an S BVHModel stores them).
template <typename S>
Mesh roundedMesh(Mesh mesh) {
  for (Vector3d& v : mesh.vertices) v = v.cast<S>().template cast<double>();
  return mesh;
}

/// The mesh as an FCL model with bounding volume BV (vertices rounded to BV's scalar).
template <typename BV>
std::shared_ptr<fcl::BVHModel<BV>> bvhOf(const Mesh& mesh) {
  using S = typename BV::S;
  std::vector<fcl::Vector3<S>> vertices;
  for (const Vector3d& v : mesh.vertices) vertices.push_back(v.cast<S>());
  std::vector<fcl::Triangle> triangles;
  for (const auto& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  auto model = std::make_shared<fcl::BVHModel<BV>>();
  model->beginModel();
  model->addSubModel(vertices, triangles);
  model->endModel();
  model->computeLocalAABB();
  return model;
}

// ---- octrees --------------------------------------------------------------------

/// Octree leaves are set by integer cell index: cell (i, j, k) of an octomap
/// tree of resolution res is [i res, (i + 1) res] x ... in the tree's frame.
struct Cell {
  int i, j, k;
  float log_odds;
};

/// An octomap tree described by its cells; occupancy threshold `threshold`
/// (a probability), FCL reads it when wrapping the tree.
struct OcTreeData {
  std::string name;
  double resolution;
  double threshold;
  std::vector<Cell> cells;

  std::shared_ptr<const octomap::OcTree> build() const {
    auto tree = std::make_shared<octomap::OcTree>(resolution);
    tree->setOccupancyThres(threshold);
    for (const Cell& c : cells) {
      tree->setNodeValue((c.i + 0.5) * resolution, (c.j + 0.5) * resolution, (c.k + 0.5) * resolution,
                         c.log_odds);
    }
    return tree;
  }
};

/// Log-odds written into cells: occupied, free, and uncertain (between FCL's
/// free threshold, log-odds 0, and the occupancy threshold of the trees below,
/// probability 0.6 = log-odds 0.405).
constexpr float kOccupiedLogOdds = 2.0f;
constexpr float kFreeLogOdds = -2.0f;
constexpr float kUncertainLogOdds = 0.2f;
constexpr double kOcTreeThreshold = 0.6;

/// Random blobs of occupied cells, with free and uncertain cells around them
/// and a few cells exactly at the occupancy threshold (occupied for FCL: its
/// test is log-odds >= threshold).
inline OcTreeData blobOcTree(std::uint64_t seed) {
  Random rng(seed);
  OcTreeData data{"blobs", 0.05, kOcTreeThreshold, {}};
  const float at_threshold = float(std::log(kOcTreeThreshold / (1 - kOcTreeThreshold)));
  for (int blob = 0; blob < 5; ++blob) {
    const Vector3d centre = rng.inBall(8.0);  // in cells
    const double radius = rng.uniform(1.2, 2.6);
    for (int i = -3; i <= 3; ++i) {
      for (int j = -3; j <= 3; ++j) {
        for (int k = -3; k <= 3; ++k) {
          const Vector3d p = centre.array().round().matrix() + Vector3d(i, j, k);
          const double r = (p - centre).norm();
          float value;
          if (r <= radius) {
            value = rng.chance(0.1) ? at_threshold : kOccupiedLogOdds;
          } else if (r <= radius + 1) {
            value = rng.chance(0.5) ? kFreeLogOdds : kUncertainLogOdds;
          } else {
            continue;
          }
          data.cells.push_back({int(p.x()), int(p.y()), int(p.z()), value});
        }
      }
    }
  }
  return data;
}

/// A wall one cell thick (the cells i = 0, 16 x 16 of them, resolution 0.1),
/// free cells in front of it (i = 1) and uncertain ones behind (i = -1), with a
/// few holes.
inline OcTreeData wallOcTree() {
  OcTreeData data{"wall", 0.1, kOcTreeThreshold, {}};
  for (int j = -8; j < 8; ++j) {
    for (int k = -8; k < 8; ++k) {
      const bool hole = (j == 3 && k == -2) || (j == -5 && k == 4);
      data.cells.push_back({0, j, k, hole ? kFreeLogOdds : kOccupiedLogOdds});
      if ((j + k) % 3 == 0) data.cells.push_back({1, j, k, kFreeLogOdds});
      if ((j - k) % 4 == 0) data.cells.push_back({-1, j, k, kUncertainLogOdds});
    }
  }
  return data;
}

// ---- surfaces and disk poses ------------------------------------------------------

/// What the pose families need to know of a mesh or an octree, in its frame E:
/// points whose convex hull is the hull of the set (vertices, cell corners), a
/// way to draw a point of the set with a unit normal of a face through it, and
/// the set's bounding radius about the frame origin.
struct Surface {
  std::vector<Vector3d> hull_points;
  std::function<void(Random&, Vector3d* point, Vector3d* normal)> sample_face;
  double bounding_radius;
};

inline Surface surfaceOf(const Mesh& mesh) {
  Surface s;
  s.hull_points = mesh.vertices;
  s.bounding_radius = mesh.boundingRadius();
  std::vector<int> faces;  // triangles with a well-defined normal
  for (int t = 0; t < int(mesh.triangles.size()); ++t) {
    if (mesh.doubleArea(t) > 1e-3 * s.bounding_radius * s.bounding_radius) faces.push_back(t);
  }
  s.sample_face = [mesh, faces](Random& rng, Vector3d* point, Vector3d* normal) {
    const int t = faces[std::min(int(rng.uniform01() * faces.size()), int(faces.size()) - 1)];
    double u = rng.uniform01(), v = rng.uniform01();
    if (u + v > 1) u = 1 - u, v = 1 - v;
    const Vector3d a = mesh.vertex(t, 0), b = mesh.vertex(t, 1), c = mesh.vertex(t, 2);
    *point = a + u * (b - a) + v * (c - a);
    *normal = (b - a).cross(c - a).normalized();
  };
  return s;
}

/// The boxes of occupied cells (min, max corners in the tree frame) as a surface.
inline Surface surfaceOfBoxes(const std::vector<std::pair<Vector3d, Vector3d>>& boxes) {
  Surface s;
  s.bounding_radius = 0;
  for (const auto& box : boxes) {
    for (int corner = 0; corner < 8; ++corner) {
      const Vector3d p((corner & 1) ? box.second.x() : box.first.x(),
                       (corner & 2) ? box.second.y() : box.first.y(),
                       (corner & 4) ? box.second.z() : box.first.z());
      s.hull_points.push_back(p);
      s.bounding_radius = std::max(s.bounding_radius, p.norm());
    }
  }
  s.sample_face = [boxes](Random& rng, Vector3d* point, Vector3d* normal) {
    const auto& box = boxes[std::min(int(rng.uniform01() * boxes.size()), int(boxes.size()) - 1)];
    const int axis = std::min(int(rng.uniform01() * 3), 2);
    const bool upper = rng.chance(0.5);
    for (int i = 0; i < 3; ++i) (*point)[i] = rng.uniform(box.first[i], box.second[i]);
    (*point)[axis] = upper ? box.second[axis] : box.first[axis];
    *normal = Vector3d::Zero();
    (*normal)[axis] = upper ? 1 : -1;
  };
  return s;
}

enum class Family { random_near, separated, touching, crossing, parallel_face, far_away, scaled };

inline const char* familyName(Family f) {
  switch (f) {
    case Family::random_near: return "random_near";
    case Family::separated: return "separated";
    case Family::touching: return "touching";
    case Family::crossing: return "crossing";
    case Family::parallel_face: return "parallel_face";
    case Family::far_away: return "far_away";
    case Family::scaled: return "scaled";
  }
  return "?";
}

inline std::vector<Family> allFamilies() {
  return {Family::random_near, Family::separated,  Family::touching, Family::crossing,
          Family::parallel_face, Family::far_away, Family::scaled};
}

/// A disk against a mesh or octree whose frame E has pose X_WE, the set scaled
/// by `scale` about E's origin (family `scaled`; 1 otherwise).
struct DiskPose {
  Family family;
  std::string detail;
  double radius;
  Transform3d X_WD;
  Transform3d X_WE;
  double scale = 1;
  /// The distance fixed by construction (separated, touching, crossing), or NaN.
  double known_distance = std::numeric_limits<double>::quiet_NaN();
};

inline Transform3d poseOf(const Eigen::Matrix3d& R, const Vector3d& t) {
  Transform3d X = Transform3d::Identity();
  X.linear() = R;
  X.translation() = t;
  return X;
}

/// A rotation taking +z to `normal`.
inline Eigen::Matrix3d rotationWithNormal(const Vector3d& normal, Random& rng) {
  const Eigen::Matrix3d R =
      Eigen::Quaterniond::FromTwoVectors(Vector3d::UnitZ(), normal.normalized()).toRotationMatrix();
  // A random turn about the normal (the disk is symmetric, the pose is not).
  return R * Eigen::AngleAxisd(rng.uniform(0, 2 * M_PI), Vector3d::UnitZ()).toRotationMatrix();
}

/// `count` disk poses of `family` against `surface` with pose X_WE; radii are
/// drawn in [radius_lo, radius_hi] times the surface's bounding radius.
///
/// separated / touching: for a unit direction w (disk towards the set), the
/// disk's highest point along w is put at gap * w below the set's lowest hull
/// point along w: the plane between them separates the sets by gap and those
/// two points are gap apart, so the distance is exactly gap (0 for touching).
/// crossing: the disk's centre is a point of a face (distance 0), the disk
/// tilted at random. parallel_face: the disk's normal is a face's normal (or
/// within 1e-8..1e-3 rad of it), centre 1e-9..1e-1 of the size above a face
/// point. far_away: random_near with the set moved 1e5 from the origin.
/// scaled: random_near with the set scaled by 1e-3..1e3 (the caller scales the
/// set by pose.scale).
inline std::vector<DiskPose> diskPoses(const Surface& surface, const Transform3d& X_WE_base,
                                       Family family, int count, double radius_lo, double radius_hi,
                                       std::uint64_t seed) {
  Random rng(seed * 1000003u + std::uint64_t(family) * 7919u);
  std::vector<DiskPose> out;
  const double size = surface.bounding_radius;
  while (int(out.size()) < count) {
    DiskPose p;
    p.family = family;
    p.X_WE = X_WE_base;
    double k = 1;
    if (family == Family::scaled) k = std::pow(10.0, rng.uniform(-3, 3));
    if (family == Family::far_away) p.X_WE.translation() += 1e5 * rng.unitVector();
    p.scale = k;
    p.radius = k * size * rng.uniform(radius_lo, radius_hi);
    const Eigen::Matrix3d& R_WE = p.X_WE.linear();
    const Vector3d& t_WE = p.X_WE.translation();
    switch (family) {
      case Family::random_near:
      case Family::far_away:
      case Family::scaled: {
        p.X_WD = poseOf(rng.rotation(), t_WE + R_WE * (k * rng.inBall(1.5 * size)));
        p.detail = "random";
        break;
      }
      case Family::separated:
      case Family::touching: {
        const double gap = family == Family::touching ? 0.0 : size * std::pow(10.0, rng.uniform(-9, 2));
        const Vector3d w = rng.unitVector();  // world, from the disk towards the set
        Vector3d lowest = Vector3d::Zero();
        double lowest_height = std::numeric_limits<double>::infinity();
        for (const Vector3d& x : surface.hull_points) {
          const Vector3d x_W = t_WE + R_WE * x;
          if (w.dot(x_W) < lowest_height) lowest_height = w.dot(x_W), lowest = x_W;
        }
        const Eigen::Matrix3d R = rng.rotation();
        const Vector3d in_plane = w - w.dot(R.col(2)) * R.col(2);
        const Vector3d reach = in_plane.norm() > 1e-12 ? Vector3d(p.radius * in_plane.normalized())
                                                        : Vector3d::Zero();
        p.X_WD = poseOf(R, lowest - gap * w - reach);
        p.known_distance = gap;
        p.detail = "gap " + std::to_string(gap);
        break;
      }
      case Family::crossing: {
        Vector3d point, normal;
        surface.sample_face(rng, &point, &normal);
        p.X_WD = poseOf(rng.rotation(), t_WE + R_WE * point);
        p.known_distance = 0;
        p.detail = "centre on a face";
        break;
      }
      case Family::parallel_face: {
        Vector3d point, normal;
        surface.sample_face(rng, &point, &normal);
        const double height = size * std::pow(10.0, rng.uniform(-9, -1));
        const double tilt = rng.chance(0.5) ? std::pow(10.0, rng.uniform(-8, -3)) : 0.0;
        const Vector3d n =
            (normal + std::tan(tilt) * normal.cross(rng.unitVector()).normalized()).normalized();
        // Over the face or overhanging its edges: the centre up to a radius
        // beside the face point, raised so that the tilted rim's lowest point
        // is `height` above the face's plane.
        const Vector3d slide = rng.uniform01() * p.radius * normal.cross(rng.unitVector()).normalized();
        const Vector3d centre = point + slide + (height + p.radius * std::sin(tilt)) * normal;
        p.X_WD = poseOf(rotationWithNormal(R_WE * (rng.chance(0.5) ? n : Vector3d(-n)), rng),
                        t_WE + R_WE * centre);
        p.detail = "tilt " + std::to_string(tilt) + ", height " + std::to_string(height);
        break;
      }
    }
    out.push_back(p);
  }
  return out;
}

/// A random rotation and translation of size ~1: the meshes' and octrees' poses.
inline Transform3d randomFrame(std::uint64_t seed) {
  Random rng(seed);
  return poseOf(rng.rotation(), rng.inBall(1.0));
}

}  // namespace mesh_families
}  // namespace fcl_disk_test

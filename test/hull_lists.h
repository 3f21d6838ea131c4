// Large convex hulls as vertex and face lists, for the tests of the Convex
// pair's paths of many faces and vertices, and hulls whose faces are planar
// only to float's rounding put beside a disk (test_disk_shape_cases,
// test_disk_shape_penetration).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <fcl/geometry/shape/convex.h>

#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <vector>

namespace fcl_disk_test {

using Vector3d = Eigen::Vector3d;

/// A large hull as vertices and faces (counter-clockwise seen from outside).
struct HullLists {
  std::vector<Vector3d> vertices;
  std::vector<std::vector<int>> faces;
};

/// The polyhedron of `rings` latitude circles of `around` points on the unit
/// sphere, scaled by `semi_axes`, and the two poles: planar quadrilaterals
/// between the rings and triangle fans at the poles (strictly convex).
inline HullLists ringHull(int rings, int around, const Vector3d& semi_axes) {
  HullLists hull;
  hull.vertices.push_back(Vector3d(0, 0, -semi_axes.z()));
  for (int ring = 0; ring < rings; ++ring) {
    const double polar = M_PI * (ring + 1) / (rings + 1);
    for (int k = 0; k < around; ++k) {
      const double azimuth = 2 * M_PI * k / around;
      hull.vertices.push_back(semi_axes.cwiseProduct(Vector3d(
          std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth), -std::cos(polar))));
    }
  }
  hull.vertices.push_back(Vector3d(0, 0, semi_axes.z()));
  const auto at_ring = [&](int ring, int k) { return 1 + ring * around + (k % around); };
  const int top = int(hull.vertices.size()) - 1;
  for (int k = 0; k < around; ++k) {
    hull.faces.push_back({0, at_ring(0, k + 1), at_ring(0, k)});
    for (int ring = 0; ring + 1 < rings; ++ring) {
      hull.faces.push_back({at_ring(ring, k), at_ring(ring, k + 1), at_ring(ring + 1, k + 1),
                            at_ring(ring + 1, k)});
    }
    hull.faces.push_back({at_ring(rings - 1, k), at_ring(rings - 1, k + 1), top});
  }
  return hull;
}

/// The cube [-h, h]^3 with each face cut into n x n squares, each split into
/// two triangles: many coplanar faces (ties everywhere for the face climb and
/// the vertex clusters).
inline HullLists subdividedCube(int n, double h) {
  HullLists hull;
  std::map<std::array<int, 3>, int> index;
  const auto vertex = [&](std::array<int, 3> grid) {
    const auto [it, added] = index.emplace(grid, int(hull.vertices.size()));
    if (added) hull.vertices.push_back(h * (Vector3d(grid[0], grid[1], grid[2]) * (2.0 / n) - Vector3d::Ones()));
    return it->second;
  };
  for (int axis = 0; axis < 3; ++axis) {
    for (const int side : {0, n}) {
      const int a = (axis + 1) % 3, b = (axis + 2) % 3;
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          std::array<int, 4> corner;
          const int steps[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
          for (int c = 0; c < 4; ++c) {
            std::array<int, 3> grid{};
            grid[axis] = side, grid[a] = i + steps[c][0], grid[b] = j + steps[c][1];
            corner[c] = vertex(grid);
          }
          // (a, b, axis) is right-handed: counter-clockwise in (a, b) faces +axis.
          if (side == n) {
            hull.faces.push_back({corner[0], corner[1], corner[2]});
            hull.faces.push_back({corner[0], corner[2], corner[3]});
          } else {
            hull.faces.push_back({corner[0], corner[2], corner[1]});
            hull.faces.push_back({corner[0], corner[3], corner[2]});
          }
        }
      }
    }
  }
  return hull;
}

/// x rounded to float, as a double. Through a volatile float: GCC 12 at -O2
/// drops the rounding of double(float(a * cos(t))) when it merges cos(t) and
/// sin(t) into one sincos call, and the hull would stay planar in double.
inline double roundedToFloat(double x) {
  volatile float rounded = float(x);
  return double(rounded);
}

/// A prism tapered by `taper` (top ring = taper x bottom ring) over the n-gon
/// inscribed in the ellipse of semi-axes a, b, from z = -h to h, its vertices
/// rounded to float: quadrilateral sides planar only to float's precision (as
/// fuzz_disk_shapes builds its hulls), an n-gon at each end.
inline HullLists floatTaperedPrism(int n, double a, double b, double h, double taper) {
  HullLists hull;
  for (const double z : {-h, h}) {
    const double ring = z < 0 ? 1.0 : taper;
    for (int i = 0; i < n; ++i) {
      const double angle = 2 * M_PI * i / n;
      hull.vertices.push_back(Vector3d(roundedToFloat(ring * a * std::cos(angle)),
                                       roundedToFloat(ring * b * std::sin(angle)),
                                       roundedToFloat(z)));
    }
  }
  std::vector<int> bottom, top;
  for (int i = 0; i < n; ++i) bottom.push_back(n - 1 - i), top.push_back(n + i);
  hull.faces.push_back(bottom);
  hull.faces.push_back(top);
  for (int i = 0; i < n; ++i) {
    const int next = (i + 1) % n;
    hull.faces.push_back({i, next, n + next, n + i});
  }
  return hull;
}

/// A random pair of the float-hull tests: a floatTaperedPrism over a
/// 32..63-gon at length scale k (log-uniform in 1e-4..1: semi-axes a, b and
/// half-height h are k U(0.02, 1.02)) with the taper `draw_taper(rng)` gives,
/// a disk radius k U(0.02, 1.02), and two random rotations (disk, hull).
struct FloatPrismAndDisk {
  HullLists lists;
  double k;         ///< the length scale
  Vector3d extent;  ///< (a, b, h)
  double r;
  Eigen::Matrix3d R_disk, R_hull;
};
template <typename Rng, typename DrawTaper>
FloatPrismAndDisk drawFloatPrismAndDisk(Rng& rng, DrawTaper&& draw_taper) {
  FloatPrismAndDisk pair;
  const double k = rng.logUniform(1e-4, 1.0);
  const int n = 32 + int(rng.uniform(0.0, 32.0)) % 32;
  const double a = k * rng.uniform(0.02, 1.02), b = k * rng.uniform(0.02, 1.02);
  const double h = k * rng.uniform(0.02, 1.02), taper = draw_taper(rng);
  pair.lists = floatTaperedPrism(n, a, b, h, taper);
  pair.k = k;
  pair.extent = Vector3d(a, b, h);
  pair.r = k * rng.uniform(0.02, 1.02);
  pair.R_disk = rng.rotation();
  pair.R_hull = rng.rotation();
  return pair;
}

/// The point most along unit w of the disk of radius r centred at the origin
/// with unit normal n.
inline Vector3d diskPointMostAlong(double r, const Vector3d& n, const Vector3d& w) {
  return r * (w - w.dot(n) * n).normalized();
}

/// The vertex of `vertices` turned by R least along w (the first of ties).
inline Vector3d vertexLeastAlong(const std::vector<Vector3d>& vertices, const Eigen::Matrix3d& R,
                                 const Vector3d& w) {
  Vector3d least = R * vertices[0];
  for (const Vector3d& v : vertices) {
    if ((R * v).dot(w) < least.dot(w)) least = R * v;
  }
  return least;
}

/// A disk of radius r and a hull of `vertices`, their rotations R_disk and
/// R_hull as poses in S, the hull translated so that along unit w its
/// vertices' support clears the disk's by about `wanted_gap` (0: they touch).
/// Read back in double from the poses in S: the hull's translation t and the
/// clearance `gap` they give.
template <typename S>
struct HullBesideDisk {
  fcl::Transform3<S> X_WD, X_WS;
  Vector3d t;
  double gap;
};
template <typename S>
HullBesideDisk<S> placeHullBesideDisk(const std::vector<Vector3d>& vertices, S r,
                                      const Eigen::Matrix3d& R_disk,
                                      const Eigen::Matrix3d& R_hull, const Vector3d& w,
                                      double wanted_gap) {
  HullBesideDisk<S> placed;
  placed.X_WD = placed.X_WS = fcl::Transform3<S>::Identity();
  placed.X_WD.linear() = R_disk.cast<S>();
  placed.X_WS.linear() = R_hull.cast<S>();
  const Eigen::Matrix3d R_D = placed.X_WD.linear().template cast<double>();
  const Eigen::Matrix3d R_S = placed.X_WS.linear().template cast<double>();
  const Vector3d disk_support = diskPointMostAlong(double(r), R_D.col(2).normalized(), w);
  const Vector3d lowest = vertexLeastAlong(vertices, R_S, w);
  placed.X_WS.translation() = (disk_support - lowest + wanted_gap * w).template cast<S>();
  placed.t = placed.X_WS.translation().template cast<double>();
  placed.gap = (lowest + placed.t).dot(w) - disk_support.dot(w);
  return placed;
}

/// FCL's face list of `lists`: [k, i_1..i_k, k', ...].
inline std::shared_ptr<std::vector<int>> faceListOf(const HullLists& lists) {
  auto face_list = std::make_shared<std::vector<int>>();
  for (const auto& face : lists.faces) {
    face_list->push_back(int(face.size()));
    face_list->insert(face_list->end(), face.begin(), face.end());
  }
  return face_list;
}

/// fcl::Convex<S> of `lists`, its vertices rounded to S.
template <typename S>
fcl::Convex<S> convexOf(const HullLists& lists) {
  auto vertices = std::make_shared<std::vector<fcl::Vector3<S>>>();
  for (const Vector3d& v : lists.vertices) vertices->push_back(v.cast<S>());
  return fcl::Convex<S>(vertices, int(lists.faces.size()), faceListOf(lists));
}

}  // namespace fcl_disk_test

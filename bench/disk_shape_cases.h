// Random disk-vs-shape cases for bench_disk_shapes and fcl_disk_report's shape
// section: one generator, so both measure the same distribution of poses.
//
// A case: a disk of radius 0.5 with a uniformly random rotation and its centre
// uniform in the ball of radius 1; one other FCL shape of size ~0.5 (each
// dimension its nominal value times a factor uniform in [0.7, 1.3]), uniformly
// rotated, its frame origin uniform in the ball of radius 1. About 40-80% of the
// cases overlap, depending on the shape. Shapes (FCL conventions, shape frame S):
//   sphere     Sphere(0.4)
//   box        Box(0.6, 0.5, 0.4)                      (full side lengths)
//   capsule    Capsule(0.2, 0.6)                       (radius, segment length)
//   cylinder   Cylinder(0.3, 0.6)
//   cone       Cone(0.3, 0.6)
//   ellipsoid  Ellipsoid(0.5, 0.35, 0.25)              (semi-axes)
//   convex8    Convex: 8 vertices, 6 quadrilateral faces: the box of half sides
//              (0.3, 0.25, 0.2) under a random linear map I + 0.2 G (G Gaussian,
//              determinant > 0), a parallelepiped
//   convex40   Convex: the hull of 40 random points on the sphere of radius 0.45,
//              76 triangular faces (brute-force hull below)
//   halfspace  Halfspace(n, d) = {x : n.x <= d}, n a random unit vector,
//              d uniform in [-0.3, 0.3]
//   plane      Plane(n, d) = {x : n.x = d}, n and d as for halfspace
//   triangle   TriangleP(a, b, c), three points uniform in the ball of radius 0.5
// Faces of Convex are listed counter-clockwise seen from outside.
//
// Scale of a case (the error is |d - d_ref| / scale; include/fcl_disk/
// disk_shape_distance.h): r + R_S + |c_D - c_S|, R_S the shape's bounding radius
// about its frame origin c_S; for halfspace and plane R_S = 0 and c_S is the
// foot of the disk centre on the boundary plane, so scale = r + |n.c_D - d|.
//
// Random numbers: fcl_disk_test::Random (test/test_random.h), so a
// (shape, count, seed) triple gives the same cases with every standard library.
// Cases are generated in double and rounded once to S by makeShape / toS.
//
// probeInChild(): runs a piece of code in a forked child and reports whether it
// finished, crashed, hung or made FCL print "not supported". FCL 0.7 crashes
// (segfault) on a flat cylinder against Halfspace or Plane under libccd, and has
// no entries for TriangleP at all; the harnesses probe every query kind over its
// whole pool before timing it and skip those that do not finish cleanly.
#pragma once

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cone.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/plane.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/geometry/shape/triangle_p.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "test_random.h"

namespace fcl_disk_shape_cases {

enum class ShapeKind {
  sphere,
  box,
  capsule,
  cylinder,
  cone,
  ellipsoid,
  convex8,
  convex40,
  halfspace,
  plane,
  triangle
};

inline const std::vector<ShapeKind>& allShapeKinds() {
  static const std::vector<ShapeKind> kinds{
      ShapeKind::sphere,   ShapeKind::box,      ShapeKind::capsule,   ShapeKind::cylinder,
      ShapeKind::cone,     ShapeKind::ellipsoid, ShapeKind::convex8,  ShapeKind::convex40,
      ShapeKind::halfspace, ShapeKind::plane,    ShapeKind::triangle};
  return kinds;
}

inline const char* shapeName(ShapeKind kind) {
  switch (kind) {
    case ShapeKind::sphere: return "sphere";
    case ShapeKind::box: return "box";
    case ShapeKind::capsule: return "capsule";
    case ShapeKind::cylinder: return "cylinder";
    case ShapeKind::cone: return "cone";
    case ShapeKind::ellipsoid: return "ellipsoid";
    case ShapeKind::convex8: return "convex8";
    case ShapeKind::convex40: return "convex40";
    case ShapeKind::halfspace: return "halfspace";
    case ShapeKind::plane: return "plane";
    case ShapeKind::triangle: return "triangle";
  }
  return "?";
}

constexpr double kDiskRadius = 0.5;

/// The shape of a case, in double, in its own frame S.
struct ShapeSpec {
  ShapeKind kind = ShapeKind::sphere;
  Eigen::Vector3d dims = Eigen::Vector3d::Zero();  ///< per kind, see the file comment
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< halfspace, plane
  double offset = 0;                                  ///< halfspace, plane: d
  std::vector<Eigen::Vector3d> vertices;              ///< convex, triangle
  std::vector<int> faces;  ///< convex: FCL's layout, [n, i_1 .. i_n] per face
  int num_faces = 0;
};

struct CaseSpec {
  std::string name;  ///< "<shape>/<index>"
  double disk_radius = kDiskRadius;
  Eigen::Isometry3d X_WD = Eigen::Isometry3d::Identity();
  ShapeSpec shape;
  Eigen::Isometry3d X_WS = Eigen::Isometry3d::Identity();
  double bounding_radius = 0;  ///< R_S about the shape frame's origin (0: halfspace, plane)
  double scale = 1;            ///< r + R_S + |c_D - c_S|
};

namespace detail {

inline Eigen::Isometry3d randomPose(fcl_disk_test::Random& random) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = random.rotation();
  X.translation() = random.inBall(1.0);
  return X;
}

/// Hull of points in general position (no four coplanar): every triangle with all
/// other points on its inner side, oriented outwards. O(n^4); for n ~ 40.
inline void bruteForceHull(const std::vector<Eigen::Vector3d>& p, std::vector<int>* faces,
                           int* num_faces) {
  const int n = static_cast<int>(p.size());
  faces->clear();
  *num_faces = 0;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      for (int k = j + 1; k < n; ++k) {
        const Eigen::Vector3d normal = (p[j] - p[i]).cross(p[k] - p[i]);
        int above = 0, below = 0;
        for (int l = 0; l < n && !(above && below); ++l) {
          if (l == i || l == j || l == k) continue;
          const double side = normal.dot(p[l] - p[i]);
          (side > 0 ? above : below) += 1;
        }
        if (above && below) continue;
        faces->push_back(3);
        if (above) {  // the others are on the +normal side: flip to point outwards
          faces->insert(faces->end(), {i, k, j});
        } else {
          faces->insert(faces->end(), {i, j, k});
        }
        ++*num_faces;
      }
    }
  }
}

inline double factor(fcl_disk_test::Random& random) { return random.uniform(0.7, 1.3); }

/// The Convex hull of `vertex_count` random points on the sphere of radius 0.45
/// (convex40's shape; the hull-size benchmarks' for other counts).
inline ShapeSpec sphereHull(int vertex_count, fcl_disk_test::Random& random) {
  ShapeSpec s;
  s.kind = ShapeKind::convex40;
  for (int v = 0; v < vertex_count; ++v) s.vertices.push_back(0.45 * random.unitVector());
  bruteForceHull(s.vertices, &s.faces, &s.num_faces);
  return s;
}

inline ShapeSpec randomShape(ShapeKind kind, fcl_disk_test::Random& random) {
  ShapeSpec s;
  s.kind = kind;
  switch (kind) {
    case ShapeKind::sphere:
      s.dims = Eigen::Vector3d(0.4 * factor(random), 0, 0);
      break;
    case ShapeKind::box:
      s.dims = Eigen::Vector3d(0.6 * factor(random), 0.5 * factor(random), 0.4 * factor(random));
      break;
    case ShapeKind::capsule:
    case ShapeKind::cylinder:
    case ShapeKind::cone:
      s.dims = Eigen::Vector3d((kind == ShapeKind::capsule ? 0.2 : 0.3) * factor(random),
                               0.6 * factor(random), 0);
      break;
    case ShapeKind::ellipsoid:
      s.dims = Eigen::Vector3d(0.5 * factor(random), 0.35 * factor(random),
                               0.25 * factor(random));
      break;
    case ShapeKind::convex8: {
      Eigen::Matrix3d A;
      do {
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) A(r, c) = (r == c ? 1.0 : 0.0) + 0.2 * random.normal();
      } while (A.determinant() < 0.3);
      const Eigen::Vector3d half(0.3, 0.25, 0.2);
      for (int v = 0; v < 8; ++v) {
        const Eigen::Vector3d corner((v & 1) ? half.x() : -half.x(),
                                     (v & 2) ? half.y() : -half.y(),
                                     (v & 4) ? half.z() : -half.z());
        s.vertices.push_back(A * corner);
      }
      // Vertex v has +x if bit 0, +y if bit 1, +z if bit 2; a linear map with
      // positive determinant keeps the box's outward counter-clockwise order.
      s.faces = {4, 0, 4, 6, 2,   4, 1, 3, 7, 5,   4, 0, 1, 5, 4,
                 4, 2, 6, 7, 3,   4, 0, 2, 3, 1,   4, 4, 5, 7, 6};
      s.num_faces = 6;
      break;
    }
    case ShapeKind::convex40:
      s = sphereHull(40, random);
      break;
    case ShapeKind::halfspace:
    case ShapeKind::plane:
      s.normal = random.unitVector();
      s.offset = random.uniform(-0.3, 0.3);
      break;
    case ShapeKind::triangle:
      for (int v = 0; v < 3; ++v) s.vertices.push_back(random.inBall(0.5));
      break;
  }
  return s;
}

inline double boundingRadius(const ShapeSpec& s) {
  switch (s.kind) {
    case ShapeKind::sphere: return s.dims.x();
    case ShapeKind::box: return 0.5 * s.dims.norm();
    case ShapeKind::capsule: return s.dims.x() + 0.5 * s.dims.y();
    case ShapeKind::cylinder:
    case ShapeKind::cone: return std::hypot(s.dims.x(), 0.5 * s.dims.y());
    case ShapeKind::ellipsoid: return s.dims.maxCoeff();
    case ShapeKind::halfspace:
    case ShapeKind::plane: return 0;
    case ShapeKind::convex8:
    case ShapeKind::convex40:
    case ShapeKind::triangle: {
      double r = 0;
      for (const auto& v : s.vertices) r = std::max(r, v.norm());
      return r;
    }
  }
  return 0;
}

}  // namespace detail

/// `count` random cases of one shape kind; `seed` and the kind fix them.
inline std::vector<CaseSpec> makeCases(ShapeKind kind, std::size_t count, std::uint64_t seed) {
  fcl_disk_test::Random random(seed ^ (0x9E3779B97F4A7C15ull * (1 + static_cast<int>(kind))));
  std::vector<CaseSpec> cases;
  cases.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    CaseSpec c;
    c.name = std::string(shapeName(kind)) + "/" + std::to_string(i);
    c.X_WD = detail::randomPose(random);
    c.shape = detail::randomShape(kind, random);
    c.X_WS = detail::randomPose(random);
    c.bounding_radius = detail::boundingRadius(c.shape);
    if (kind == ShapeKind::halfspace || kind == ShapeKind::plane) {
      const Eigen::Vector3d n_W = c.X_WS.linear() * c.shape.normal;
      const double d_W = c.shape.offset + n_W.dot(c.X_WS.translation());
      c.scale = c.disk_radius + std::fabs(n_W.dot(c.X_WD.translation()) - d_W);
    } else {
      c.scale = c.disk_radius + c.bounding_radius +
                (c.X_WD.translation() - c.X_WS.translation()).norm();
    }
    cases.push_back(std::move(c));
  }
  return cases;
}

template <typename S>
fcl::Transform3<S> toS(const Eigen::Isometry3d& X) {
  fcl::Transform3<S> Y = fcl::Transform3<S>::Identity();
  Y.linear() = X.linear().cast<S>();
  Y.translation() = X.translation().cast<S>();
  return Y;
}

/// The FCL shape of a spec, in scalar S.
template <typename S>
std::shared_ptr<fcl::ShapeBase<S>> makeShape(const ShapeSpec& s) {
  const fcl::Vector3<S> d = s.dims.cast<S>();
  switch (s.kind) {
    case ShapeKind::sphere: return std::make_shared<fcl::Sphere<S>>(d.x());
    case ShapeKind::box: return std::make_shared<fcl::Box<S>>(d.x(), d.y(), d.z());
    case ShapeKind::capsule: return std::make_shared<fcl::Capsule<S>>(d.x(), d.y());
    case ShapeKind::cylinder: return std::make_shared<fcl::Cylinder<S>>(d.x(), d.y());
    case ShapeKind::cone: return std::make_shared<fcl::Cone<S>>(d.x(), d.y());
    case ShapeKind::ellipsoid: return std::make_shared<fcl::Ellipsoid<S>>(d.x(), d.y(), d.z());
    case ShapeKind::convex8:
    case ShapeKind::convex40: {
      auto vertices = std::make_shared<std::vector<fcl::Vector3<S>>>();
      for (const auto& v : s.vertices) vertices->push_back(v.cast<S>());
      auto faces = std::make_shared<const std::vector<int>>(s.faces);
      return std::make_shared<fcl::Convex<S>>(vertices, s.num_faces, faces);
    }
    case ShapeKind::halfspace:
      return std::make_shared<fcl::Halfspace<S>>(s.normal.cast<S>(), S(s.offset));
    case ShapeKind::plane:
      return std::make_shared<fcl::Plane<S>>(s.normal.cast<S>(), S(s.offset));
    case ShapeKind::triangle:
      return std::make_shared<fcl::TriangleP<S>>(
          s.vertices[0].cast<S>(), s.vertices[1].cast<S>(), s.vertices[2].cast<S>());
  }
  return nullptr;
}

/// Outcome of probeInChild: ok, or why not ("crashed (signal 11, ...)",
/// "FCL: not supported", "did not finish in N s", ...).
struct ProbeOutcome {
  bool ok = false;
  std::string reason;
};

/// Runs body() in a forked child with std::cerr captured. body returns 0 when
/// every answer was usable, else a code in 10..99 whose meaning `describe` gives.
/// Not ok: body returned non-zero, FCL printed "not supported", the child died
/// of a signal, or it ran longer than timeout_s. Call it while the process has a
/// single thread.
inline ProbeOutcome probeInChild(const std::function<int()>& body,
                                 const std::function<std::string(int)>& describe,
                                 unsigned timeout_s = 30) {
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid < 0) return {false, std::string("fork failed: ") + std::strerror(errno)};
  if (pid == 0) {
    alarm(timeout_s);
    std::ostringstream captured;
    std::cerr.rdbuf(captured.rdbuf());
    int code = body();
    if (captured.str().find("not supported") != std::string::npos) code = 3;
    _exit(code);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return {false, std::string("waitpid failed: ") + std::strerror(errno)};
  }
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    if (sig == SIGALRM)
      return {false, "did not finish in " + std::to_string(timeout_s) + " s"};
    return {false, "crashed (signal " + std::to_string(sig) + ", " + strsignal(sig) + ")"};
  }
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (code == 0) return {true, ""};
  if (code == 3) return {false, "FCL: not supported"};
  return {false, describe(code)};
}

}  // namespace fcl_disk_shape_cases

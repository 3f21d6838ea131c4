// Configuration families of a disk against each FCL primitive, for
// test_disk_shape_accuracy.cpp: poses and dimensions drawn with
// fcl_disk_test::Random (portable), held in reference_disk_shape.h's structs.
//
// Most families are built so that the distance is known in exact arithmetic
// (support-point placement): pick a unit direction w (disk -> shape), the disk's
// point x_D extreme along +w (a rim point, or any point of the face when w is
// the disk's normal) and a shape feature (face, edge, vertex or smooth point) y
// whose outward normal cone contains a local direction e; rotate the shape so
// that R_S e = -w and translate it so that R_S y + t_S = x_D + gap w. The plane
// through x_D normal to w then separates the two sets by `gap` and the pair
// (x_D, x_D + gap w) realises it, so the distance is exactly max(gap, 0). The
// poses are rounded to double afterwards, so the recorded known_distance holds
// to the rounding of the poses only (a few ulps of the scene).
//
// Families (a shape without the needed feature has no cases in that family):
//   random          disk and shape at random, overlapping or apart;
//   separated       support placement, gap 1e-12..1e6 of the scene size, the
//                   shape touching with a random feature (smooth point, face,
//                   edge or vertex) and the disk with its rim;
//   touching        the same with gap 0;
//   overlapping     a disk point placed on a shape point 1e-12..1 of the way
//                   from the boundary to an interior point;
//   parallel_face   the disk's face on a face of the shape (box, convex, cylinder
//                   cap, cone base, halfspace, plane, triangle), or on an edge of
//                   it lying flat; gap 0 or 1e-12..1;
//   rim_edge        the disk's rim against an edge (box, convex, triangle,
//                   cylinder and cone rims), half of them with the rim tangent
//                   parallel to the edge; gap 0 or 1e-12..1;
//   vertex_face     a vertex (box, convex, triangle, cone apex) over the disk's
//                   face; gap 0 or 1e-12..1;
//   inside          the disk entirely inside the shape (every solid);
//   far             separated / touching / face / random cases translated by
//                   1e5..1e6;
//   scaled          the same scaled by 1e-6..1e6 (every length).
#pragma once

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "reference_disk_shape.h"
#include "test_random.h"

namespace fcl_disk_test {
namespace shape_families {

using ref::M3;
using ref::Real;
using ref::V3;
using Vd = Eigen::Vector3d;
using Md = Eigen::Matrix3d;

enum class Family {
  random,
  separated,
  touching,
  overlapping,
  parallel_face,
  rim_edge,
  vertex_face,
  inside,
  far,
  scaled
};

inline const char* familyName(Family f) {
  switch (f) {
    case Family::random: return "random";
    case Family::separated: return "separated";
    case Family::touching: return "touching";
    case Family::overlapping: return "overlapping";
    case Family::parallel_face: return "parallel_face";
    case Family::rim_edge: return "rim_edge";
    case Family::vertex_face: return "vertex_face";
    case Family::inside: return "inside";
    case Family::far: return "far";
    case Family::scaled: return "scaled";
  }
  return "?";
}

inline std::vector<Family> allFamilies() {
  return {Family::random,        Family::separated, Family::touching,    Family::overlapping,
          Family::parallel_face, Family::rim_edge,  Family::vertex_face, Family::inside,
          Family::far,           Family::scaled};
}

/// The shape feature a support placement touches with.
enum class Feature { smooth, face, edge, vertex };

inline const char* featureName(Feature f) {
  switch (f) {
    case Feature::smooth: return "support point";
    case Feature::face: return "face";
    case Feature::edge: return "edge";
    case Feature::vertex: return "vertex";
  }
  return "?";
}

/// One disk-shape pair. All values are exactly representable in double (the
/// test rounds them to float for float runs).
template <typename Shape>
struct DiskShapeCase {
  std::string family;
  std::string detail;  ///< sub-kind: the feature, gap, depth, offset or factor used.
  Real radius{1};
  M3 R_D{M3::Identity()};
  V3 t_D{V3::Zero()};
  Shape shape;
  /// The distance by construction (exact arithmetic, before the poses were
  /// rounded), NaN when not known.
  Real known_distance{std::numeric_limits<Real>::quiet_NaN()};

  bool hasKnownDistance() const { return !std::isnan(known_distance); }
  ref::Disk disk() const { return ref::makeDisk(radius, R_D, t_D); }
};

/// A contact feature in the shape's frame: a point y of it and a direction e in
/// the interior of its outward normal cone at y (so y maximises e.x over the
/// shape); edge_dir is the edge's unit direction for edges (else zero).
struct Contact {
  Vd e{Vd::UnitZ()};
  Vd y{Vd::Zero()};
  Vd edge_dir{Vd::Zero()};
};

namespace detail {

inline Vd toD(const V3& x) { return x.cast<double>(); }
inline V3 toR(const Vd& x) { return x.cast<Real>(); }

/// A uniformly random point of the disk of radius r spanned by orthonormal a, b.
inline Vd inDisk(Random& rng, double r, const Vd& a, const Vd& b) {
  const double rho = r * std::sqrt(rng.uniform01());
  const double phi = rng.uniform(0, 2 * M_PI);
  return rho * (std::cos(phi) * a + std::sin(phi) * b);
}

/// Two unit vectors completing n to an orthonormal frame.
inline void tangents(const Vd& n, Vd* a, Vd* b) {
  const Vd pick = std::fabs(n.x()) < 0.6 ? Vd::UnitX() : Vd::UnitY();
  *a = (pick - n.dot(pick) * n).normalized();
  *b = n.cross(*a);
}

/// Random convex weights for k points (a weight is 0 one time in five, so points
/// on the edges and at the vertices of a face occur).
inline std::vector<double> convexWeights(Random& rng, size_t k) {
  std::vector<double> w(k);
  double sum = 0;
  for (double& x : w) {
    x = rng.chance(0.2) ? 0.0 : -std::log(1.0 - rng.uniform01());
    sum += x;
  }
  if (sum == 0) {
    w[0] = 1;
    sum = 1;
  }
  for (double& x : w) x /= sum;
  return w;
}

/// Newell normal of a polygon.
inline Vd newell(const std::vector<Vd>& v) {
  Vd m = Vd::Zero();
  for (size_t i = 0; i < v.size(); ++i) {
    const Vd& a = v[i];
    const Vd& b = v[(i + 1) % v.size()];
    m.x() += (a.y() - b.y()) * (a.z() + b.z());
    m.y() += (a.z() - b.z()) * (a.x() + b.x());
    m.z() += (a.x() - b.x()) * (a.y() + b.y());
  }
  return m;
}

inline int pick(Random& rng, int n) { return std::min(n - 1, int(rng.uniform(0, n))); }

}  // namespace detail

// ------------------------------------------------------------- per-shape makers
// ShapeGen<Shape>: make(rng) (random dimensions, identity pose);
// contact(rng, shape, feature, &c) (false if the shape has no such feature);
// interior(rng, shape, &clearance) (a point of the shape and the radius of a
// ball about it inside the shape, 0 for the plane and the triangle);
// scaleDims(&shape, k).

template <typename Shape>
struct ShapeGen;

template <>
struct ShapeGen<ref::Sphere> {
  static constexpr const char* kName = "sphere";
  static ref::Sphere make(Random& rng) {
    ref::Sphere s;
    s.radius = rng.uniform(0.1, 2);
    return s;
  }
  static bool contact(Random& rng, const ref::Sphere& s, Feature f, Contact* c) {
    if (f != Feature::smooth) return false;
    c->e = rng.unitVector();
    c->y = double(s.radius) * c->e;
    return true;
  }
  static Vd interior(Random& rng, const ref::Sphere& s, double* clearance) {
    const Vd y = rng.inBall(0.9 * double(s.radius));
    *clearance = double(s.radius) - y.norm();
    return y;
  }
  static void scaleDims(ref::Sphere* s, double k) { s->radius = double(s->radius) * k; }
};

template <>
struct ShapeGen<ref::Box> {
  static constexpr const char* kName = "box";
  static ref::Box make(Random& rng) {
    ref::Box b;
    b.side = V3(rng.uniform(0.1, 3), rng.uniform(0.1, 3), rng.uniform(0.1, 3));
    return b;
  }
  static bool contact(Random& rng, const ref::Box& b, Feature f, Contact* c) {
    const Vd h = detail::toD(b.side) / 2;
    const auto sign = [&] { return rng.chance(0.5) ? 1.0 : -1.0; };
    switch (f) {
      case Feature::smooth:
      case Feature::vertex: {
        const Vd s(sign(), sign(), sign());
        c->y = s.cwiseProduct(h);
        c->e = s.cwiseProduct(Vd(rng.uniform(0.05, 1), rng.uniform(0.05, 1), rng.uniform(0.05, 1)))
                   .normalized();
        return true;
      }
      case Feature::face: {
        const int i = detail::pick(rng, 3);
        const double s = sign();
        for (int k = 0; k < 3; ++k) c->y[k] = rng.uniform(-h[k], h[k]);
        c->y[i] = s * h[i];
        c->e = Vd::Zero();
        c->e[i] = s;
        return true;
      }
      case Feature::edge: {
        const int k = detail::pick(rng, 3), i = (k + 1) % 3, j = (k + 2) % 3;
        const double si = sign(), sj = sign();
        c->y[k] = rng.uniform(-h[k], h[k]);
        c->y[i] = si * h[i];
        c->y[j] = sj * h[j];
        c->e = Vd::Zero();
        c->e[i] = si * rng.uniform(0.05, 1);
        c->e[j] = sj * rng.uniform(0.05, 1);
        c->e.normalize();
        c->edge_dir = Vd::Unit(k);
        return true;
      }
    }
    return false;
  }
  static Vd interior(Random& rng, const ref::Box& b, double* clearance) {
    const Vd h = detail::toD(b.side) / 2;
    Vd y;
    double cl = h.maxCoeff();
    for (int k = 0; k < 3; ++k) {
      y[k] = rng.uniform(-0.9, 0.9) * h[k];
      cl = std::min(cl, h[k] - std::fabs(y[k]));
    }
    *clearance = cl;
    return y;
  }
  static void scaleDims(ref::Box* b, double k) { b->side = (detail::toD(b->side) * k).cast<Real>(); }
};

template <>
struct ShapeGen<ref::Capsule> {
  static constexpr const char* kName = "capsule";
  static ref::Capsule make(Random& rng) {
    ref::Capsule c;
    c.radius = rng.uniform(0.1, 1);
    c.lz = rng.uniform(0.1, 3);
    return c;
  }
  static bool contact(Random& rng, const ref::Capsule& cap, Feature f, Contact* c) {
    if (f != Feature::smooth) return false;
    c->e = rng.unitVector();
    c->y = double(cap.radius) * c->e + (c->e.z() >= 0 ? 1 : -1) * double(cap.lz) / 2 * Vd::UnitZ();
    return true;
  }
  static Vd interior(Random& rng, const ref::Capsule& cap, double* clearance) {
    const double h = double(cap.lz) / 2, rho = double(cap.radius);
    const Vd y = Vd(0, 0, rng.uniform(-h, h)) + rng.inBall(0.9 * rho);
    const Vd axis(0, 0, std::min(h, std::max(-h, y.z())));
    *clearance = rho - (y - axis).norm();
    return y;
  }
  static void scaleDims(ref::Capsule* c, double k) {
    c->radius = double(c->radius) * k;
    c->lz = double(c->lz) * k;
  }
};

template <>
struct ShapeGen<ref::Cylinder> {
  static constexpr const char* kName = "cylinder";
  static ref::Cylinder make(Random& rng) {
    ref::Cylinder c;
    c.radius = rng.uniform(0.1, 2);
    c.lz = rng.uniform(0.05, 3);
    return c;
  }
  static bool contact(Random& rng, const ref::Cylinder& cyl, Feature f, Contact* c) {
    const double R = double(cyl.radius), h = double(cyl.lz) / 2;
    switch (f) {
      case Feature::smooth: {
        c->e = rng.unitVector();
        const Vd radial = Vd(c->e.x(), c->e.y(), 0).normalized();
        c->y = R * radial + (c->e.z() >= 0 ? h : -h) * Vd::UnitZ();
        return true;
      }
      case Feature::face: {
        const double s = rng.chance(0.5) ? 1 : -1;
        c->e = s * Vd::UnitZ();
        c->y = detail::inDisk(rng, R, Vd::UnitX(), Vd::UnitY()) + s * h * Vd::UnitZ();
        return true;
      }
      case Feature::edge: {
        const double s = rng.chance(0.5) ? 1 : -1;
        const double phi = rng.uniform(0, 2 * M_PI);
        const Vd radial(std::cos(phi), std::sin(phi), 0);
        c->y = R * radial + s * h * Vd::UnitZ();
        c->e = (rng.uniform(0.05, 1) * radial + rng.uniform(0.05, 1) * s * Vd::UnitZ()).normalized();
        c->edge_dir = Vd(-std::sin(phi), std::cos(phi), 0);
        return true;
      }
      case Feature::vertex: return false;
    }
    return false;
  }
  static Vd interior(Random& rng, const ref::Cylinder& cyl, double* clearance) {
    const double R = double(cyl.radius), h = double(cyl.lz) / 2;
    const Vd y = detail::inDisk(rng, 0.9 * R, Vd::UnitX(), Vd::UnitY()) +
                 rng.uniform(-0.9 * h, 0.9 * h) * Vd::UnitZ();
    *clearance = std::min(R - std::hypot(y.x(), y.y()), h - std::fabs(y.z()));
    return y;
  }
  static void scaleDims(ref::Cylinder* c, double k) {
    c->radius = double(c->radius) * k;
    c->lz = double(c->lz) * k;
  }
};

template <>
struct ShapeGen<ref::Cone> {
  static constexpr const char* kName = "cone";
  static ref::Cone make(Random& rng) {
    ref::Cone c;
    c.radius = rng.uniform(0.1, 2);
    c.lz = rng.uniform(0.1, 3);
    return c;
  }
  static bool contact(Random& rng, const ref::Cone& cone, Feature f, Contact* c) {
    const double R = double(cone.radius), h = double(cone.lz) / 2;
    switch (f) {
      case Feature::smooth: {
        c->e = rng.unitVector();
        const double rxy = std::hypot(c->e.x(), c->e.y());
        if (h * c->e.z() >= -h * c->e.z() + R * rxy) {
          c->y = Vd(0, 0, h);
        } else {
          c->y = Vd(R * c->e.x() / rxy, R * c->e.y() / rxy, -h);
        }
        return true;
      }
      case Feature::face:
        c->e = -Vd::UnitZ();
        c->y = detail::inDisk(rng, R, Vd::UnitX(), Vd::UnitY()) - h * Vd::UnitZ();
        return true;
      case Feature::edge: {
        const double phi = rng.uniform(0, 2 * M_PI);
        const Vd radial(std::cos(phi), std::sin(phi), 0);
        const Vd lateral = (2 * h * radial + R * Vd::UnitZ()).normalized();
        c->y = R * radial - h * Vd::UnitZ();
        c->e = (rng.uniform(0.05, 1) * lateral - rng.uniform(0.05, 1) * Vd::UnitZ()).normalized();
        c->edge_dir = Vd(-std::sin(phi), std::cos(phi), 0);
        return true;
      }
      case Feature::vertex: {
        // The apex's normal cone: polar angle up to atan2(2h, R), the lateral normal's.
        const double theta = rng.uniform(0, 0.95) * std::atan2(2 * h, R);
        const double phi = rng.uniform(0, 2 * M_PI);
        c->e = Vd(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
        c->y = Vd(0, 0, h);
        return true;
      }
    }
    return false;
  }
  static Vd interior(Random& rng, const ref::Cone& cone, double* clearance) {
    const double R = double(cone.radius), h = double(cone.lz) / 2;
    const double z = rng.uniform(-0.9 * h, 0.5 * h);
    const double rho_max = R * (h - z) / (2 * h);
    const Vd y = detail::inDisk(rng, 0.9 * rho_max, Vd::UnitX(), Vd::UnitY()) + z * Vd::UnitZ();
    const double rho = std::hypot(y.x(), y.y());
    *clearance = std::min(z + h, (R * h - 2 * h * rho - R * z) / std::hypot(2 * h, R));
    return y;
  }
  static void scaleDims(ref::Cone* c, double k) {
    c->radius = double(c->radius) * k;
    c->lz = double(c->lz) * k;
  }
};

template <>
struct ShapeGen<ref::Ellipsoid> {
  static constexpr const char* kName = "ellipsoid";
  static ref::Ellipsoid make(Random& rng) {
    ref::Ellipsoid e;
    e.radii = V3(rng.uniform(0.1, 2), rng.uniform(0.1, 2), rng.uniform(0.1, 2));
    return e;
  }
  static bool contact(Random& rng, const ref::Ellipsoid& ell, Feature f, Contact* c) {
    if (f != Feature::smooth) return false;
    const Vd a = detail::toD(ell.radii);
    c->e = rng.unitVector();
    const Vd ae = a.cwiseProduct(c->e);
    c->y = a.cwiseProduct(ae) / ae.norm();  // the support point A^2 e / |A e|
    return true;
  }
  static Vd interior(Random& rng, const ref::Ellipsoid& ell, double* clearance) {
    const double a_min = double(ell.radii.minCoeff());
    const Vd y = rng.inBall(0.9 * a_min);
    *clearance = a_min - y.norm();  // the ball of radius a_min lies inside
    return y;
  }
  static void scaleDims(ref::Ellipsoid* e, double k) {
    e->radii = (detail::toD(e->radii) * k).cast<Real>();
  }
};

template <>
struct ShapeGen<ref::Convex> {
  static constexpr const char* kName = "convex";

  /// Orients every face counter-clockwise seen from outside (away from the
  /// vertex centroid).
  static void orient(ref::Convex* cv) {
    Vd centroid = Vd::Zero();
    for (const V3& x : cv->vertices) centroid += detail::toD(x);
    centroid /= double(cv->vertices.size());
    for (auto& f : cv->faces) {
      std::vector<Vd> pts;
      Vd mean = Vd::Zero();
      for (int i : f) {
        pts.push_back(detail::toD(cv->vertices[i]));
        mean += pts.back();
      }
      mean /= double(f.size());
      if (detail::newell(pts).dot(mean - centroid) < 0) std::reverse(f.begin(), f.end());
    }
  }

  /// A tetrahedron, an octahedron, or a prism or pyramid over a convex polygon
  /// (points on an ellipse at sorted angles); every face exactly planar.
  static ref::Convex make(Random& rng) {
    ref::Convex cv;
    const int kind = detail::pick(rng, 4);
    if (kind == 0) {  // tetrahedron
      Vd p[4];
      for (;;) {
        for (Vd& x : p) x = rng.inBall(1.5);
        if (std::fabs((p[1] - p[0]).cross(p[2] - p[0]).dot(p[3] - p[0])) > 0.3) break;
      }
      for (const Vd& x : p) cv.vertices.push_back(detail::toR(x));
      cv.faces = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
    } else if (kind == 1) {  // octahedron with semi-axes a, b, c
      const double a = rng.uniform(0.2, 1.5), b = rng.uniform(0.2, 1.5), c = rng.uniform(0.2, 1.5);
      for (const Vd& x : {Vd(a, 0, 0), Vd(-a, 0, 0), Vd(0, b, 0), Vd(0, -b, 0), Vd(0, 0, c), Vd(0, 0, -c)})
        cv.vertices.push_back(detail::toR(x));
      for (int sx : {0, 1})
        for (int sy : {2, 3})
          for (int sz : {4, 5}) cv.faces.push_back({sx, sy, sz});
    } else {  // prism or pyramid over an n-gon
      const int n = 3 + detail::pick(rng, 6);
      std::vector<double> angles(n);
      for (double& x : angles) x = rng.uniform(0, 2 * M_PI);
      std::sort(angles.begin(), angles.end());
      // Half-way to the regular n-gon: no two vertices nearly coincide.
      for (int i = 0; i < n; ++i) angles[i] = 0.5 * angles[i] + 0.5 * (2 * M_PI * i / n);
      const double A = rng.uniform(0.3, 1.5), B = rng.uniform(0.3, 1.5), h = rng.uniform(0.1, 1.5);
      for (int i = 0; i < n; ++i)
        cv.vertices.push_back(detail::toR(Vd(A * std::cos(angles[i]), B * std::sin(angles[i]), -h)));
      std::vector<int> bottom(n);
      for (int i = 0; i < n; ++i) bottom[i] = i;
      cv.faces.push_back(bottom);
      if (kind == 2) {  // prism
        for (int i = 0; i < n; ++i)
          cv.vertices.push_back(detail::toR(Vd(A * std::cos(angles[i]), B * std::sin(angles[i]), h)));
        std::vector<int> top(n);
        for (int i = 0; i < n; ++i) top[i] = n + i;
        cv.faces.push_back(top);
        for (int i = 0; i < n; ++i) cv.faces.push_back({i, (i + 1) % n, n + (i + 1) % n, n + i});
      } else {  // pyramid, apex anywhere above the base plane
        cv.vertices.push_back(detail::toR(Vd(rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), h)));
        for (int i = 0; i < n; ++i) cv.faces.push_back({i, (i + 1) % n, n});
      }
    }
    orient(&cv);
    return cv;
  }

  static Vd outwardNormal(const ref::Convex& cv, const std::vector<int>& f) {
    std::vector<Vd> pts;
    for (int i : f) pts.push_back(detail::toD(cv.vertices[i]));
    return detail::newell(pts).normalized();
  }

  static bool contact(Random& rng, const ref::Convex& cv, Feature f, Contact* c) {
    const int nf = int(cv.faces.size());
    switch (f) {
      case Feature::smooth: {
        c->e = rng.unitVector();
        double best = -std::numeric_limits<double>::infinity();
        for (const V3& x : cv.vertices) {
          if (c->e.dot(detail::toD(x)) > best) {
            best = c->e.dot(detail::toD(x));
            c->y = detail::toD(x);
          }
        }
        return true;
      }
      case Feature::face: {
        const auto& face = cv.faces[detail::pick(rng, nf)];
        c->e = outwardNormal(cv, face);
        const std::vector<double> w = detail::convexWeights(rng, face.size());
        c->y = Vd::Zero();
        for (size_t i = 0; i < face.size(); ++i) c->y += w[i] * detail::toD(cv.vertices[face[i]]);
        return true;
      }
      case Feature::edge: {
        const int fi = detail::pick(rng, nf);
        const auto& face = cv.faces[fi];
        const size_t k = size_t(detail::pick(rng, int(face.size())));
        const int a = face[k], b = face[(k + 1) % face.size()];
        for (int gi = 0; gi < nf; ++gi) {
          if (gi == fi) continue;
          const auto& g = cv.faces[gi];
          if (std::find(g.begin(), g.end(), a) == g.end()) continue;
          if (std::find(g.begin(), g.end(), b) == g.end()) continue;
          c->e = (rng.uniform(0.05, 1) * outwardNormal(cv, face) +
                  rng.uniform(0.05, 1) * outwardNormal(cv, g))
                     .normalized();
          const Vd va = detail::toD(cv.vertices[a]), vb = detail::toD(cv.vertices[b]);
          c->y = va + rng.uniform01() * (vb - va);
          c->edge_dir = (vb - va).normalized();
          return true;
        }
        return false;
      }
      case Feature::vertex: {
        const int vi = detail::pick(rng, int(cv.vertices.size()));
        c->e = Vd::Zero();
        for (const auto& face : cv.faces)
          if (std::find(face.begin(), face.end(), vi) != face.end())
            c->e += rng.uniform(0.05, 1) * outwardNormal(cv, face);
        c->e.normalize();
        c->y = detail::toD(cv.vertices[vi]);
        return true;
      }
    }
    return false;
  }
  static Vd interior(Random& rng, const ref::Convex& cv, double* clearance) {
    Vd centroid = Vd::Zero();
    for (const V3& x : cv.vertices) centroid += detail::toD(x);
    centroid /= double(cv.vertices.size());
    const Vd corner = detail::toD(cv.vertices[detail::pick(rng, int(cv.vertices.size()))]);
    const Vd y = centroid + rng.uniform(0, 0.8) * (corner - centroid);
    double cl = std::numeric_limits<double>::infinity();
    for (const auto& face : cv.faces)
      cl = std::min(cl, outwardNormal(cv, face).dot(detail::toD(cv.vertices[face[0]]) - y));
    *clearance = std::max(0.0, cl);
    return y;
  }
  static void scaleDims(ref::Convex* cv, double k) {
    for (V3& x : cv->vertices) x = (detail::toD(x) * k).cast<Real>();
  }
};

/// Halfspace and Plane share their generator: n random, d in [-1, 1].
template <typename Flat, bool kTwoSided>
struct FlatGen {
  static Flat make(Random& rng) {
    Flat s;
    s.n = detail::toR(rng.unitVector());
    s.d = rng.uniform(-1, 1);
    return s;
  }
  static Vd pointOnPlane(Random& rng, const Flat& s) {
    const Vd n = detail::toD(s.n);
    Vd a, b;
    detail::tangents(n, &a, &b);
    return double(s.d) * n + rng.uniform(-1, 1) * a + rng.uniform(-1, 1) * b;
  }
  static bool contact(Random& rng, const Flat& s, Feature f, Contact* c) {
    if (f != Feature::smooth && f != Feature::face) return false;
    c->e = (kTwoSided && rng.chance(0.5) ? -1.0 : 1.0) * detail::toD(s.n);
    c->y = pointOnPlane(rng, s);
    return true;
  }
  static Vd interior(Random& rng, const Flat& s, double* clearance) {
    if (kTwoSided) {
      *clearance = 0;
      return pointOnPlane(rng, s);
    }
    const double depth = rng.uniform(0.01, 2);
    *clearance = depth;
    return pointOnPlane(rng, s) - depth * detail::toD(s.n);
  }
  static void scaleDims(Flat* s, double k) { s->d = double(s->d) * k; }
};

template <>
struct ShapeGen<ref::Halfspace> : FlatGen<ref::Halfspace, false> {
  static constexpr const char* kName = "halfspace";
};
template <>
struct ShapeGen<ref::Plane> : FlatGen<ref::Plane, true> {
  static constexpr const char* kName = "plane";
};

template <>
struct ShapeGen<ref::TriangleP> {
  static constexpr const char* kName = "triangle";
  static ref::TriangleP make(Random& rng) {
    ref::TriangleP t;
    for (;;) {
      const Vd a = rng.inBall(1.5), b = rng.inBall(1.5), c = rng.inBall(1.5);
      if ((b - a).cross(c - a).norm() < 0.1) continue;
      t.a = detail::toR(a);
      t.b = detail::toR(b);
      t.c = detail::toR(c);
      return t;
    }
  }
  static std::vector<Vd> corners(const ref::TriangleP& t) {
    return {detail::toD(t.a), detail::toD(t.b), detail::toD(t.c)};
  }
  static bool contact(Random& rng, const ref::TriangleP& t, Feature f, Contact* c) {
    const std::vector<Vd> v = corners(t);
    const Vd m = (v[1] - v[0]).cross(v[2] - v[0]).normalized();
    // In-plane outward normal of edge i (v_i -> v_i+1); a, b, c run
    // counter-clockwise about m.
    const auto out = [&](int i) { return (v[(i + 1) % 3] - v[i]).cross(m).normalized(); };
    const double side = rng.chance(0.5) ? 1 : -1;
    switch (f) {
      case Feature::smooth: {
        c->e = rng.unitVector();
        c->y = v[0];
        for (const Vd& x : v)
          if (c->e.dot(x) > c->e.dot(c->y)) c->y = x;
        return true;
      }
      case Feature::face: {
        c->e = side * m;
        const std::vector<double> w = detail::convexWeights(rng, 3);
        c->y = w[0] * v[0] + w[1] * v[1] + w[2] * v[2];
        return true;
      }
      case Feature::edge: {
        const int i = detail::pick(rng, 3);
        c->e = (rng.uniform(-1, 1) * m + rng.uniform(0.05, 1) * out(i)).normalized();
        c->y = v[i] + rng.uniform01() * (v[(i + 1) % 3] - v[i]);
        c->edge_dir = (v[(i + 1) % 3] - v[i]).normalized();
        return true;
      }
      case Feature::vertex: {
        const int i = detail::pick(rng, 3);
        c->e = (rng.uniform(-1, 1) * m + rng.uniform(0.05, 1) * out((i + 2) % 3) +
                rng.uniform(0.05, 1) * out(i))
                   .normalized();
        c->y = v[i];
        return true;
      }
    }
    return false;
  }
  static Vd interior(Random& rng, const ref::TriangleP& t, double* clearance) {
    const std::vector<Vd> v = corners(t);
    const std::vector<double> w = detail::convexWeights(rng, 3);
    *clearance = 0;
    return w[0] * v[0] + w[1] * v[1] + w[2] * v[2];
  }
  static void scaleDims(ref::TriangleP* t, double k) {
    t->a = (detail::toD(t->a) * k).cast<Real>();
    t->b = (detail::toD(t->b) * k).cast<Real>();
    t->c = (detail::toD(t->c) * k).cast<Real>();
  }
};

// ------------------------------------------------------------------ assembly

/// Whether the shape has a feature of this kind (asked on a sample shape).
template <typename Shape>
bool hasFeature(Feature f) {
  Random rng(1);
  const Shape s = ShapeGen<Shape>::make(rng);
  Contact c;
  return ShapeGen<Shape>::contact(rng, s, f, &c);
}

template <typename Shape>
bool isSolid() {
  return !std::is_same<Shape, ref::Plane>::value && !std::is_same<Shape, ref::TriangleP>::value;
}

/// Whether `family` has cases for this shape.
template <typename Shape>
bool familyApplies(Family f) {
  switch (f) {
    case Family::parallel_face: return hasFeature<Shape>(Feature::face);
    case Family::rim_edge: return hasFeature<Shape>(Feature::edge);
    case Family::vertex_face: return hasFeature<Shape>(Feature::vertex);
    case Family::inside: return isSolid<Shape>();
    default: return true;
  }
}

namespace detail {

inline std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

/// A portable hash of a name (FNV-1a), to give each shape its own stream.
inline std::uint64_t nameHash(const char* s) {
  std::uint64_t h = 1469598103934665603ull;
  for (; *s; ++s) h = (h ^ std::uint64_t(static_cast<unsigned char>(*s))) * 1099511628211ull;
  return h;
}

template <typename Shape>
void setPose(Shape* s, const Md& R, const Vd& t) {
  s->R = R.cast<Real>();
  s->t = t.cast<Real>();
}

/// The length gaps are expressed in: disk radius plus the shape's bounding
/// radius (1 for the halfspace and the plane).
template <typename Shape>
double sizeOf(double r, const Shape& s) {
  const double R_S = double(ref::boundingRadius(s));
  return r + (R_S > 0 ? R_S : 1);
}

/// Support placement (see the top of the file). disk_face: w is the disk's
/// normal (the disk touches with its face); align: turn the shape about w so
/// that its edge is parallel to the rim's tangent at x_D.
template <typename Shape>
bool supportPlacement(Random& rng, Feature feature, double gap_in_sizes, bool disk_face, bool align,
                      DiskShapeCase<Shape>* out) {
  using Gen = ShapeGen<Shape>;
  Shape shape = Gen::make(rng);
  Contact c;
  if (!Gen::contact(rng, shape, feature, &c)) return false;
  const double r = rng.uniform(0.05, 2);
  const Md R_D = rng.rotation();
  const Vd centre = rng.inBall(1);
  const Vd n = R_D.col(2);
  Vd w, x_D, tangent = Vd::Zero();
  if (disk_face) {
    w = rng.chance(0.5) ? n : Vd(-n);
    x_D = centre + inDisk(rng, r, R_D.col(0), R_D.col(1));
  } else {
    Vd pw;
    do {
      w = rng.unitVector();
      pw = w - n.dot(w) * n;
    } while (pw.norm() < 0.05);
    x_D = centre + r * pw.normalized();
    tangent = n.cross(pw.normalized());
  }
  // R_S = B A^T with orthonormal frames A = [e, a1, e x a1] (shape) and
  // B = [-w, b1, -w x b1] (world): R_S e = -w, and a1 (the edge's direction when
  // aligning) goes to b1 (then the rim tangent, else a random direction normal
  // to w). Built from frames, R_S is orthonormal to rounding.
  Vd a1, a2, b1, b2;
  detail::tangents(c.e, &a1, &a2);
  detail::tangents(-w, &b1, &b2);
  if (align && c.edge_dir.norm() > 0 && tangent.norm() > 0) {
    a1 = c.edge_dir;
    b1 = tangent;
  } else {
    const double spin = rng.uniform(0, 2 * M_PI);
    b1 = std::cos(spin) * b1 + std::sin(spin) * b2;
  }
  Md A, B;
  A << c.e, a1, c.e.cross(a1);
  B << -w, b1, (-w).cross(b1);
  const Md R_S = B * A.transpose();
  const double gap = gap_in_sizes * sizeOf(r, shape);
  setPose(&shape, R_S, x_D + gap * w - R_S * c.y);
  out->radius = r;
  out->R_D = R_D.cast<Real>();
  out->t_D = centre.cast<Real>();
  out->shape = shape;
  out->known_distance = std::max(0.0, gap);
  out->detail = std::string(featureName(feature)) + (disk_face ? " on the disk's face" : " at the rim") +
                (align ? ", edge parallel to the rim" : "") + ", gap " + number(gap);
  return true;
}

template <typename Shape>
Feature randomFeature(Random& rng) {
  for (;;) {
    const Feature f = Feature(pick(rng, 4));
    if (hasFeature<Shape>(f)) return f;
  }
}

template <typename Shape>
void randomCase(Random& rng, DiskShapeCase<Shape>* out) {
  Shape shape = ShapeGen<Shape>::make(rng);
  setPose(&shape, rng.rotation(), rng.inBall(3));
  out->radius = rng.uniform(0.2, 2);
  out->R_D = rng.rotation().cast<Real>();
  out->t_D = rng.inBall(2).cast<Real>();
  out->shape = shape;
  out->detail = "random";
}

template <typename Shape>
void overlappingCase(Random& rng, DiskShapeCase<Shape>* out) {
  using Gen = ShapeGen<Shape>;
  Shape shape = Gen::make(rng);
  double clearance;
  const Vd inner = Gen::interior(rng, shape, &clearance);
  Contact c;
  Gen::contact(rng, shape, Feature::smooth, &c);
  const double depth = std::pow(10.0, rng.uniform(-12, 0));
  const Vd y = c.y + depth * (inner - c.y);  // a convex combination: in the shape
  const double r = rng.uniform(0.05, 2);
  const Md R_D = rng.rotation();
  const Vd centre = rng.inBall(1);
  const Vd x = centre + inDisk(rng, r, R_D.col(0), R_D.col(1));
  const Md R_S = rng.rotation();
  setPose(&shape, R_S, x - R_S * y);
  out->radius = r;
  out->R_D = R_D.cast<Real>();
  out->t_D = centre.cast<Real>();
  out->shape = shape;
  out->known_distance = 0;
  out->detail = "depth " + number(depth) + " of the way in";
}

template <typename Shape>
void insideCase(Random& rng, DiskShapeCase<Shape>* out) {
  using Gen = ShapeGen<Shape>;
  Shape shape = Gen::make(rng);
  double clearance;
  const Vd y = Gen::interior(rng, shape, &clearance);
  const Md R_S = rng.rotation();
  const Vd t_S = rng.inBall(2);
  setPose(&shape, R_S, t_S);
  out->radius = rng.uniform(0.05, 0.95) * clearance;
  out->R_D = rng.rotation().cast<Real>();
  out->t_D = (R_S * y + t_S).cast<Real>();
  out->shape = shape;
  out->known_distance = 0;
  out->detail = "clearance " + number(clearance);
}

template <typename Shape>
void translateCase(DiskShapeCase<Shape>* c, const Vd& T) {
  c->t_D = (c->t_D.template cast<double>() + T).template cast<Real>();
  c->shape.t = (c->shape.t.template cast<double>() + T).template cast<Real>();
}

template <typename Shape>
void scaleCase(DiskShapeCase<Shape>* c, double k) {
  c->radius = double(c->radius) * k;
  c->t_D = (c->t_D.template cast<double>() * k).template cast<Real>();
  c->shape.t = (c->shape.t.template cast<double>() * k).template cast<Real>();
  ShapeGen<Shape>::scaleDims(&c->shape, k);
  if (c->hasKnownDistance()) c->known_distance *= k;
}

/// The cases that "far" and "scaled" move: random, touching, separated (gap
/// 1e-12..10 sizes) or a face on the disk's face.
template <typename Shape>
void baseCase(Random& rng, DiskShapeCase<Shape>* out) {
  const double u = rng.uniform01();
  if (u < 0.25) {
    randomCase(rng, out);
  } else if (u < 0.5) {
    supportPlacement(rng, randomFeature<Shape>(rng), 0.0, false, false, out);
  } else if (u < 0.75 || !hasFeature<Shape>(Feature::face)) {
    supportPlacement(rng, randomFeature<Shape>(rng), std::pow(10.0, rng.uniform(-12, 1)), false,
                     false, out);
  } else {
    supportPlacement(rng, Feature::face, rng.chance(0.5) ? 0.0 : std::pow(10.0, rng.uniform(-12, 0)),
                     true, false, out);
  }
}

}  // namespace detail

/// Applies f to every stored dimension of a shape (not its pose), for rounding
/// a case to a scalar type.
template <typename F> void forEachDimension(ref::Sphere* s, F f) { f(&s->radius); }
template <typename F> void forEachDimension(ref::Box* s, F f) {
  for (int i = 0; i < 3; ++i) f(&s->side[i]);
}
template <typename F> void forEachDimension(ref::Capsule* s, F f) { f(&s->radius); f(&s->lz); }
template <typename F> void forEachDimension(ref::Cylinder* s, F f) { f(&s->radius); f(&s->lz); }
template <typename F> void forEachDimension(ref::Cone* s, F f) { f(&s->radius); f(&s->lz); }
template <typename F> void forEachDimension(ref::Ellipsoid* s, F f) {
  for (int i = 0; i < 3; ++i) f(&s->radii[i]);
}
template <typename F> void forEachDimension(ref::Convex* s, F f) {
  for (V3& x : s->vertices)
    for (int i = 0; i < 3; ++i) f(&x[i]);
}
template <typename F> void forEachDimension(ref::Halfspace* s, F f) {
  for (int i = 0; i < 3; ++i) f(&s->n[i]);
  f(&s->d);
}
template <typename F> void forEachDimension(ref::Plane* s, F f) {
  for (int i = 0; i < 3; ++i) f(&s->n[i]);
  f(&s->d);
}
template <typename F> void forEachDimension(ref::TriangleP* s, F f) {
  for (int i = 0; i < 3; ++i) {
    f(&s->a[i]);
    f(&s->b[i]);
    f(&s->c[i]);
  }
}

/// The case with every value rounded to S (exactly representable afterwards).
template <typename S, typename Shape>
DiskShapeCase<Shape> roundedTo(DiskShapeCase<Shape> c) {
  const auto round = [](Real* x) { *x = Real(S(*x)); };
  round(&c.radius);
  for (int i = 0; i < 9; ++i) {
    round(&c.R_D.data()[i]);
    round(&c.shape.R.data()[i]);
  }
  for (int i = 0; i < 3; ++i) {
    round(&c.t_D[i]);
    round(&c.shape.t[i]);
  }
  forEachDimension(&c.shape, round);
  return c;
}

/// `count` cases of `family` for Shape, deterministic for a seed; empty when the
/// family does not apply to the shape.
template <typename Shape>
std::vector<DiskShapeCase<Shape>> makeFamily(Family family, int count, std::uint64_t seed) {
  std::vector<DiskShapeCase<Shape>> out;
  if (!familyApplies<Shape>(family)) return out;
  Random rng(seed * 1000003u + std::uint64_t(family) * 7919u +
             detail::nameHash(ShapeGen<Shape>::kName));
  while (int(out.size()) < count) {
    DiskShapeCase<Shape> c;
    bool ok = true;
    switch (family) {
      case Family::random: detail::randomCase(rng, &c); break;
      case Family::separated:
        ok = detail::supportPlacement(rng, detail::randomFeature<Shape>(rng),
                                      std::pow(10.0, rng.uniform(-12, 6)), false, false, &c);
        break;
      case Family::touching:
        ok = detail::supportPlacement(rng, detail::randomFeature<Shape>(rng), 0.0, false, false, &c);
        break;
      case Family::overlapping: detail::overlappingCase(rng, &c); break;
      case Family::parallel_face: {
        const bool edge = hasFeature<Shape>(Feature::edge) && rng.chance(0.25);
        const double gap = rng.chance(0.4) ? 0.0 : std::pow(10.0, rng.uniform(-12, 0));
        ok = detail::supportPlacement(rng, edge ? Feature::edge : Feature::face, gap, true, false, &c);
        break;
      }
      case Family::rim_edge: {
        const double gap = rng.chance(0.5) ? 0.0 : std::pow(10.0, rng.uniform(-12, 0));
        ok = detail::supportPlacement(rng, Feature::edge, gap, false, rng.chance(0.5), &c);
        break;
      }
      case Family::vertex_face: {
        const double gap = rng.chance(0.5) ? 0.0 : std::pow(10.0, rng.uniform(-12, 0));
        ok = detail::supportPlacement(rng, Feature::vertex, gap, true, false, &c);
        break;
      }
      case Family::inside: detail::insideCase(rng, &c); break;
      case Family::far: {
        detail::baseCase(rng, &c);
        const double len = std::pow(10.0, rng.uniform(5, 6));
        detail::translateCase(&c, len * rng.unitVector());
        c.detail += ", translated by " + detail::number(len);
        break;
      }
      case Family::scaled: {
        detail::baseCase(rng, &c);
        const double k = std::pow(10.0, rng.uniform(-6, 6));
        detail::scaleCase(&c, k);
        c.detail += ", scaled by " + detail::number(k);
        break;
      }
    }
    if (!ok) continue;
    c.family = familyName(family);
    out.push_back(roundedTo<double>(c));
  }
  return out;
}

}  // namespace shape_families
}  // namespace fcl_disk_test

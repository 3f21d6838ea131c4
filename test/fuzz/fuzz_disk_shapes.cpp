// libFuzzer target: fcl_disk::diskShapeDistance / diskShapeIntersect for a disk
// against every FCL primitive, double and float.
//
// The first byte picks the shape (ten kinds), the second the mode (its value
// mod 3), float (bit 0x80) and, for Convex, a large hull (bit 0x40,
// makeLargeHull) instead of an 8-vertex frustum:
// * raw: radius, dimensions and poses straight from IEEE bit patterns (NaN, inf,
//   negative, huge, denormal, non-orthonormal): input describing no pair must
//   give NaN distance, lower_bound and points and no contact; a valid pair must
//   give a finite, checked answer;
// * aligned: the shape placed so that its support point along -w is `gap` from
//   the disk's support point along w (test/disk_shape_oracle.h), so the
//   distance is exactly gap; gaps and lengths span 1e-9..1e6 of the scene, w is
//   random, the disk's normal, or a shape's face normal;
// * random: fractions of the bytes as dimensions and poses in the unit ball.
// Every valid answer: the disk point on the disk and the shape point on the
// shape (long double distances of disk_shape_oracle.h), |p - q| == distance,
// lower_bound <= distance, the aligned gap matched within kFuzzRelative* of the
// scene where the certificate is closed (else lower_bound <= truth <=
// distance), and diskShapeIntersect agreeing with distance 0 outside the
// touching band. An intersecting pair of a shape with an exact penetration
// depth (kExactDiskShapePenetration; bounded shapes here): the contact's depth
// is the shortest separating translation, depth <= F(w) = h_disk(w) +
// h_shape(-w) on the disk's normals, the shape frame's axes and a Fibonacci
// sphere of directions, a step past it along the normal separates and a step
// short of it does not. Bounds are loose multiples of the documented ones: the fuzzer hunts
// crashes, hangs and gross errors; the tests hold the exact bounds.
#include <fcl_disk/disk_shape_distance.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "disk_shape_fcl.h"
#include "disk_shape_oracle.h"
#include "fuzz_checks.h"
#include "fuzz_input.h"

namespace {

using namespace fcl_disk_test::oracle;
using fcl_disk_fuzz::ByteReader;

/// Abort thresholds, relative to the scene: 1e3 times the documented 1e-12 in
/// double; in float 64 ulps (the answer is rounded to float).
constexpr double kFuzzRelativeDouble = 1e-9;
constexpr double kFuzzRelativeFloat = 64 * 1.1920928955078125e-07;
/// A certified gap below this counts as closed (the header promises 1e-12 of the
/// scene on converged answers; an open one must still bracket the truth).
constexpr double kFuzzGapRelative = 1e-9;

[[noreturn]] void fail(const std::string& what, const std::string& detail) {
  std::fprintf(stderr, "invariant violated: %s\n  %s\n", what.c_str(), detail.c_str());
  std::abort();
}

/// A large hull for the Convex pair's paths of many faces and vertices
/// (src/pairs/disk_convex.cpp: the support search from 64 vertices, the face
/// graph's climb from 100 faces, the vertex clusters from 128 vertices): a
/// prism over an ellipse's inscribed N-gon, N = 32..79 (64..158 vertices),
/// its top ring scaled by `taper` (0: all top vertices one point), its sides
/// quadrilaterals or, with the byte's low bit, pairs of coplanar triangles
/// (N + 2 or 2 N + 2 faces: the climb from N = 49 on). Sizes stop there: the
/// oracle's long-double distances grow with the faces, and the target's other
/// shapes share its time.
void makeLargeHull(ByteReader& in, Real a, Real b, Real h, Real taper, Shape* s) {
  const std::uint8_t shape_byte = in.byte();
  const int n = 32 + (shape_byte >> 1) % 48;
  const bool triangulated = shape_byte & 1;
  for (const Real z : {-h, h}) {
    const Real ring = z < 0 ? Real(1) : taper;
    for (int k = 0; k < n; ++k) {
      const Real angle = 2 * Real(3.14159265358979323846) * k / n;
      s->vertices.emplace_back(ring * a * std::cos(angle), ring * b * std::sin(angle), z);
    }
  }
  std::vector<int> bottom, top;  // counter-clockwise seen from outside
  for (int k = 0; k < n; ++k) bottom.push_back(n - 1 - k), top.push_back(n + k);
  s->faces = {bottom, top};
  for (int k = 0; k < n; ++k) {
    const int next = (k + 1) % n;
    if (triangulated) {
      s->faces.push_back({k, next, n + next});
      s->faces.push_back({k, n + next, n + k});
    } else {
      s->faces.push_back({k, next, n + next, n + k});
    }
  }
}

Shape makeShape(Kind kind, ByteReader& in, bool raw, bool large_hull) {
  Shape s;
  s.kind = kind;
  auto length = [&] { return raw ? Real(in.raw<double>()) : Real(0.02 + in.fraction()); };
  switch (kind) {
    case Kind::sphere: s.dims = V3(length(), 0, 0); break;
    case Kind::box:
    case Kind::ellipsoid: s.dims = V3(length(), length(), length()); break;
    case Kind::capsule:
    case Kind::cylinder:
    case Kind::cone: s.dims = V3(length(), length(), 0); break;
    case Kind::convex: {
      // Fractions even in raw mode: FCL's own Convex constructor is not the target.
      const Real a = Real(0.02 + in.fraction()), b = Real(0.02 + in.fraction()),
                 h = Real(0.02 + in.fraction()), t = Real(in.fraction());
      if (large_hull) {
        makeLargeHull(in, a, b, h, t, &s);
        break;
      }
      s.vertices = {V3(-a, -b, -h), V3(a, -b, -h), V3(a, b, -h), V3(-a, b, -h),
                    V3(-a * t, -b * t, h), V3(a * t, -b * t, h), V3(a * t, b * t, h), V3(-a * t, b * t, h)};
      s.faces = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
      break;
    }
    case Kind::halfspace:
    case Kind::plane:
      s.n = V3(Real(in.fraction() - 0.5), Real(in.fraction() - 0.5), Real(in.fraction() - 0.5));
      if (!(s.n.norm() > 1e-3)) s.n = V3::UnitZ();
      s.n.normalize();
      s.d = raw ? Real(in.raw<double>()) : Real(in.fraction() - 0.5);
      break;
    case Kind::triangle:
      for (int i = 0; i < 3; ++i) {
        s.vertices.push_back(raw ? V3(Real(in.raw<double>()), Real(in.raw<double>()), Real(in.raw<double>()))
                                 : V3(Real(in.fraction() - 0.5), Real(in.fraction() - 0.5),
                                      Real(in.fraction() - 0.5)));
      }
      break;
  }
  return s;
}

M3 rotationFrom(ByteReader& in) {
  Eigen::Quaternion<Real> q(Real(in.fraction() - 0.5), Real(in.fraction() - 0.5),
                            Real(in.fraction() - 0.5), Real(in.fraction() - 0.5));
  if (!(q.norm() > 1e-3)) q = Eigen::Quaternion<Real>::Identity();
  return q.normalized().toRotationMatrix();
}

/// Whether the input describes a pair (the library's rule, written here).
template <typename S>
bool describesPair(const Shape& s, S r, const fcl::Transform3<S>& X_WD, const fcl::Transform3<S>& X_WS) {
  const auto finite_lengths = [&] {
    for (int i = 0; i < 3; ++i) {
      if (!(S(s.dims[i]) >= S(0) && S(s.dims[i]) <= fcl_disk::kMaxDiskLength<S>)) return false;
    }
    for (const V3& v : s.vertices) {
      for (int i = 0; i < 3; ++i) {
        if (!(std::abs(S(v[i])) <= fcl_disk::kMaxDiskLength<S>)) return false;
      }
    }
    return !(s.kind == Kind::halfspace || s.kind == Kind::plane) ||
           std::abs(S(s.d)) <= fcl_disk::kMaxDiskLength<S>;
  };
  return fcl_disk::isValidDiskRadius(r) && fcl_disk::isValidDiskPose(X_WD) &&
         fcl_disk::isValidDiskPose(X_WS) && finite_lengths();
}

/// The penetration depth's checks (see the top): `tolerance` as check()'s.
template <typename S>
void checkPenetration(const Shape& shape, const fcl::ShapeBase<S>& fcl_shape, S r,
                      const fcl::Transform3<S>& X_WD, const fcl::Transform3<S>& X_WS, const Disk& disk,
                      const Pose& X, Real tolerance, const char* detail) {
  const bool exact = withShapeClass(fcl_shape, [](const auto& typed) {
    return fcl_disk::kExactDiskShapePenetration<std::decay_t<decltype(typed)>>;
  });
  if (!exact || shape.kind == Kind::halfspace || shape.kind == Kind::plane) return;
  fcl_disk::DiskContact<S> contact;
  if (!withShapeClass(fcl_shape, [&](const auto& typed) {
        return fcl_disk::diskShapeIntersect(r, X_WD, typed, X_WS, &contact);
      })) {
    return;
  }
  const Real depth = Real(contact.penetration_depth);
  const V3 normal = contact.normal.template cast<Real>();
  const auto text = [](Real x) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.17g", double(x));
    return std::string(buffer);
  };
  std::string with_depth = std::string(detail) + "\n  depth " + text(depth) + " along (" +
                           text(normal.x()) + " " + text(normal.y()) + " " + text(normal.z()) +
                           "), tolerance " + text(tolerance);
  for (const V3& v : shape.vertices) {
    with_depth += "\n  vertex " + text(v.x()) + " " + text(v.y()) + " " + text(v.z());
  }
  if (!(std::isfinite(double(depth)) && depth >= 0 && std::abs(normal.norm() - 1) <= 1e-6)) {
    fail("the contact's depth is finite, >= 0, along a unit normal", with_depth);
  }
  // F(w): translating the shape by F(w) w separates along w.
  const auto separating_length = [&](const V3& w) {
    const V3 lowest = X.t + X.R * supportPoint(shape, X.R.transpose() * -w);
    return disk.supportPoint(w).dot(w) - lowest.dot(w);
  };
  std::vector<V3> directions = {disk.normal(), -disk.normal()};
  for (int i = 0; i < 3; ++i) directions.insert(directions.end(), {X.R.col(i), -X.R.col(i)});
  constexpr int kSphereDirections = 64;
  for (int k = 0; k < kSphereDirections; ++k) {
    const Real z = 1 - (2 * k + 1) / Real(kSphereDirections), ring = std::sqrt(1 - z * z);
    const Real angle = k * Real(2.399963229728653);  // the golden angle
    directions.emplace_back(ring * std::cos(angle), ring * std::sin(angle), z);
  }
  for (const V3& w : directions) {
    if (!(depth <= separating_length(w) + tolerance)) {
      fail("depth <= F(w) for every direction w (the shortest translation)",
           with_depth + "\n  F(w) " + text(separating_length(w)) + " along (" + text(w.x()) +
               " " + text(w.y()) + " " + text(w.z()) + ")");
    }
  }
  // A step far above the tolerance: each side is decided robustly.
  const Real step = 1e3 * tolerance;
  const auto moved = [&](Real length) {
    fcl::Transform3<S> X_moved = X_WS;
    X_moved.translation() = (X.t + length * normal).template cast<S>();
    return X_moved;
  };
  if (diskShapeIntersectAny(r, X_WD, fcl_shape, moved(depth + step))) {
    fail("moving the shape by (depth + step) normal separates", with_depth);
  }
  if (depth > 2 * step && !diskShapeIntersectAny(r, X_WD, fcl_shape, moved(depth - step))) {
    fail("moving the shape by (depth - step) normal leaves them intersecting", with_depth);
  }
}

template <typename S>
void check(const Shape& wanted, S r, const fcl::Transform3<S>& X_WD, const fcl::Transform3<S>& X_WS,
           Real truth) {
  const auto fcl_shape = toFcl<S>(wanted);
  const fcl_disk::DiskShapeDistanceResult<S> result = diskShapeDistanceAny(r, X_WD, *fcl_shape, X_WS);
  const bool intersect = diskShapeIntersectAny(r, X_WD, *fcl_shape, X_WS);
  char detail[2048];
  const auto& D = X_WD.matrix();
  const auto& M = X_WS.matrix();
  std::snprintf(detail, sizeof detail,
                "%s %s: r %.17g dims (%.17Lg %.17Lg %.17Lg) distance %.17g lower %.17g truth %.17Lg\n"
                "  X_WD rows (%.17g %.17g %.17g %.17g) (%.17g %.17g %.17g %.17g) (%.17g %.17g %.17g %.17g)\n"
                "  X_WS rows (%.17g %.17g %.17g %.17g) (%.17g %.17g %.17g %.17g) (%.17g %.17g %.17g %.17g)",
                kindName(wanted.kind), std::is_same<S, float>::value ? "float" : "double", double(r),
                wanted.dims.x(), wanted.dims.y(), wanted.dims.z(), double(result.distance),
                double(result.lower_bound), truth, double(D(0, 0)), double(D(0, 1)), double(D(0, 2)),
                double(D(0, 3)), double(D(1, 0)), double(D(1, 1)), double(D(1, 2)), double(D(1, 3)),
                double(D(2, 0)), double(D(2, 1)), double(D(2, 2)), double(D(2, 3)), double(M(0, 0)),
                double(M(0, 1)), double(M(0, 2)), double(M(0, 3)), double(M(1, 0)), double(M(1, 1)),
                double(M(1, 2)), double(M(1, 3)), double(M(2, 0)), double(M(2, 1)), double(M(2, 2)),
                double(M(2, 3)));
  if (fcl_disk_fuzz::printInputs()) {
    std::fprintf(stderr, "%s\n", detail);
    for (const V3& v : wanted.vertices) {
      std::fprintf(stderr, "  vertex %.17Lg %.17Lg %.17Lg\n", v.x(), v.y(), v.z());
    }
  }
  if (!describesPair(wanted, r, X_WD, X_WS)) {
    if (!(std::isnan(result.distance) && std::isnan(result.lower_bound) &&
          result.p_W_disk.array().isNaN().all() && result.p_W_shape.array().isNaN().all()) ||
        intersect) {
      fail("input describing no pair gives NaN and no contact", detail);
    }
    return;
  }
  Shape shape = wanted;  // as stored in S; halfspace and plane normals as FCL keeps them
  for (int i = 0; i < 3; ++i) shape.dims[i] = Real(S(shape.dims[i]));
  for (V3& v : shape.vertices) v = v.cast<S>().template cast<Real>();
  if (shape.kind == Kind::halfspace) {
    shape.n = static_cast<const fcl::Halfspace<S>&>(*fcl_shape).n.template cast<Real>();
    shape.d = Real(static_cast<const fcl::Halfspace<S>&>(*fcl_shape).d);
  } else if (shape.kind == Kind::plane) {
    shape.n = static_cast<const fcl::Plane<S>&>(*fcl_shape).n.template cast<Real>();
    shape.d = Real(static_cast<const fcl::Plane<S>&>(*fcl_shape).d);
  }
  if (!std::isfinite(double(result.distance))) fail("a valid pair gives a finite distance", detail);
  const Disk disk{X_WD.translation().template cast<Real>(), X_WD.linear().col(0).template cast<Real>(),
                  X_WD.linear().col(1).template cast<Real>(), Real(r)};
  Pose X;
  X.R = X_WS.linear().template cast<Real>();
  X.t = X_WS.translation().template cast<Real>();
  const bool boundary = shape.kind == Kind::halfspace || shape.kind == Kind::plane;
  const Real scale = disk.r + shape.boundingRadius() +
                     (boundary ? std::abs((X.R * shape.n).dot(disk.c - X.t) - shape.d) : (disk.c - X.t).norm());
  const Real far = std::max(disk.c.norm(), X.t.norm());
  const Real relative = std::is_same<S, float>::value ? kFuzzRelativeFloat : kFuzzRelativeDouble;
  // An accepted rotation is used as given (disk_pair.h): its defect costs about
  // defect * scale beyond the solver's bound (raw poses only; ours are ~1 ulp).
  const Real defect_cost = Real(fcl_disk_fuzz::kDefectNormFactor) *
                           Real(std::max(fcl_disk_fuzz::rotationDefect(X_WD), fcl_disk_fuzz::rotationDefect(X_WS))) *
                           scale;
  const Real tolerance = relative * scale + 8 * Real(std::numeric_limits<S>::epsilon()) * far + defect_cost;
  const V3 p = result.p_W_disk.template cast<Real>(), q = result.p_W_shape.template cast<Real>();
  if (!(pointToDisk(disk, p) <= tolerance)) fail("the disk point lies on the disk", detail);
  if (!(pointDistanceWorld(shape, X, q) <= tolerance)) fail("the shape point lies on the shape", detail);
  if (!(std::abs((p - q).norm() - Real(result.distance)) <= 2 * tolerance)) fail("|p - q| == distance", detail);
  if (!(result.lower_bound <= result.distance)) fail("lower_bound <= distance", detail);
  // Closed certificate: the distance is the aligned gap. Open (the iteration
  // stopped at its cap, documented for nearly parallel faces whose rims cross):
  // the answer is still an honest bracket, lower_bound <= truth <= distance.
  const bool closed = Real(result.distance - result.lower_bound) <= kFuzzGapRelative * scale + tolerance;
  if (truth >= 0 && closed && !(std::abs(Real(result.distance) - truth) <= tolerance)) {
    fail("the distance equals the aligned gap", detail);
  }
  if (truth >= 0 && !(Real(result.lower_bound) <= truth + tolerance &&
                      truth <= Real(result.distance) + tolerance)) {
    fail("lower_bound <= the aligned gap <= distance", detail);
  }
  const Real band = 1e3 * tolerance;
  if (result.distance == 0 && !intersect) fail("distance 0 means intersecting", detail);
  if (Real(result.distance) > band && intersect) fail("apart means not intersecting", detail);
  if (intersect) checkPenetration<S>(shape, *fcl_shape, r, X_WD, X_WS, disk, X, tolerance, detail);
}

template <typename S>
void run(ByteReader& in, Kind kind, int mode, bool large_hull) {
  const bool raw = mode == 0;
  Shape shape = makeShape(kind, in, raw, large_hull);
  fcl::Transform3<S> X_WD = fcl::Transform3<S>::Identity(), X_WS = fcl::Transform3<S>::Identity();
  S r;
  Real truth = -1;
  if (raw) {
    r = S(in.raw<double>());
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 4; ++j) X_WD.matrix()(i, j) = S(in.raw<double>());
    }
    X_WS.linear() = rotationFrom(in).cast<S>();
    X_WS.translation() = fcl::Vector3<S>(S(in.raw<double>()), S(in.raw<double>()), S(in.raw<double>()));
  } else {
    const Real k = std::pow(Real(10), Real(12 * in.fraction() - 6));  // every length
    for (int i = 0; i < 3; ++i) shape.dims[i] *= k;
    for (V3& v : shape.vertices) v *= k;
    shape.d *= k;
    r = S(Real(0.02 + in.fraction()) * k);
    const M3 R_disk = rotationFrom(in), R_shape = rotationFrom(in);
    const V3 offset = in.byte() % 4 == 0 ? V3(rotationFrom(in).col(0) * k * Real(1e5)) : V3::Zero();
    const Disk disk{offset, R_disk.col(0), R_disk.col(1), Real(r)};
    Pose X;
    if (mode == 1) {
      // Aligned: w random, the disk normal, or (halfspace, plane) the normal.
      V3 w = rotationFrom(in).col(2);
      if (in.byte() % 2 == 0) w = R_disk.col(2);
      if (kind == Kind::halfspace || kind == Kind::plane) w = -(R_shape * shape.n);
      const Real gap = (r + shape.boundingRadius()) * std::pow(Real(10), Real(15 * in.fraction() - 9)) *
                       (in.byte() % 8 == 0 ? 0 : 1);
      X = alignedPair(disk, shape, R_shape, w, gap);
      truth = gap;
    } else {
      X.R = R_shape;
      X.t = offset + rotationFrom(in).col(0) * k * Real(1.5 * in.fraction());
    }
    X_WD.linear() = R_disk.cast<S>();
    X_WD.translation() = offset.cast<S>();
    X_WS.linear() = X.R.cast<S>();
    X_WS.translation() = X.t.cast<S>();
    // Rounding the poses to S moves the aligned truth by about an ulp of the
    // offset: keep it only where that is negligible.
    if (Real(std::numeric_limits<S>::epsilon()) * offset.norm() > 1e-3 * Real(kFuzzRelativeDouble) * k) truth = -1;
  }
  check<S>(shape, r, X_WD, X_WS, truth);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ByteReader in(data, size);
  const Kind kind = Kind(in.byte() % 10);
  const std::uint8_t mode_byte = in.byte();
  const int mode = mode_byte % 3;
  const bool large_hull = mode_byte & 0x40;  // Convex only
  if (mode_byte & 0x80) {
    run<float>(in, kind, mode, large_hull);
  } else {
    run<double>(in, kind, mode, large_hull);
  }
  return 0;
}

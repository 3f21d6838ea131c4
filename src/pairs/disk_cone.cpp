// Disk - fcl::Cone: the apex (closed form) or the base (the disk-disk solver)
// where their certificates close, else the generic solver with the cone's
// projection, computed in the meridian half-plane (a right triangle) and turned
// about the axis, and its support (apex or base rim).
// docs/disk_shape_distance.md, section 4. The
// contact's directions make its depth the exact penetration depth
// (docs/penetration_depth.md, section 7).
#include "../disk_shape_pair.h"
#include "feature_candidates.h"
#include "flat_end_pair.h"

#include <vector>

namespace fcl_disk {
namespace internal {
namespace {

/// The solid cone of FCL: base disk of radius `radius` at z = -half_length, apex
/// at z = +half_length, in its frame. In the meridian half-plane (rho, z), rho >= 0
/// the distance from the axis, it is the triangle O = (0, -h), B = (radius, -h),
/// A = (0, h).
struct ConeTarget {
  double radius;
  double half_length;

  /// Nearest point of the segment from `from` to `to` to `point` (meridian
  /// coordinates); its Jacobian is u u^T with u the unit edge direction inside
  /// the segment (*weight = 1), 0 at an end (*weight = 0).
  static Vec2 nearestOnEdge(const Vec2& point, const Vec2& from, const Vec2& to, Vec2* unit_edge,
                            double* weight) {
    const Vec2 edge = to - from;
    const double length_squared = edge.squaredNorm();
    double t = length_squared > 0.0 ? edge.dot(point - from) / length_squared : 0.0;
    *unit_edge = length_squared > 0.0 ? Vec2(edge / std::sqrt(length_squared)) : Vec2(1.0, 0.0);
    *weight = t > 0.0 && t < 1.0 ? 1.0 : 0.0;
    return from + std::clamp(t, 0.0, 1.0) * edge;
  }

  Projection project(const Vec3& y) const {
    const double h = half_length;
    const double rho = std::sqrt(y.x() * y.x() + y.y() * y.y());
    const Vec2 m(rho, y.z());
    // Inside: above the base, under the slant side A-B (written without a
    // division so that degenerate cones, radius or height 0, stay exact).
    if (y.z() >= -h && y.z() <= h && rho <= radius &&
        2.0 * h * rho + radius * (y.z() - h) <= 0.0) {
      return Projection{y, FactoredHessian()};
    }
    // Outside, the nearest point is on the slant side A-B or on the base O-B
    // (whose end O lies on the axis, inside the base disk: no corner).
    Vec2 side_edge;
    double side_weight;
    const Vec2 on_side = nearestOnEdge(m, Vec2(0.0, h), Vec2(radius, -h), &side_edge, &side_weight);
    const Vec2 on_base(std::min(rho, radius), -h);
    const bool side = (m - on_side).squaredNorm() <= (m - on_base).squaredNorm();
    const Vec2 nearest = side ? on_side : on_base;
    const Vec2 unit_edge = side ? side_edge : Vec2(1.0, 0.0);
    const double jacobian_weight = side ? side_weight : (rho <= radius ? 1.0 : 0.0);
    // Back to 3-D: the radial direction e (any, on the axis) and the tangent t;
    // turning about the axis scales by nearest_rho / rho. D proj is the
    // meridian Jacobian (u u^T: u the edge direction, or e on the base, or 0
    // at a corner) plus turn * t t^T, so psi's Hessian is I - u u^T - turn t t^T.
    const Vec3 e = rho > 0.0 ? Vec3(y.x() / rho, y.y() / rho, 0.0) : Vec3::UnitX();
    const Vec3 t(-e.y(), e.x(), 0.0);
    const double turn = rho > 0.0 ? nearest.x() / rho : jacobian_weight * unit_edge.x() * unit_edge.x();
    FactoredHessian hessian = FactoredHessian::identity();
    if (jacobian_weight > 0.0) hessian.add(-1.0, unit_edge.x() * e + unit_edge.y() * Vec3::UnitZ());
    hessian.add(-turn, t);
    const Vec3 q_S = nearest.x() * e + nearest.y() * Vec3::UnitZ();
    return Projection{q_S, hessian};
  }

  Vec3 support(const Vec3& w_S) const {
    const double planar = std::sqrt(w_S.x() * w_S.x() + w_S.y() * w_S.y());
    const Vec3 apex(0.0, 0.0, half_length);
    const Vec3 rim = planar > 0.0 ? Vec3(radius * w_S.x() / planar, radius * w_S.y() / planar,
                                         -half_length)
                                  : Vec3(radius, 0.0, -half_length);
    // Ties take the apex.
    return w_S.dot(rim) > w_S.dot(apex) ? rim : apex;
  }

  /// The base: a candidate where a nearly parallel disk's rim crosses its rim.
  std::array<FlatEnd, 1> flatEnds() const { return {FlatEnd{-half_length, radius}}; }
};

/// Appends the directions w = -m on the circle of the cone's side normals m at
/// which F is stationary along that circle. With the base radius rho, half
/// length h and L = |(2h, rho)|, the outward side normal at azimuth phi is m(phi)
/// = (2h cos phi, 2h sin phi, rho) / L, and there the cone's support at m is the
/// whole generator from the apex a to the base rim; F(-m) = h_disk(-m) + m.a.
/// dF/dphi = (a - b).m' with b the disk's support point at -m, so a critical
/// phi has g = b - a normal to the base circle's tangent, (cos phi, sin phi) =
/// +-g_xy / |g_xy|, while -m is in the disk's normal cone at b(theta): m normal
/// to the rim tangent t(theta). Eliminating phi:
///   G(theta) = (2h)^2 (g_xy . t_xy)^2 - rho^2 t_z^2 |g_xy|^2 = 0,
/// a trigonometric polynomial of degree 4 (every root, trig_roots.h; squaring
/// adds only candidates, each an upper bound). Each root's phi is taken from
/// both conditions: from g_xy (undefined where the rim point is on the axis)
/// and from m . t = 0 (two solutions; ill-conditioned where t is nearly
/// vertical), all appended.
template <typename Search>
void addConeSideCandidates(const DiskInShape& disk, double radius, double half_length,
                           Search* directions) {
  using namespace trig_roots;
  const double height = 2.0 * half_length;  // the 2h of the side normal
  const double slant = std::hypot(height, radius);
  if (!(slant > 0.0)) return;  // a point: the apex's candidates
  const Vec3 apex(0.0, 0.0, half_length);
  const Vec3 d = disk.c - apex;
  const auto normal_at = [&](double cos_phi, double sin_phi) {
    return Vec3(height * cos_phi, height * sin_phi, radius);
  };
  static const AngleTable<kSamples> angles;
  std::array<double, kSamples> samples;
  for (int j = 0; j < kSamples; ++j) {
    const Vec3 g = d + disk.r * (angles.cos[j] * disk.u + angles.sin[j] * disk.v);
    const Vec3 t = angles.cos[j] * disk.v - angles.sin[j] * disk.u;
    const double along = g.x() * t.x() + g.y() * t.y();
    samples[j] = height * height * along * along -
                 radius * radius * t.z() * t.z() * (g.x() * g.x() + g.y() * g.y());
  }
  const double size = d.norm() + disk.r;  // bounds |g|
  const double noise = kBernsteinNoise * slant * slant * size * size;
  forEachRootAngle(TrigPolynomial::fromSamples(samples), noise, [&](double cos_theta, double sin_theta) {
    const Vec3 g = d + disk.r * (cos_theta * disk.u + sin_theta * disk.v);
    const double g_xy = std::hypot(g.x(), g.y());
    if (g_xy > 0.0) {
      directions->push_back(normal_at(g.x() / g_xy, g.y() / g_xy));
      directions->push_back(normal_at(-g.x() / g_xy, -g.y() / g_xy));
    }
    // m . t = 0: 2h (t_x cos phi + t_y sin phi) = -rho t_z.
    const Vec3 t = cos_theta * disk.v - sin_theta * disk.u;
    const double amplitude = height * std::hypot(t.x(), t.y());
    if (!(amplitude > 0.0)) return;
    const double cosine = std::clamp(-radius * t.z() / amplitude, -1.0, 1.0);
    const double sine = std::sqrt((1.0 - cosine) * (1.0 + cosine));
    const double base_cos = height * t.x() / amplitude, base_sin = height * t.y() / amplitude;
    for (const double side : {1.0, -1.0}) {
      directions->push_back(normal_at(cosine * base_cos - side * sine * base_sin,
                                      cosine * base_sin + side * sine * base_cos));
    }
  });
}

template <typename S>
struct ConeTraits {
  static bool valid(const fcl::Cone<S>& cone) {
    return areValidShapeLengths({double(cone.radius), double(cone.lz)});
  }
  static double boundingRadius(const fcl::Cone<S>& cone) {
    return Vec2(double(cone.radius), 0.5 * double(cone.lz)).norm();
  }
  static double inflation(const fcl::Cone<S>&) { return 0.0; }
  static ConeTarget target(const fcl::Cone<S>& cone) {
    return ConeTarget{double(cone.radius), 0.5 * double(cone.lz)};
  }
  /// Two exact cases, each tried where the disk's centre says it is likely
  /// (docs/disk_shape_distance.md, section 4); what neither settles goes to the
  /// generic solver. `disk`'s axes are orthonormal (solvedDiskInShape).
  /// - the apex, for a centre above it: the disk's point p nearest the apex
  ///   (closed form) is optimal when p - apex lies in the cone's normal cone
  ///   at the apex, radius |(p - apex)_xy| <= 2 half_length (p - apex)_z (the
  ///   apex is then p's nearest cone point: the KKT conditions of the convex
  ///   pair); the certificate along the pair proves it;
  /// - the base, a disk (diskAgainstFlatEnd: exact where the certificate along
  ///   the disk-base pair closes), for a centre beyond the base's plane, or
  ///   beside the cone with its nearest cone point at the base's rim (in the
  ///   meridian half-plane, past the slant side's end B = (radius, -h) along
  ///   it) and the disk reaching below the base's plane.
  static LeafToDisk closedForm(const DiskInShape& disk, const fcl::Cone<S>& cone, double scale) {
    const ConeTarget cone_target = target(cone);
    const double h = cone_target.half_length, radius = cone_target.radius;
    const Vec3& c = disk.c;
    if (c.z() > h) return apexAgainstDisk(cone_target, disk, scale);
    const auto against_base = [&] {
      return diskAgainstFlatEnd(disk, cone_target, cone_target.flatEnds()[0], scale);
    };
    if (c.z() < -h) return against_base();
    const double centre_rho = std::sqrt(c.x() * c.x() + c.y() * c.y());
    const bool nearest_base_rim = (centre_rho - radius) * radius >= 2.0 * h * (c.z() + h);
    const double normal_tilt = Vec2(disk.u.z(), disk.v.z()).norm();  // |P_disk z|
    if (centre_rho > radius && nearest_base_rim && c.z() - disk.r * normal_tilt < -h) {
      return against_base();
    }
    return LeafToDisk{};
  }
  /// The apex case of closedForm; not exact where the disk's nearest point to
  /// the apex is not the cone's nearest, or within touching of it (overlaps
  /// are the generic solver's to decide).
  static LeafToDisk apexAgainstDisk(const ConeTarget& cone_target, const DiskInShape& disk,
                                    double scale) {
    const Vec3 apex(0.0, 0.0, cone_target.half_length);
    const Vec3 p = disk.point(disk.nearest(apex));
    const Vec3 away = p - apex;
    const double away_rho = std::sqrt(away.x() * away.x() + away.y() * away.y());
    if (!(cone_target.radius * away_rho <= 2.0 * cone_target.half_length * away.z())) {
      return LeafToDisk{};
    }
    const double upper = away.norm();
    if (!(upper > kShapeTouchingTolerance * scale)) return LeafToDisk{};
    const double lower = certificateAlong(cone_target, disk, 0.0, Vec3(-away));
    return certifiedOrBound(lower, upper, p, apex, scale);
  }
  /// The directions among which the shortest separating translation lies
  /// (shortestSeparation adds the disk's normals and both signs), so the contact's
  /// depth is the exact penetration depth. The cone's support at -w is the apex
  /// on one region of directions, the base on the other (kinked at its normal
  /// -z), and the side's generators on the circle between them: the apex's
  /// vertex candidates, the base's disk-disk candidates and the side's
  /// (addConeSideCandidates; docs/penetration_depth.md, section 7).
  template <typename Search>
  static void contactDirections(const ConeTarget& target, const DiskInShape& disk,
                                Search* directions) {
    directions->push_back(Vec3::UnitZ());
    addVertexCandidates(disk, Vec3(0.0, 0.0, target.half_length), directions);
    addFlatEndCandidates(disk, target.flatEnds()[0], directions);
    addConeSideCandidates(disk, target.radius, target.half_length, directions);
  }
};

}  // namespace

template <typename S>
struct DiskShapePair<fcl::Cone<S>> : GenericDiskShapePair<S, fcl::Cone<S>, ConeTraits<S>> {};

}  // namespace internal
}  // namespace fcl_disk

FCL_DISK_INSTANTIATE_DISK_SHAPE_PAIR(fcl::Cone)

// Disk - fcl::Cone: the apex (closed form), the slant side (Newton along the
// rim) or the base (the disk-disk solver) where their certificates close, else
// the generic solver with the cone's projection, computed in the meridian
// half-plane (a right triangle) and turned about the axis, and its support
// (apex or base rim). docs/disk_shape_distance.md, section 4. The contact's
// directions make its depth the exact penetration depth
// (docs/penetration_depth.md, section 7).
#include "../disk_shape_pair.h"
#include "feature_candidates.h"
#include "flat_end_pair.h"

#include <optional>
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

  /// Whether y lies in the solid cone: above the base, under the slant side
  /// A-B (written without a division so that degenerate cones, radius or
  /// height 0, stay exact).
  bool contains(const Vec3& y) const {
    const double h = half_length;
    const double rho = std::sqrt(y.x() * y.x() + y.y() * y.y());
    return y.z() >= -h && y.z() <= h && rho <= radius &&
           2.0 * h * rho + radius * (y.z() - h) <= 0.0;
  }

  Projection project(const Vec3& y) const {
    if (contains(y)) return Projection{y, FactoredHessian()};
    const double h = half_length;
    const double rho = std::sqrt(y.x() * y.x() + y.y() * y.y());
    const Vec2 m(rho, y.z());
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

  /// min over the cone of w.y: the apex's h w_z or the base rim's
  /// -radius |w_xy| - h w_z.
  double leastAlong(const Vec3& w_S) const {
    const double at_apex = half_length * w_S.z();
    return std::min(at_apex, -radius * std::sqrt(w_S.x() * w_S.x() + w_S.y() * w_S.y()) - at_apex);
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

/// The slant side's closed form (ConeTraits::sideAgainstDisk) takes at most
/// this many Newton steps along the rim, and has converged once a step is
/// below kSideAngleTolerance radians: Newton's error after a step s is then
/// about s^2 = 1e-10 rad (the rim's curvatures relative to the radius are of
/// order 1), whose cost to the distance and to the certificate along the pair
/// (second order in it, ~1e-20 of the scene) is far under the 1e-14 the
/// certificate must close to. On the report's 2,000 cone cases the side takes
/// 2,678 Newton steps, against 3,209 to 1e-9 rad, with the same answers.
constexpr int kMaxSideNewtonSteps = 8;
constexpr double kSideAngleTolerance = 1e-5;
/// Where Newton has no step (phi concave along the rim, or a turn beyond
/// kShapeMaxRimStep), the side's iteration turns this many radians down phi's
/// slope instead.
constexpr double kSideDescentTurn = 0.5;

/// Axis points, at these heights relative to the half length, whose nearest
/// disk points are tried for a common point of an overlapping disk and cone
/// that the apex, side and base cases leave (ConeTraits::commonPointNearAxis):
/// the centroid's height first (-1/2). On the report's 2,000 cone cases
/// (bench/disk_shape_cases.h) they settle 170 overlaps the three cases leave.
constexpr double kAxisProbeHeights[] = {-0.5, 0.0, -1.0, 0.5};

/// Where the disk's point least over the side's line has its foot, when not
/// on the side: past the apex or past the base's rim, whose own cases are
/// then the likely ones.
enum class SideEnd { none, apex, base };

/// The cone's features whose closed forms a query has tried.
struct ConeFeatures {
  bool apex = false, side = false, base = false;
};

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
  /// Three exact cases, each tried where the disk's centre says it is likely
  /// (docs/disk_shape_distance.md, section 4); what none settles goes to the
  /// generic solver. `disk`'s axes are orthonormal (solvedDiskInShape).
  /// - the apex, for a centre above it (apexAgainstDisk);
  /// - the slant side (sideAgainstDisk), for a centre above the apex where the
  ///   apex fails and for a centre beside the cone where the base is not
  ///   tried; a disk whose least point over the side's line has its foot past
  ///   the base's rim or the apex goes to that end's case;
  /// - the base, a disk (diskAgainstFlatEnd: exact where the certificate along
  ///   the disk-base pair closes; for a disk wholly beyond the base's plane
  ///   the pair's own, diskBeyondFlatEnd), for a centre beyond the base's plane, or
  ///   beside the cone with its nearest cone point at the base's rim (in the
  ///   meridian half-plane, past the slant side's end B = (radius, -h) along
  ///   it) and the disk reaching below the base's plane;
  /// - where that case is not exact, a common point (commonPointNearAxis):
  ///   most overlaps;
  /// - else the features the centre's choice did not try, side, base, apex:
  ///   the choice reads only the centre, and the nearest feature can be
  ///   another (on the report's 2,000 cone cases, 83 of the 96 the choice and
  ///   the common point leave).
  static LeafToDisk closedForm(const DiskInShape& disk, const fcl::Cone<S>& cone, double scale) {
    ConeFeatures tried;
    const LeafToDisk by_feature = nearestFeature(disk, cone, scale, &tried);
    if (by_feature.exact) return by_feature;
    const ConeTarget cone_target = target(cone);
    if (const auto common = commonPointNearAxis(cone_target, disk)) return meetingAt(*common);
    if (!tried.side) {
      SideEnd past = SideEnd::none;
      const LeafToDisk side = sideAgainstDisk(cone_target, disk, scale, &past);
      if (side.exact) return side;
    }
    if (!tried.base) {
      const LeafToDisk base = diskAgainstFlatEnd(disk, cone_target, cone_target.flatEnds()[0], scale);
      if (base.exact) return base;
    }
    if (!tried.apex) {
      const LeafToDisk apex = apexAgainstDisk(cone_target, disk, scale);
      if (apex.exact) return apex;
    }
    return by_feature;
  }
  /// The disk's point nearest one of the axis points at kAxisProbeHeights,
  /// when it lies in the solid cone: a common point.
  static std::optional<Vec3> commonPointNearAxis(const ConeTarget& cone_target,
                                                 const DiskInShape& disk) {
    for (const double height : kAxisProbeHeights) {
      const Vec3 x = disk.point(disk.nearest(Vec3(0.0, 0.0, height * cone_target.half_length)));
      if (cone_target.contains(x)) return x;
    }
    return std::nullopt;
  }
  /// The apex, the side or the base, as closedForm chooses; *tried says which
  /// it tried.
  static LeafToDisk nearestFeature(const DiskInShape& disk, const fcl::Cone<S>& cone,
                                   double scale, ConeFeatures* tried) {
    const ConeTarget cone_target = target(cone);
    const double h = cone_target.half_length, radius = cone_target.radius;
    const Vec3& c = disk.c;
    const auto against_apex = [&] {
      tried->apex = true;
      return apexAgainstDisk(cone_target, disk, scale);
    };
    const double normal_tilt = Vec2(disk.u.z(), disk.v.z()).norm();  // |P_disk z|
    // A disk wholly beyond the base's plane needs only the disk-base pair's own
    // certificate (diskBeyondFlatEnd).
    const auto against_base = [&] {
      tried->base = true;
      const FlatEnd base = cone_target.flatEnds()[0];
      return c.z() + disk.r * normal_tilt < -h ? diskBeyondFlatEnd(disk, base, scale)
                                                : diskAgainstFlatEnd(disk, cone_target, base, scale);
    };
    // The side, else the end its least point lies past.
    const auto against_side = [&] {
      tried->side = true;
      SideEnd past = SideEnd::none;
      const LeafToDisk side = sideAgainstDisk(cone_target, disk, scale, &past);
      if (past == SideEnd::base) return against_base();
      if (past == SideEnd::apex && !tried->apex) return against_apex();
      return side;
    };
    if (c.z() > h) {
      const LeafToDisk apex = against_apex();
      return apex.exact ? apex : against_side();
    }
    if (c.z() < -h) return against_base();
    const double centre_rho = std::sqrt(c.x() * c.x() + c.y() * c.y());
    const bool nearest_base_rim = (centre_rho - radius) * radius >= 2.0 * h * (c.z() + h);
    if (centre_rho > radius && nearest_base_rim && c.z() - disk.r * normal_tilt < -h) {
      return against_base();
    }
    return against_side();
  }
  /// The apex case of closedForm: the disk's point p nearest the apex
  /// (closed form) is optimal when p - apex lies in the cone's normal cone at
  /// the apex, radius |(p - apex)_xy| <= 2 half_length (p - apex)_z (the apex
  /// is then p's nearest cone point: the KKT conditions of the convex pair);
  /// the certificate along the pair proves it. Not exact where that fails, or
  /// within touching (overlaps are the generic solver's to decide).
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
  /// The slant side case of closedForm. The solid cone lies in {s <= 0}, s(x) =
  /// (2h rho(x) + R (z(x) - h)) / L the signed distance of x's meridian point
  /// (rho, z) to the side's line (L = |(2h, R)|, rho the distance from the
  /// axis), and s is convex and 1-Lipschitz, so dist(x, cone) >= s(x) for every
  /// x: where the disk's point p minimising s has its meridian foot on the side
  /// (between the apex and the base's rim) at s(p) > 0, that foot is p's nearest
  /// cone point and (p, foot) the nearest pair. p is sought on the rim (s's
  /// level sets are cones with apices on the axis, so in a plane s is
  /// stationary off the axis only along a line on which it is constant: over
  /// the disk it is least on the rim, or where the disk meets the axis, which
  /// is left to the generic solver) by Newton in the rim angle on
  /// phi(theta) = 2h rho + R z, from the rim point down phi's gradient at the
  /// centre (a turn of kSideDescentTurn down the slope where Newton has no
  /// step); the certificate along the pair proves it. Not exact (the generic
  /// solver then answers) where an iterate reaches the side's line, stops at
  /// a maximum along the rim or does not converge within kMaxSideNewtonSteps,
  /// or its foot is off the side (*past says which end).
  static LeafToDisk sideAgainstDisk(const ConeTarget& cone_target, const DiskInShape& disk,
                                    double scale, SideEnd* past) {
    const double h = cone_target.half_length, radius = cone_target.radius;
    const double height = 2.0 * h, slant = Vec2(height, radius).norm();
    const double r = disk.r;
    // The rim point x(theta) = c + r (cos u + sin v): its horizontal part w
    // and its height z are affine in (cos, sin).
    const Vec2 c_xy(disk.c.x(), disk.c.y()), u_xy(disk.u.x(), disk.u.y()),
        v_xy(disk.v.x(), disk.v.y());
    const Vec2 axes_z(disk.u.z(), disk.v.z());
    const double c_rho = c_xy.norm();
    if (!(c_rho > 0.0 && slant > 0.0)) return LeafToDisk{};
    const Vec2 descent =
        -(height / c_rho) * Vec2(u_xy.dot(c_xy), v_xy.dot(c_xy)) - radius * axes_z;
    const double descent_length = descent.norm();
    if (!(descent_length > 0.0)) return LeafToDisk{};
    Vec2 radial = descent / descent_length;
    bool converged = false;
    for (int step = 0; step < kMaxSideNewtonSteps && !converged; ++step) {
      // phi' = 2h rho' + R z', phi'' = 2h rho'' + R z'', with w' along the
      // tangent and w'' = -(w - c_xy), z'' = -(z - c_z).
      const Vec2 tangent(-radial.y(), radial.x());
      const Vec2 from_centre = r * (radial.x() * u_xy + radial.y() * v_xy);
      const Vec2 w = c_xy + from_centre;
      const Vec2 w_turn = r * (tangent.x() * u_xy + tangent.y() * v_xy);
      const double rho_squared = w.squaredNorm();
      if (!(rho_squared > 0.0)) return LeafToDisk{};
      // 1 / rho as sqrt(rho^2) (1 / rho^2): the two run side by side.
      const double inverse_rho_squared = 1.0 / rho_squared;
      const double inverse_rho = std::sqrt(rho_squared) * inverse_rho_squared;
      const double rho = rho_squared * inverse_rho;
      const double z_offset = r * radial.dot(axes_z);  // z - c_z
      // An iterate at or below the side's line: s is least below it, so the
      // side is not the nearest feature (an overlap, or the base's rim).
      if (!(height * rho + radius * (disk.c.z() + z_offset - h) >
            kShapeTouchingTolerance * scale * slant)) {
        return LeafToDisk{};
      }
      // slope = phi', curvature = phi'' (lengths).
      const double w_w_turn = w.dot(w_turn);
      const double slope = height * w_w_turn * inverse_rho + radius * r * tangent.dot(axes_z);
      const double rho_curvature = w_turn.squaredNorm() - w.dot(from_centre) -
                                   w_w_turn * w_w_turn * inverse_rho_squared;  // rho rho''
      const double curvature = height * inverse_rho * rho_curvature - radius * z_offset;
      // Where phi is concave along the rim or Newton's turn would exceed
      // kShapeMaxRimStep, a turn of kSideDescentTurn down the slope instead
      // (the curvature that makes Newton's turn that long).
      double turn_curvature = curvature;
      if (!(curvature > 0.0 && std::abs(slope) <= kShapeMaxRimStep * curvature)) {
        if (!(std::abs(slope) > 0.0)) return LeafToDisk{};  // a maximum along the rim
        turn_curvature = std::abs(slope) / kSideDescentTurn;
      }
      // The turn by dtheta = -slope / turn_curvature as the Cayley rotation
      // over one denominator (as the disk-disk rim iteration): one division.
      const double four_curvature_squared = 4.0 * turn_curvature * turn_curvature;
      const double inverse = 1.0 / (four_curvature_squared + slope * slope);
      const double cos = (four_curvature_squared - slope * slope) * inverse;
      const double sin = -4.0 * slope * turn_curvature * inverse;
      radial = cos * radial + sin * tangent;
      converged = std::abs(slope) <= kSideAngleTolerance * curvature;
    }
    if (!converged) return LeafToDisk{};
    const Vec3 p = disk.point(r * radial);
    const double rho = std::sqrt(p.x() * p.x() + p.y() * p.y());
    const double along = (radius * rho - height * (p.z() - h)) / slant;  // from the apex
    const double side_distance = (height * rho + radius * (p.z() - h)) / slant;
    if (!(rho > 0.0 && side_distance > kShapeTouchingTolerance * scale)) return LeafToDisk{};
    if (!(along >= 0.0 && along <= slant)) {
      *past = along < 0.0 ? SideEnd::apex : SideEnd::base;
      return LeafToDisk{};
    }
    // The foot: (rho, z) moved by side_distance along the side's outward
    // normal (2h, R) / L, turned back about the axis.
    const double along_normal = side_distance / slant;
    const double shrink = 1.0 - along_normal * height / rho;
    const Vec3 q(shrink * p.x(), shrink * p.y(), p.z() - along_normal * radius);
    const double lower = certificateAlong(cone_target, disk, 0.0, Vec3(q - p));
    return certifiedOrBound(lower, (q - p).norm(), p, q, scale);
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

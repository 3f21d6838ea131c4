// Intersecting disk pairs for fcl_disk_report's penetration section: families
// of configurations where the penetration depth PD (the length of the shortest
// translation that separates the disks) is interesting, each generated with a
// fixed seed and kept only if fcl_disk::intersectDisks() says the stored (double)
// poses share a point.
//
// Every pair is built in a "family frame": disk 1 centred at the origin with
// normal +z (spun about it at random); then a random common rigid motion (a
// uniform rotation Q and a translation t, |t| <= 2, or exactly 1e5 for
// far_from_origin) is applied so that nothing is axis-aligned by accident, and
// the poses are rounded once to double. Radii: r1 uniform in [0.3, 1.5] and
// r2 = r1 times a log-uniform ratio in [0.5, 2] unless a family says otherwise.
//
// Families (most pairs are built around the line L = {y = b, z = 0} of disk 1's
// plane, which disk 2's plane contains; onCommonLine() below):
//   chain_links          interlocked links: disk 2's chord on L straddles disk 1's
//                        rim and disk 1's chord straddles disk 2's, so each disk
//                        passes through the other's interior; disk 2 perpendicular
//                        to disk 1 (every 4th pair) or tilted by up to 1.2 rad.
//   through_interior     disk 2's chord on L lies inside disk 1's chord: disk 2
//                        passes through a slot in disk 1's interior.
//   rim_through_face     as through_interior, but only a cap of disk 2 of height
//                        1e-4..0.2 r2 (log-uniform) is through disk 1's face.
//   coplanar_overlap     same plane (normals equal or opposite), centres
//                        0..0.98 (r1 + r2) apart (every 5th concentric): PD = 0.
//   coaxial_centred      same centre, disk 2 tilted by theta (log-uniform
//                        1e-6..pi/2, every 7th exactly pi/2):
//                        PD = min(r1, r2) sin(theta).
//   nearly_touching      a touching pair pushed into each other by a depth of
//                        1e-9..1e-3 of the scene (log-uniform): "face" (disk 2's
//                        lowest rim point that deep below disk 1's face, over its
//                        interior: PD = depth) and "rim_rim" (rim 1 and rim 2
//                        touching at a point with a common separating direction
//                        w, then moved by depth along w: PD <= depth).
//   far_from_origin      random_intersecting pairs translated by exactly 1e5 in a
//                        random direction.
//   random_intersecting  a random point x of disk 1, disk 2 with a random
//                        orientation placed through x at a random point of its own.
//
// Random numbers: fcl_disk_test::Random (test/test_random.h), so a
// (family, count, seed) triple gives the same pairs with every standard library.
#pragma once

#include <fcl/common/types.h>
#include <fcl_disk/disk_intersection.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "test_random.h"

namespace fcl_disk_penetration_cases {

enum class PenFamily {
  chain_links,
  through_interior,
  rim_through_face,
  coplanar_overlap,
  coaxial_centred,
  nearly_touching,
  far_from_origin,
  random_intersecting,
};

inline const std::vector<PenFamily>& allPenFamilies() {
  static const std::vector<PenFamily> families{
      PenFamily::chain_links,      PenFamily::through_interior, PenFamily::rim_through_face,
      PenFamily::coplanar_overlap, PenFamily::coaxial_centred,  PenFamily::nearly_touching,
      PenFamily::far_from_origin,  PenFamily::random_intersecting};
  return families;
}

inline const char* penFamilyName(PenFamily f) {
  switch (f) {
    case PenFamily::chain_links: return "chain_links";
    case PenFamily::through_interior: return "through_interior";
    case PenFamily::rim_through_face: return "rim_through_face";
    case PenFamily::coplanar_overlap: return "coplanar_overlap";
    case PenFamily::coaxial_centred: return "coaxial_centred";
    case PenFamily::nearly_touching: return "nearly_touching";
    case PenFamily::far_from_origin: return "far_from_origin";
    case PenFamily::random_intersecting: return "random_intersecting";
  }
  return "?";
}

/// One stored pair (double poses, disk i in its local XY plane, normal +z).
struct PenCase {
  std::string name;  ///< "family/kind/index"
  double r1 = 1, r2 = 1;
  fcl::Transform3d X_W1 = fcl::Transform3d::Identity();
  fcl::Transform3d X_W2 = fcl::Transform3d::Identity();
  /// PD of the construction before rounding the poses (NaN when the family
  /// has no closed form; an upper bound for nearly_touching/rim_rim is not stored).
  double known_pd = std::numeric_limits<double>::quiet_NaN();
  double scale = 1;  ///< r1 + r2 + |c1 - c2| of the stored poses
};

namespace detail {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Random = fcl_disk_test::Random;

// ---- construction parameters (the reasons are in the file comment) --------

constexpr double kMinRadius1 = 0.3, kMaxRadius1 = 1.5;
/// r2 / r1, log-uniform: neither disk more than twice the other.
constexpr double kMinRadiusRatio = 0.5, kMaxRadiusRatio = 2.0;
/// |t| of the common motion, so the pairs are not all around the origin.
constexpr double kCommonTranslation = 2.0;
/// far_from_origin: the common translation, where ulp(|c|) ~ 1.5e-11.
constexpr double kFarTranslation = 1e5;
/// L's offset from disk 1's centre, as a fraction of r1: keeps disk 1's chord on
/// L at least ~0.7 r1 long, so chords fit with room to place disk 2.
constexpr double kMaxLineOffset = 0.7;
/// Tilt of disk 2's plane from perpendicular to disk 1's (radians): below ~1.3,
/// so the pairs are clearly not coplanar (that has a family of its own).
constexpr double kMaxTilt = 1.2;
/// Every kPerpendicularEvery-th chain link is exactly perpendicular (a symmetric
/// pair: ties between minima).
constexpr int kPerpendicularEvery = 4;
/// chain_links: where disk 2's chord centre sits relative to disk 1's rim, as a
/// fraction of disk 2's half chord (|.| < 1 straddles the rim).
constexpr double kMaxStraddle = 0.8;
/// through_interior: disk 2's half chord, as a fraction of min(r2, s1).
constexpr double kMinSlot = 0.1, kMaxSlot = 0.9;
/// Where a chord inside disk 1's sits, as a fraction of the room left (< 1: it
/// never touches disk 1's rim).
constexpr double kMaxSlotShift = 0.9;
/// rim_through_face: the cap of disk 2 below disk 1's plane, as a fraction of r2.
constexpr double kMinCap = 1e-4, kMaxCap = 0.2;
/// coplanar_overlap: centre gap as a fraction of r1 + r2 (< 1: overlapping).
constexpr double kMaxCoplanarGap = 0.98;
constexpr int kConcentricEvery = 5;
/// coaxial_centred: tilt range (radians), and every kRightAngleEvery-th pair at pi/2.
constexpr double kMinCoaxialTilt = 1e-6;
constexpr int kRightAngleEvery = 7;
/// nearly_touching: the depth, as a fraction of the scene r1 + r2 + |c1 - c2|.
constexpr double kMinNearDepth = 1e-9, kMaxNearDepth = 1e-3;
/// nearly_touching/face: disk 2 at least this far (radians) from parallel to disk 1,
/// so its lowest point is a single rim point; the foot within this fraction of r1
/// from disk 1's centre, so the contact is on the face, not the rim.
constexpr double kMinFaceTilt = 0.05, kMaxFootRadius = 0.9;
/// nearly_touching/rim_rim: the separating direction w makes at most this angle
/// (radians) with disk 1's plane, and disk 2's plane is at least this far from
/// normal to w (|P2 w| >= kMinInPlane), so its support along -w is one rim point.
constexpr double kMaxRimElevation = 1.3, kMinInPlane = 0.1;
/// Attempts per requested pair before a family gives up (pairs that the
/// stored poses do not make intersecting, and redraws, are rare).
constexpr int kAttemptsPerPair = 20;

inline Mat3 rotZ(double angle) {
  return Eigen::AngleAxisd(angle, Vec3::UnitZ()).toRotationMatrix();
}

/// A rotation whose third column is the unit vector n, spun at random about n.
inline Mat3 frameWithNormal(const Vec3& n, Random& rng) {
  const Vec3 helper = std::fabs(n.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY();
  Mat3 m;
  m.col(0) = (helper - n.dot(helper) * n).normalized();
  m.col(1) = n.cross(m.col(0));
  m.col(2) = n;
  return m * rotZ(rng.uniform(0, 2 * M_PI));
}

/// A pair in the family frame (disk 1 at the origin, normal +z).
struct Local {
  double r1 = 1, r2 = 1;
  Mat3 R1 = Mat3::Identity(), R2 = Mat3::Identity();
  Vec3 c1 = Vec3::Zero(), c2 = Vec3::Zero();
  double known_pd = std::numeric_limits<double>::quiet_NaN();
  std::string kind = "generic";
  bool valid = true;  ///< false: the draw failed a constraint, draw again
};

inline void drawRadii(Local* l, Random& rng) {
  l->r1 = rng.uniform(kMinRadius1, kMaxRadius1);
  l->r2 = l->r1 * rng.logUniform(kMinRadiusRatio, kMaxRadiusRatio);
}

/// Disk 2's plane contains L = {y = b, z = 0}, tilted by chi from perpendicular
/// to disk 1; its centre is `offset` from L within its plane, so its chord on L
/// has half-length sqrt(r2^2 - offset^2), centred at x = x2.
inline void onCommonLine(Local* l, double b, double chi, double offset, double x2) {
  const Vec3 n2(0, std::cos(chi), std::sin(chi));
  const Vec3 across = n2.cross(Vec3::UnitX());  // in plane 2, perpendicular to L
  l->R2.col(0) = Vec3::UnitX();
  l->R2.col(1) = across;
  l->R2.col(2) = n2;
  l->c2 = Vec3(x2, b, 0) + offset * across;
}

inline Vec3 pointInDisk(double r, Random& rng) {
  const double rho = r * std::sqrt(rng.uniform01()), phi = rng.uniform(0, 2 * M_PI);
  return Vec3(rho * std::cos(phi), rho * std::sin(phi), 0);
}

inline Local randomIntersecting(Random& rng) {
  Local l;
  drawRadii(&l, rng);
  const Vec3 x = pointInDisk(l.r1, rng);
  l.R2 = rng.rotation();
  l.c2 = x - l.R2 * pointInDisk(l.r2, rng);
  l.kind = "random";
  return l;
}

inline Local makeLocal(PenFamily family, int index, Random& rng) {
  Local l;
  switch (family) {
    case PenFamily::chain_links: {
      drawRadii(&l, rng);
      const double b = l.r1 * rng.uniform(-kMaxLineOffset, kMaxLineOffset);
      const double s1 = std::sqrt(l.r1 * l.r1 - b * b);
      const double offset = l.r2 * rng.uniform(-kMaxLineOffset, kMaxLineOffset);
      const double s2 = std::sqrt(l.r2 * l.r2 - offset * offset);
      const double x2 = s1 + rng.uniform(-kMaxStraddle, kMaxStraddle) * s2;
      // Disk 2's chord [x2 - s2, x2 + s2] contains disk 1's rim point s1; for a
      // link it must not also contain the other one, -s1.
      l.valid = x2 - s2 > -s1;
      const bool perpendicular = index % kPerpendicularEvery == 0;
      onCommonLine(&l, b, perpendicular ? 0.0 : rng.uniform(-kMaxTilt, kMaxTilt), offset, x2);
      l.kind = perpendicular ? "perpendicular" : "tilted";
      return l;
    }
    case PenFamily::through_interior:
    case PenFamily::rim_through_face: {
      drawRadii(&l, rng);
      const double b = l.r1 * rng.uniform(-kMaxLineOffset, kMaxLineOffset);
      const double s1 = std::sqrt(l.r1 * l.r1 - b * b);
      const double side = rng.chance(0.5) ? 1 : -1;
      double s2, offset;
      if (family == PenFamily::through_interior) {
        s2 = std::min(l.r2, s1) * rng.uniform(kMinSlot, kMaxSlot);
        offset = side * std::sqrt(l.r2 * l.r2 - s2 * s2);
        l.kind = "through";
      } else {
        offset = side * l.r2 * (1 - rng.logUniform(kMinCap, kMaxCap));
        s2 = std::sqrt(l.r2 * l.r2 - offset * offset);
        l.valid = s2 < s1;  // the cap's chord must fit inside disk 1's
        l.kind = "cap";
      }
      onCommonLine(&l, b, rng.uniform(-kMaxTilt, kMaxTilt), offset,
                   (s1 - s2) * rng.uniform(-kMaxSlotShift, kMaxSlotShift));
      return l;
    }
    case PenFamily::coplanar_overlap: {
      drawRadii(&l, rng);
      l.R2 = rotZ(rng.uniform(0, 2 * M_PI));
      // Half the pairs face each other (opposite normals): the same disk set.
      if (rng.chance(0.5)) l.R2 = l.R2 * Eigen::Vector3d(1, -1, -1).asDiagonal();
      const bool concentric = index % kConcentricEvery == 0;
      const double gap = concentric ? 0.0 : rng.uniform(0, kMaxCoplanarGap) * (l.r1 + l.r2);
      const double beta = rng.uniform(0, 2 * M_PI);
      l.c2 = gap * Vec3(std::cos(beta), std::sin(beta), 0);
      l.known_pd = 0;
      l.kind = concentric ? "concentric" : "overlap";
      return l;
    }
    case PenFamily::coaxial_centred: {
      drawRadii(&l, rng);
      const double theta =
          index % kRightAngleEvery == 0 ? M_PI / 2 : rng.logUniform(kMinCoaxialTilt, M_PI / 2);
      l.R2 = frameWithNormal(Vec3(std::sin(theta), 0, std::cos(theta)), rng);
      l.known_pd = std::min(l.r1, l.r2) * std::sin(theta);
      l.kind = "tilt";
      return l;
    }
    case PenFamily::nearly_touching: {
      drawRadii(&l, rng);
      const double depth_fraction = rng.logUniform(kMinNearDepth, kMaxNearDepth);
      if (index % 2 == 0) {
        // Disk 2's lowest rim point on disk 1's face (touching), then `depth`
        // lower: pushing disk 2 up by depth separates them, and +z is a strict
        // minimum of F at this kink, so PD = depth.
        Mat3 R2;
        do {
          R2 = rng.rotation();
        } while (std::hypot(R2(2, 0), R2(2, 1)) < std::sin(kMinFaceTilt));
        // Disk 2's in-plane direction of steepest ascent (P2 z, normalised).
        const Vec3 up = (R2.col(0) * R2(2, 0) + R2.col(1) * R2(2, 1)).normalized();
        const Vec3 foot = pointInDisk(kMaxFootRadius * l.r1, rng);
        l.R2 = R2;
        l.c2 = foot + l.r2 * up;
        const double depth = depth_fraction * (l.r1 + l.r2 + l.c2.norm());
        l.c2.z() -= depth;
        l.known_pd = depth;
        l.kind = "face";
      } else {
        // Rim 1 at p and rim 2 touch, w (in disk 1's normal cone at p, pointing
        // out of disk 1) separates them: disk 2's support along -w is p. Moving
        // disk 2 by -depth w gives F(w) = depth, so PD <= depth.
        const double a = rng.uniform(0, 2 * M_PI);
        const double elevation = rng.uniform(-kMaxRimElevation, kMaxRimElevation);
        const Vec3 radial(std::cos(a), std::sin(a), 0);
        const Vec3 w = std::cos(elevation) * radial + std::sin(elevation) * Vec3::UnitZ();
        Mat3 R2;
        Vec3 in_plane;  // P2 w
        do {
          R2 = rng.rotation();
          in_plane = R2.col(0) * R2.col(0).dot(w) + R2.col(1) * R2.col(1).dot(w);
        } while (in_plane.norm() < kMinInPlane);
        l.R2 = R2;
        const Vec3 p = l.r1 * radial;
        l.c2 = p + l.r2 * in_plane.normalized();
        const double depth = depth_fraction * (l.r1 + l.r2 + l.c2.norm());
        l.c2 -= depth * w;
        l.kind = "rim_rim";
      }
      return l;
    }
    case PenFamily::far_from_origin:
    case PenFamily::random_intersecting:
      return randomIntersecting(rng);
  }
  return l;
}

/// A per-family stream, so that adding a family does not change the others.
inline std::uint64_t familySeed(std::uint64_t seed, PenFamily family) {
  constexpr std::uint64_t kGolden = 0x9E3779B97F4A7C15ULL;  // splitmix64's increment
  return (seed + 0x5045ULL /* "PE" */) * kGolden + static_cast<std::uint64_t>(family) * kGolden;
}

}  // namespace detail

/// `count` intersecting pairs of `family` (fewer only if kAttemptsPerPair * count
/// draws did not yield them; the caller reports the number it got).
inline std::vector<PenCase> makePenFamily(PenFamily family, std::size_t count,
                                          std::uint64_t seed) {
  using namespace detail;
  Random rng(familySeed(seed, family));
  std::vector<PenCase> cases;
  cases.reserve(count);
  const std::size_t max_attempts = kAttemptsPerPair * count + 100;
  for (std::size_t attempt = 0; attempt < max_attempts && cases.size() < count; ++attempt) {
    const int index = static_cast<int>(cases.size());
    Local l = makeLocal(family, index, rng);
    l.R1 = rotZ(rng.uniform(0, 2 * M_PI));  // spin disk 1 about its normal
    const Mat3 Q = rng.rotation();
    const Vec3 t = family == PenFamily::far_from_origin ? Vec3(kFarTranslation * rng.unitVector())
                                                        : rng.inBall(kCommonTranslation);
    if (!l.valid) continue;
    PenCase c;
    c.name = std::string(penFamilyName(family)) + "/" + l.kind + "/" + std::to_string(index);
    c.r1 = l.r1;
    c.r2 = l.r2;
    c.X_W1.linear() = Q * l.R1;
    c.X_W1.translation() = Q * l.c1 + t;
    c.X_W2.linear() = Q * l.R2;
    c.X_W2.translation() = Q * l.c2 + t;
    c.known_pd = l.known_pd;
    c.scale = c.r1 + c.r2 + (c.X_W1.translation() - c.X_W2.translation()).norm();
    if (!fcl_disk::intersectDisks(c.r1, c.X_W1, c.r2, c.X_W2)) continue;
    cases.push_back(std::move(c));
  }
  return cases;
}

}  // namespace fcl_disk_penetration_cases

// Penetration depth and signed distance of two disks (disk_penetration.h),
// against the independent long-double reference of reference_penetration.h, on
// families of intersecting poses, in double and float; properties (separation by
// translation, judged by the library's exact distance; symmetry; rigid motion;
// continuity through contact); the same answers through fcl::distance and
// fcl::collide; invalid input. The reference itself is checked first, against
// hand-derived closed forms, against reference_distance.h on separated pairs and
// against a denser run of itself.
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>
#include <fcl_disk/disk.h>
#include <fcl_disk/disk_intersection.h>
#include <fcl_disk/disk_penetration.h>
#include <fcl_disk/exact_distance.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "reference_distance.h"
#include "reference_penetration.h"
#include "test_random.h"

namespace {

namespace ref = fcl_disk_penetration_reference;
using ref::PenDisk;
using ref::PenReference;
using ref::Real;
using ref::Vector3R;

// ---- tolerances -------------------------------------------------------------
// Relative ones multiply a length: `scale` = r1 + r2 + |c1 - c2| (the length of
// disk_penetration.h's guarantee) in double; in float max(scale, |c1|, |c2|)
// (float poses are stored to ulp(|c_i|), which no solver can beat).

template <typename S>
struct Tol {
  static constexpr bool kFloat = std::is_same<S, float>::value;
  static constexpr double kEps = std::numeric_limits<S>::epsilon();

  /// |PD - PD_ref|, relative. double: disk_penetration.h's guarantee, 1e-12
  /// (measured <= 7.5e-16 where the solver is right). float: the solver promotes
  /// to double and rounds PD to float (1/2 ulp), and a float rotation is
  /// orthonormal only to ~1.5 eps_f, so the disk itself is defined only to
  /// ~3 eps_f r per disk: 8 float ulps (measured <= 0.43 ulps where it is right).
  static constexpr double kPdRelative = kFloat ? 8 * kEps : 1e-12;

  /// Storing a world point rounds each coordinate by 1/2 ulp of its magnitude
  /// (<= max|c_i| + r1 + r2), computing it as c + R x about as much again: the
  /// points' checks add this many eps times that magnitude (as
  /// test_reference_accuracy.cpp does).
  static constexpr double kWorldRoundingEps = 4;

  /// | |direction| - 1 |: normalised in double, then (float) rounded per
  /// coordinate: 32 ulps of S as test_tolerances.h's kUnitNormal.
  static constexpr double kUnitDirection = 32 * kEps;

  /// F_ref(direction) may exceed PD_ref by the PD budget plus what rounding the
  /// direction to S costs: F is Lipschitz with constant <= scale on the sphere
  /// and each coordinate moves by <= eps/2, so 2 eps of the length.
  static constexpr double kDirectionValueExtraEps = 2;

  /// Angle between two directions that are the same up to storing each in S:
  /// sqrt(3)/2 eps per direction, so < 2 eps for the pair; 4 eps.
  static constexpr double kDirectionRoundingEps = 4;

  /// Extra translation past / short of PD in the separation check, relative to
  /// scale. double: the brief's 1e-9, 1000x the PD budget and 1e4x
  /// intersectDisks' touching band (1e-13), so the decision cannot be rounding.
  /// float: PD and direction are known only to ~8 float ulps, so 64 ulps (8x).
  static constexpr double kSeparationMargin = kFloat ? 64 * kEps : 1e-9;

  /// A common rigid motion stored in S moves each centre by ~ulp(|c|) and each
  /// rotation entry by ~eps/2; F is 1-Lipschitz in such moves, so 8 eps of the
  /// world magnitude (max |c| + r1 + r2, before and after the motion) bound the
  /// change.
  static constexpr double kPoseRoundingEps = 8;

  /// intersectDisks' touching band (disk_intersection.h: 1e-13 * scale) with
  /// the same 10x spare as test_tolerances.h's kIntersectionBandRelative; float
  /// inputs: 64 ulps. A contact position is "on both disks" to this.
  static constexpr double kTouchingRelative = kFloat ? 64 * kEps : 1e-11;
};

/// The reference's own accuracy, relative to scale: F in long double carries
/// ~1e-18 * scale; 1e-16 leaves 100x for the search's stopping rule and is
/// still four orders below the 1e-12 the solver is held to. Used wherever the
/// reference is judged (closed forms, denser runs, the solver beating it).
constexpr double kReferenceRelative = 1e-16;

/// Hand cases: at a kink minimiser the reference returns the normal itself, up
/// to long-double rounding of n = u x v / |u x v| (~1e-19); 1e-15 rad leaves
/// 10^4 spare and is far below any wrong minimiser (>= 1e-3 rad away here).
constexpr double kReferenceKinkAngle = 1e-15;
/// Hand cases: a minimiser "on" an axis or arc: at a smooth or flat minimum F
/// is quadratic in the angle, so a value good to ~1e-18 pins the direction only
/// to ~1e-9 rad; 1e-8 rad. The wrong answers are >= 0.1 rad away.
constexpr double kReferenceFlatAngle = 1e-8;
/// Hand cases: tied minimisers have equal values up to long-double rounding of
/// F (~1e-18 at unit scale); 1e-15 (absolute, unit-scale cases). Rivals in these
/// cases are at least pi/2 apart; any angle above 0.1 rad counts.
constexpr long double kHandTieValue = 1e-15L;
constexpr long double kHandTieAngle = 0.1L;
/// Hand cases: the next minimum of the small-disk case is 0.15 (at -z), so no
/// other minimiser comes within 1e-3 of PD = 0.05; distinct means > 1e-6 rad.
constexpr long double kHandNoRivalValue = 1e-3L;
constexpr long double kHandNoRivalAngle = 1e-6L;
/// The symmetric chain link is probed by translations of 1 +- this (absolute;
/// unit scene): 1e4x exactDiskDistance's 1e-12 * scale, so its verdict is sure.
constexpr double kHandTranslationMargin = 1e-9;

/// exactDiskDistance's guarantee (exact_distance.h), relative to scale: the
/// separation checks use it as the judge, so its error enters their bounds.
constexpr double kExactDistanceRelative = 1e-12;

/// A direction with F_ref below PD_ref by more than this (relative) means the
/// reference missed a minimum.
constexpr double kReferenceBeatenRelative = kReferenceRelative;

/// Two minimisers count as rivals (a tie: the direction is not unique to the
/// solver's tolerance) when their values are within 2x the level the solver's
/// directions are held to and they lie outside each other's sublevel set.
constexpr double kRivalLevelFactor = 2;

// ---- case counts --------------------------------------------------------------

/// Per family. The reference costs ~1 ms per pair (20000 double evaluations
/// plus long-double refinement), the sublevel radius ~0.3 ms: these keep the
/// file to a few seconds in Release.
constexpr int kDoubleCases = 300;
constexpr int kFloatCases = 200;
/// Per family for signedDiskDistance and the FCL entry points.
constexpr int kSignedCases = 60;
constexpr int kFclCases = 40;
/// Paths through contact for the continuity check, and steps per path.
constexpr int kContinuityPaths = 16;
constexpr int kContinuitySteps = 160;
/// Reference evaluated on every this-many-th step of a path.
constexpr int kContinuityReferenceEvery = 8;
constexpr std::uint64_t kSeed = 20250301;
/// Failing cases printed per check (all are counted).
constexpr int kMaxReportedFailures = 6;

// ---- cases --------------------------------------------------------------------

enum class PenFamily {
  chain_links,          ///< each disk through the other's rim; ratio 0.3..3, tilts
  through_interior,     ///< disk 2's chord on the planes' line inside disk 1's chord
  rim_through_face,     ///< disk 2 dips 1e-4..0.2 of its radius through disk 1's face
  coplanar_overlap,     ///< same plane, overlapping: PD = 0
  coaxial_centred,      ///< same centre, tilt theta: PD = min(r1, r2) sin(theta)
  nearly_touching,      ///< a dip of 1e-12..1e-3 of scale (face: PD = dip; rim-rim)
  far_from_origin,      ///< random intersecting, translated 1e3..1e6 (float 1e1..1e3)
  scales,               ///< random intersecting, all lengths times 1e-6..1e6
  random_intersecting,  ///< a random common point, random orientations
};

const PenFamily kFamilies[] = {
    PenFamily::chain_links,      PenFamily::through_interior, PenFamily::rim_through_face,
    PenFamily::coplanar_overlap, PenFamily::coaxial_centred,  PenFamily::nearly_touching,
    PenFamily::far_from_origin,  PenFamily::scales,           PenFamily::random_intersecting};

const char* familyName(PenFamily f) {
  switch (f) {
    case PenFamily::chain_links:
      return "chain_links";
    case PenFamily::through_interior:
      return "through_interior";
    case PenFamily::rim_through_face:
      return "rim_through_face";
    case PenFamily::coplanar_overlap:
      return "coplanar_overlap";
    case PenFamily::coaxial_centred:
      return "coaxial_centred";
    case PenFamily::nearly_touching:
      return "nearly_touching";
    case PenFamily::far_from_origin:
      return "far_from_origin";
    case PenFamily::scales:
      return "scales";
    case PenFamily::random_intersecting:
      return "random_intersecting";
  }
  return "?";
}

template <typename S>
struct PenCase {
  std::string name;
  S r1{1}, r2{1};
  fcl::Transform3<S> X1{fcl::Transform3<S>::Identity()};
  fcl::Transform3<S> X2{fcl::Transform3<S>::Identity()};
  /// PD of the construction before rounding the poses to S, or NaN.
  double known_pd{std::numeric_limits<double>::quiet_NaN()};
};

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

Mat3 rotZ(double a) { return Eigen::AngleAxisd(a, Vec3::UnitZ()).toRotationMatrix(); }

/// A rotation with third column n (unit) and a random spin about it.
Mat3 frameWithNormal(const Vec3& n, fcl_disk_test::Random& rng) {
  const Vec3 helper = std::fabs(n.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 u = (helper - n.dot(helper) * n).normalized();
  Mat3 m;
  m.col(0) = u;
  m.col(1) = n.cross(u);
  m.col(2) = n;
  return m * rotZ(rng.uniform(0, 2 * M_PI));
}

/// The family-frame description: disk 1 at the origin with normal +z (spun).
struct Local {
  double r1 = 1, r2 = 1;
  Mat3 R1 = Mat3::Identity(), R2 = Mat3::Identity();
  Vec3 c1 = Vec3::Zero(), c2 = Vec3::Zero();
  double known = std::numeric_limits<double>::quiet_NaN();
  std::string kind = "generic";
};

/// Disk 2's plane contains the line L = {y = b, z = 0} of disk 1's plane, at angle
/// chi from the vertical; its centre is `delta` from L in its plane and its chord
/// on L is centred at x2.
Local onCommonLine(double r1, double r2, double b, double chi, double delta, double x2) {
  Local l;
  l.r1 = r1;
  l.r2 = r2;
  const Vec3 n2(0, std::cos(chi), std::sin(chi));
  const Vec3 across = n2.cross(Vec3::UnitX());  // in plane 2, perpendicular to L
  l.R2.col(0) = Vec3::UnitX();
  l.R2.col(1) = across;
  l.R2.col(2) = n2;
  l.c2 = Vec3(x2, b, 0) + delta * across;
  return l;
}

/// A random point of the disk of radius r in the local XY plane.
Vec3 pointInDisk(double r, fcl_disk_test::Random& rng) {
  const double rho = r * std::sqrt(rng.uniform01()), phi = rng.uniform(0, 2 * M_PI);
  return Vec3(rho * std::cos(phi), rho * std::sin(phi), 0);
}

/// Random intersecting pair: a common point x, disk 2 placed through it.
Local randomIntersecting(fcl_disk_test::Random& rng) {
  Local l;
  l.r1 = rng.uniform(0.2, 1.5);
  l.r2 = l.r1 * rng.logUniform(0.3, 3);
  const Vec3 x = pointInDisk(l.r1, rng);
  l.R2 = rng.rotation();
  l.c2 = x - l.R2 * pointInDisk(l.r2, rng);
  l.kind = "random";
  return l;
}

Local makeLocal(PenFamily f, int i, fcl_disk_test::Random& rng, bool is_float) {
  switch (f) {
    case PenFamily::chain_links: {
      const double r1 = rng.uniform(0.3, 1.5), r2 = r1 * rng.logUniform(0.3, 3);
      const double b = r1 * rng.uniform(-0.7, 0.7), s1 = std::sqrt(r1 * r1 - b * b);
      const double delta = r2 * rng.uniform(-0.7, 0.7), s2 = std::sqrt(r2 * r2 - delta * delta);
      const double chi = (i % 4 == 0) ? 0.0 : rng.uniform(-1.2, 1.2);
      Local l = onCommonLine(r1, r2, b, chi, delta, s1 + rng.uniform(-0.8, 0.8) * s2);
      l.kind = chi == 0 ? "perpendicular" : "tilted";
      return l;
    }
    case PenFamily::through_interior: {
      const double r1 = rng.uniform(0.5, 1.5), r2 = r1 * rng.logUniform(0.3, 3);
      const double b = r1 * rng.uniform(-0.6, 0.6), s1 = std::sqrt(r1 * r1 - b * b);
      const double s2 = std::min(r2, s1) * rng.uniform(0.1, 0.9);
      const double delta = (rng.chance(0.5) ? 1 : -1) * std::sqrt(r2 * r2 - s2 * s2);
      Local l = onCommonLine(r1, r2, b, rng.uniform(-1.2, 1.2), delta,
                             (s1 - s2) * rng.uniform(-0.9, 0.9));
      l.kind = "through";
      return l;
    }
    case PenFamily::rim_through_face: {
      const double r1 = rng.uniform(0.5, 1.5), r2 = r1 * rng.logUniform(0.3, 3);
      const double b = r1 * rng.uniform(-0.6, 0.6), s1 = std::sqrt(r1 * r1 - b * b);
      const double dip = rng.logUniform(1e-4, 0.2);  // of r2, in disk 2's plane
      const double delta = (rng.chance(0.5) ? 1 : -1) * r2 * (1 - dip);
      const double s2 = std::sqrt(r2 * r2 - delta * delta);
      if (s2 >= s1) return makeLocal(f, i, rng, is_float);  // chord must fit: redraw
      Local l = onCommonLine(r1, r2, b, rng.uniform(-1.3, 1.3), delta,
                             (s1 - s2) * rng.uniform(-0.9, 0.9));
      l.kind = "rim";
      return l;
    }
    case PenFamily::coplanar_overlap: {
      Local l;
      l.r1 = rng.uniform(0.2, 1.5);
      l.r2 = rng.uniform(0.2, 1.5);
      l.R1 = rotZ(rng.uniform(0, 2 * M_PI));
      l.R2 = rotZ(rng.uniform(0, 2 * M_PI));
      if (rng.chance(0.5)) l.R2 = l.R2 * Eigen::Vector3d(1, -1, -1).asDiagonal();
      const double gap = (i % 5 == 0) ? 0.0 : rng.uniform(0, 0.98) * (l.r1 + l.r2);
      const double beta = rng.uniform(0, 2 * M_PI);
      l.c2 = gap * Vec3(std::cos(beta), std::sin(beta), 0);
      l.known = 0;
      l.kind = gap == 0 ? "concentric" : "overlap";
      return l;
    }
    case PenFamily::coaxial_centred: {
      Local l;
      l.r1 = rng.uniform(0.2, 1.5);
      l.r2 = (i % 5 == 1) ? l.r1 : rng.uniform(0.2, 1.5);
      const double theta = (i % 7 == 0) ? M_PI / 2 : rng.logUniform(1e-6, M_PI / 2);
      const Vec3 n2(std::sin(theta), 0, std::cos(theta));
      l.R2 = frameWithNormal(n2, rng);
      l.known = std::min(l.r1, l.r2) * std::sin(theta);
      l.kind = "tilt";
      return l;
    }
    case PenFamily::nearly_touching: {
      Local l;
      l.r1 = rng.uniform(0.3, 1.5);
      l.r2 = rng.uniform(0.3, 1.5);
      const double size = l.r1 + l.r2;
      const double dip =
          size * (is_float ? rng.logUniform(1e-6, 1e-3) : rng.logUniform(1e-12, 1e-3));
      if (i % 2 == 0) {
        // Disk 2's lowest rim point `dip` below disk 1's face, over its interior:
        // pushing disk 2 up by dip separates them, and n1 is a strict cone minimum
        // of F (the touching pair's only separating direction): PD = dip.
        Mat3 R2;
        for (;;) {
          R2 = rng.rotation();
          if (std::hypot(R2(0, 2), R2(1, 2)) >= std::sin(0.05)) break;
        }
        const Vec3 up_in_plane =
            (R2.col(0) * R2(2, 0) + R2.col(1) * R2(2, 1)).normalized();  // P2 z / |P2 z|
        const Vec3 foot = pointInDisk(0.9 * l.r1, rng);
        l.R2 = R2;
        l.c2 = foot - dip * Vec3::UnitZ() + l.r2 * up_in_plane;
        l.known = dip;
        l.kind = "face";
      } else {
        // Rim-rim: p on rim 1, w in disk 1's normal cone at p, disk 2 with -w in its
        // normal cone at q = p - dip w (the touching pair moved by -dip w): PD <= dip.
        const double a = rng.uniform(0, 2 * M_PI), psi = rng.uniform(-1.3, 1.3);
        const Vec3 rho1(std::cos(a), std::sin(a), 0);
        const Vec3 w = std::cos(psi) * rho1 + std::sin(psi) * Vec3::UnitZ();
        Mat3 R2;
        Vec3 in_plane;
        for (;;) {
          R2 = rng.rotation();
          in_plane = R2.col(0) * R2.col(0).dot(w) + R2.col(1) * R2.col(1).dot(w);
          if (in_plane.norm() >= 0.1) break;
        }
        l.R2 = R2;
        l.c2 = l.r1 * rho1 - dip * w + l.r2 * in_plane.normalized();
        l.kind = "rim_rim";
      }
      return l;
    }
    case PenFamily::far_from_origin:
    case PenFamily::scales:
    case PenFamily::random_intersecting:
      return randomIntersecting(rng);
  }
  return Local();
}

std::uint64_t familySeed(PenFamily f, bool is_float) {
  return kSeed * 0x9E3779B97F4A7C15ULL + static_cast<std::uint64_t>(f) * 0xD1B54A32D192ED03ULL +
         (is_float ? 77 : 0);
}

/// Cases of family f: built in double in the family frame, moved by a random
/// common rigid motion (far: translated by 1e3..1e6; scales: every length
/// multiplied), rounded once to S.
template <typename S>
std::vector<PenCase<S>> makeFamily(PenFamily f, int count) {
  const bool is_float = std::is_same<S, float>::value;
  fcl_disk_test::Random rng(familySeed(f, is_float));
  std::vector<PenCase<S>> cases;
  for (int i = 0; i < count; ++i) {
    Local l = makeLocal(f, i, rng, is_float);
    l.R1 = l.R1 * rotZ(rng.uniform(0, 2 * M_PI));
    const Mat3 Q = rng.rotation();
    Vec3 t = rng.inBall(2.0);
    double factor = 1;
    if (f == PenFamily::far_from_origin)
      t = (is_float ? rng.logUniform(1e1, 1e3) : rng.logUniform(1e3, 1e6)) * rng.unitVector();
    if (f == PenFamily::scales) factor = rng.logUniform(1e-6, 1e6);
    PenCase<S> c;
    c.name = std::string(familyName(f)) + "/" + l.kind + "/" + std::to_string(i);
    c.r1 = S(factor * l.r1);
    c.r2 = S(factor * l.r2);
    c.X1.linear() = (Q * l.R1).cast<S>();
    c.X1.translation() = (factor * (Q * l.c1 + t)).cast<S>();
    c.X2.linear() = (Q * l.R2).cast<S>();
    c.X2.translation() = (factor * (Q * l.c2 + t)).cast<S>();
    c.known_pd = factor * l.known;
    cases.push_back(c);
  }
  return cases;
}

// ---- helpers ------------------------------------------------------------------

template <typename S>
fcl::Transform3<double> toDouble(const fcl::Transform3<S>& X) {
  return X.template cast<double>();
}

template <typename S>
Vector3R toReal(const fcl::Vector3<S>& v) {
  return v.template cast<Real>();
}

template <typename S>
std::string describe(S r1, const fcl::Transform3<S>& X1, S r2, const fcl::Transform3<S>& X2) {
  const Eigen::IOFormat full(17, Eigen::DontAlignCols, ", ", "; ", "", "", "[", "]");
  std::ostringstream out;
  out << std::setprecision(17) << (std::is_same<S, float>::value ? "float" : "double")
      << " r1=" << double(r1) << " R1=" << X1.linear().template cast<double>().format(full)
      << " c1=" << X1.translation().transpose().template cast<double>().format(full)
      << " r2=" << double(r2) << " R2=" << X2.linear().template cast<double>().format(full)
      << " c2=" << X2.translation().transpose().template cast<double>().format(full);
  return out.str();
}

template <typename S>
std::string describe(const PenCase<S>& c) {
  return c.name + ": " + describe(c.r1, c.X1, c.r2, c.X2);
}

/// Collects failures of one check, prints the first few in full.
class FailureLog {
 public:
  explicit FailureLog(std::string check) : check_(std::move(check)) {}
  void add(const std::string& message) {
    if (count_ < kMaxReportedFailures) ADD_FAILURE() << check_ << ": " << message;
    ++count_;
  }
  int count() const { return count_; }
  ~FailureLog() { EXPECT_EQ(count_, 0) << check_ << ": " << count_ << " failing cases in total"; }

 private:
  std::string check_;
  int count_ = 0;
};

/// Everything a case's checks need from the reference.
template <typename S>
struct Referenced {
  PenCase<S> c;
  PenDisk disk1, disk2;
  PenReference reference;
  double scale;      ///< r1 + r2 + |c1 - c2|
  double length;     ///< the tolerances' length: scale (double), max(scale, |c_i|) (float)
  double world;      ///< max |c_i| + r1 + r2
  double pd_tol;     ///< allowed |PD - PD_ref|
  double point_tol;  ///< allowed distance of a returned point from its disk
  double value_tol;  ///< allowed F_ref(direction) - PD_ref
};

template <typename S>
Referenced<S> reference(const PenCase<S>& c) {
  Referenced<S> r;
  r.c = c;
  r.disk1 = ref::makePenDisk(c.X1, c.r1);
  r.disk2 = ref::makePenDisk(c.X2, c.r2);
  r.reference = ref::referencePenetration(r.disk1, r.disk2);
  const double c1 = c.X1.translation().template cast<double>().norm();
  const double c2 = c.X2.translation().template cast<double>().norm();
  r.scale =
      double(c.r1) + double(c.r2) +
      (c.X1.translation().template cast<double>() - c.X2.translation().template cast<double>())
          .norm();
  r.length = Tol<S>::kFloat ? std::max({r.scale, c1, c2}) : r.scale;
  r.world = std::max(c1, c2) + double(c.r1) + double(c.r2);
  r.pd_tol = Tol<S>::kPdRelative * r.length;
  r.point_tol = r.pd_tol + Tol<S>::kWorldRoundingEps * Tol<S>::kEps * r.world;
  r.value_tol = r.pd_tol + Tol<S>::kDirectionValueExtraEps * Tol<S>::kEps * r.length;
  return r;
}

double angleBetween(const Vector3R& a, const Vector3R& b) {
  return double(PenReference::angleBetween(a, b));
}

/// Whether the reference's minimiser is unique to `level` (no rival minimum with
/// a value within kRivalLevelFactor * level of PD_ref outside the sublevel set
/// {F <= PD_ref + level} around w), and how far apart two directions whose F is
/// within `level` of PD_ref can then be: twice the sublevel radius, plus
/// rounding each to S.
struct Uniqueness {
  bool unique;
  double direction_tol;
};

template <typename S>
Uniqueness uniqueness(const Referenced<S>& r, double level) {
  const double radius =
      double(ref::sublevelRadius(r.disk1, r.disk2, r.reference.w, r.reference.pd + Real(level)));
  bool unique = true;
  for (const ref::PenMinimum& m : r.reference.minima) {
    if (double(m.value) <= double(r.reference.pd) + kRivalLevelFactor * level &&
        double(PenReference::angleBetween(m.w, r.reference.w)) > radius)
      unique = false;
  }
  return {unique, 2 * radius + Tol<S>::kDirectionRoundingEps * Tol<S>::kEps};
}

/// Pose X translated by t (double arithmetic on the stored pose).
fcl::Transform3<double> translated(const fcl::Transform3<double>& X, const Vec3& t) {
  fcl::Transform3<double> Y = X;
  Y.translation() += t;
  return Y;
}

/// Running maximum with the case where it was reached.
struct MaxStat {
  double value = 0;
  std::string where;
  void add(double v, const std::string& name) {
    if (v > value) {
      value = v;
      where = name;
    }
  }
};

// ---- the reference: closed forms ----------------------------------------------

using Pose = fcl::Transform3<double>;

Pose poseWithNormal(const Vec3& centre, const Vec3& normal) {
  Pose X = Pose::Identity();
  X.translation() = centre;
  X.linear() =
      Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), normal.normalized()).toRotationMatrix();
  return X;
}

/// Reference PD of two disks given by centre, normal and radius.
PenReference referenceOf(double r1, const Vec3& c1, const Vec3& n1, double r2, const Vec3& c2,
                         const Vec3& n2) {
  return ref::referencePenetration(r1, poseWithNormal(c1, n1), r2, poseWithNormal(c2, n2));
}

void expectReferencePd(const PenReference& r, double expected, const std::string& what) {
  EXPECT_LE(std::fabs(double(r.pd) - expected), kReferenceRelative * double(r.scale))
      << what << ": reference " << std::setprecision(20) << double(r.pd) << ", expected "
      << expected;
}

TEST(ReferencePenetration, CoplanarOverlapIsZero) {
  // A shift along the common normal by any t > 0 separates coplanar disks, and
  // they share a point: PD = 0 (F(n1) = (c1 - c2).n1 + r2 |P2 n1| = 0).
  const Vec3 z = Vec3::UnitZ();
  expectReferencePd(referenceOf(1, Vec3::Zero(), z, 0.7, Vec3(0.5, 0.3, 0), z), 0, "overlap");
  expectReferencePd(referenceOf(1, Vec3::Zero(), z, 1, Vec3::Zero(), -z), 0, "concentric");
  expectReferencePd(referenceOf(0.4, Vec3(2, 1, -3), z, 1.5, Vec3(2.1, 0.2, -3), z), 0,
                    "small inside large");
}

TEST(ReferencePenetration, PerpendicularThroughCentresIsOneAndATie) {
  // F(w) = |P1 w| + |P2 w| = sqrt(wx^2 + wy^2) + sqrt(wx^2 + wz^2) >= 1 (Minkowski:
  // >= sqrt(4 wx^2 + (|wy| + |wz|)^2) >= 1), with equality at +-y and +-z only.
  const PenReference r =
      referenceOf(1, Vec3::Zero(), Vec3::UnitZ(), 1, Vec3::Zero(), Vec3::UnitY());
  expectReferencePd(r, 1, "perpendicular");
  EXPECT_TRUE(r.hasRival(kHandTieValue, kHandTieAngle)) << "four tied minimisers +-y, +-z";
  const double off_axis = std::min(std::fabs(double(r.w.y())), std::fabs(double(r.w.z())));
  EXPECT_LE(off_axis, kReferenceKinkAngle) << "minimiser must be +-y or +-z";
  EXPECT_LE(std::fabs(double(r.w.x())), kReferenceKinkAngle);
}

TEST(ReferencePenetration, SmallDiskThroughTheFaceIsPushedUp) {
  // Disk 2 (r 0.1, XZ plane, centre (0, 0, 0.05)) through disk 1 (r 1, XY plane).
  // F(w) = -0.05 wz + sqrt(wx^2 + wy^2) + 0.1 sqrt(wx^2 + wz^2). For wz <= 0,
  // F >= 0.1 (|P1 w| + |P2 w|) >= 0.1. For wz > 0, F >= 0.05 wz + sqrt(1 - wz^2)
  // (as sqrt(wx^2 + wz^2) >= wz), concave in wz, so >= min(1, 0.05) = 0.05, with
  // equality only at w = +z: PD = 0.05, unique, along +z.
  const PenReference r =
      referenceOf(1, Vec3::Zero(), Vec3::UnitZ(), 0.1, Vec3(0, 0, 0.05), Vec3::UnitY());
  expectReferencePd(r, 0.05, "small disk");
  EXPECT_LE(angleBetween(r.w, Vector3R::UnitZ()), kReferenceKinkAngle);
  EXPECT_FALSE(r.hasRival(kHandNoRivalValue, kHandNoRivalAngle))
      << "the next minimum is -z at 0.15";
  // Witness points: disk 2's lowest point (0, 0, -0.05) and p1 = p2 + PD z.
  EXPECT_LE(double((r.p2 - Vector3R(0, 0, -0.05L)).norm()), kReferenceRelative * double(r.scale));
  EXPECT_LE(double((r.p1 - r.p2 - r.pd * r.w).norm()), kReferenceRelative * double(r.scale));
}

TEST(ReferencePenetration, CoaxialCentredIsTheSmallerRadiusTimesSine) {
  // Same centre: F(w) = r1 |P1 w| + r2 |P2 w| = r1 sin a1 + r2 sin a2 (a_i the angle
  // of w to the line of n_i, in [0, pi/2]); a1 + a2 >= theta, and for angles in
  // [0, pi/2] sin a1 + sin a2 >= sin(min(a1 + a2, pi/2)) >= sin(theta), so
  // F >= min(r1, r2) sin(theta), attained at the larger disk's normal.
  for (double theta : {1e-6, 0.3, 1.0, M_PI / 2}) {
    for (const auto& radii : {std::pair<double, double>{1, 0.4}, {0.4, 1}, {0.8, 0.8}}) {
      const Vec3 n2(std::sin(theta), 0, std::cos(theta));
      const PenReference r =
          referenceOf(radii.first, Vec3(1, -2, 3), Vec3::UnitZ(), radii.second, Vec3(1, -2, 3), n2);
      expectReferencePd(r, std::min(radii.first, radii.second) * std::sin(theta),
                        "coaxial theta=" + std::to_string(theta));
      // F is even here (c1 = c2): w and -w always tie.
      EXPECT_TRUE(r.hasRival(kHandTieValue, kHandTieAngle));
    }
  }
}

TEST(ReferencePenetration, SymmetricChainLinkIsOneAlongTwoArcs) {
  // Disk 1: r 1, XY plane, origin; disk 2: r 1, XZ plane, centre (1, 0, 0) (each
  // through the other's centre). F(a, b, c) = -a + sqrt(a^2 + b^2) + sqrt(a^2 + c^2).
  // For a <= 0, F >= |P1 w| + |P2 w| >= 1. For a > 0 write sqrt(a^2 + c^2) = a + t,
  // t >= 0, so c^2 = t (2a + t); then F >= 1 = sqrt(A^2 + c^2) (A = sqrt(a^2 + b^2))
  // iff (A + t)^2 >= A^2 + 2at + t^2 iff A >= a: true, with equality iff t = 0 or
  // b = 0. PD = 1 on two half great circles {c = 0, a >= 0} and {b = 0, a >= 0}.
  const PenReference r =
      referenceOf(1, Vec3::Zero(), Vec3::UnitZ(), 1, Vec3(1, 0, 0), Vec3::UnitY());
  expectReferencePd(r, 1, "chain link");
  EXPECT_TRUE(r.hasRival(kHandTieValue, kHandTieAngle));
  const bool on_arc = (std::fabs(double(r.w.z())) <= kReferenceFlatAngle ||
                       std::fabs(double(r.w.y())) <= kReferenceFlatAngle) &&
                      double(r.w.x()) >= -kReferenceFlatAngle;
  EXPECT_TRUE(on_arc) << r.w.transpose();
  // Sanity by translation along directions of both arcs, judged by the library's
  // exact distance: 1 + margin separates (by at most margin), 1 - margin does not.
  const Pose X1 = poseWithNormal(Vec3::Zero(), Vec3::UnitZ());
  const Pose X2 = poseWithNormal(Vec3(1, 0, 0), Vec3::UnitY());
  for (double phi : {-1.5, -0.7, 0.0, 0.4, 1.2, 1.5707963267948966}) {
    for (const Vec3& w :
         {Vec3(std::cos(phi), 0, std::sin(phi)), Vec3(std::cos(phi), std::sin(phi), 0)}) {
      const double margin = kHandTranslationMargin;
      const double apart =
          fcl_disk::exactDiskDistance(1.0, X1, 1.0, translated(X2, (1 + margin) * w)).distance;
      EXPECT_GT(apart, 0.0) << "phi " << phi << " w " << w.transpose();
      EXPECT_LE(apart, margin + kExactDistanceRelative * double(r.scale));
      EXPECT_TRUE(fcl_disk::intersectDisks(1.0, X1, 1.0, translated(X2, (1 - margin) * w)))
          << "phi " << phi << " w " << w.transpose();
    }
  }
}

TEST(ReferencePenetration, ApartPairsGiveMinusTheDistance) {
  // Coaxial stack at height h: min F = -h (F(-z)... along +z: (c1 - c2).z = -h).
  for (double h : {1e-9, 0.3, 5.0}) {
    const PenReference r =
        referenceOf(1, Vec3::Zero(), Vec3::UnitZ(), 0.6, Vec3(0, 0, h), Vec3::UnitZ());
    expectReferencePd(r, -h, "coaxial stack h=" + std::to_string(h));
  }
  // Random separated pairs: -min F equals reference_distance.h's certified distance.
  fcl_disk_test::Random rng(kSeed + 1);
  int apart = 0;
  double worst = 0;
  for (int i = 0; i < 200; ++i) {
    Pose X1 = Pose::Identity(), X2 = Pose::Identity();
    X1.linear() = rng.rotation();
    X2.linear() = rng.rotation();
    X1.translation() = rng.inBall(2);
    X2.translation() = rng.inBall(2);
    const double r1 = rng.uniform(0.2, 1.5), r2 = rng.uniform(0.2, 1.5);
    // Both references on the same long-double disks: reference_distance.h's
    // re-orthonormalised frames (a double rotation is orthonormal only to ~1e-16,
    // which would otherwise differ by that much times the radii).
    const fcl_disk_reference::RefDisk a = fcl_disk_reference::makeRefDisk(X1, r1);
    const fcl_disk_reference::RefDisk b = fcl_disk_reference::makeRefDisk(X2, r2);
    const auto distance = fcl_disk_reference::referenceDiskDistance(a, b);
    if (!(distance.distance > 0)) continue;
    ++apart;
    const PenReference r = ref::referencePenetration(PenDisk{a.centre, a.u, a.v, a.n, a.radius},
                                                     PenDisk{b.centre, b.u, b.v, b.n, b.radius});
    const double error = std::fabs(double(r.pd + distance.distance)) / double(r.scale);
    worst = std::max(worst, error);
    EXPECT_LE(error, kReferenceRelative) << describe(r1, X1, r2, X2);
  }
  EXPECT_GE(apart, 100);
  std::cout << "[ stats    ] reference: " << apart
            << " apart pairs, max |min F + distance| / scale " << worst << std::endl;
}

// ---- the reference on the families -------------------------------------------

class FamilyTest : public ::testing::TestWithParam<PenFamily> {};

std::string familyParamName(const ::testing::TestParamInfo<PenFamily>& info) {
  return familyName(info.param);
}

/// Known PDs of constructions (coplanar 0, coaxial min(r1, r2) sin(theta), face
/// dips), a 10x denser scan with 4x the starts finding nothing lower, and the
/// reference direction separating at PD_ref + margin (library exact distance).
TEST_P(FamilyTest, ReferenceIsConsistent) {
  constexpr int kCases = 40;
  FailureLog known_log("reference vs constructed PD");
  FailureLog dense_log("reference vs 10x denser reference");
  FailureLog separation_log("reference direction separates at PD_ref + margin");
  double worst_known = 0, worst_dense = 0;
  for (const PenCase<double>& c : makeFamily<double>(GetParam(), kCases)) {
    const Referenced<double> r = reference(c);
    const double pd = double(r.reference.pd);
    if (!std::isnan(c.known_pd)) {
      // The construction holds in double before rounding: pose rounding only.
      const double tol = Tol<double>::kPoseRoundingEps * Tol<double>::kEps * r.world +
                         kReferenceRelative * r.scale;
      worst_known = std::max(worst_known, std::fabs(pd - c.known_pd) / r.scale);
      if (!(std::fabs(pd - c.known_pd) <= tol)) {
        std::ostringstream m;
        m << std::setprecision(17) << "known " << c.known_pd << " reference " << pd << " "
          << describe(c);
        known_log.add(m.str());
      }
    }
    ref::PenOptions dense;
    dense.samples = 10 * ref::kPenetrationSamples;
    dense.starts = 4 * ref::kPenetrationStarts;
    const PenReference d = ref::referencePenetration(r.disk1, r.disk2, dense);
    worst_dense = std::max(worst_dense, double(r.reference.pd - d.pd) / r.scale);
    if (!(double(r.reference.pd - d.pd) <= kReferenceRelative * r.scale)) {
      std::ostringstream m;
      m << std::setprecision(20) << "default " << pd << " dense " << double(d.pd) << " "
        << describe(c);
      dense_log.add(m.str());
    }
    if (pd > 0) {
      const double margin = Tol<double>::kSeparationMargin * r.scale;
      const Vec3 w = r.reference.w.cast<double>();
      const Pose X1 = toDouble(c.X1), X2 = toDouble(c.X2);
      const double apart = fcl_disk::exactDiskDistance(double(c.r1), X1, double(c.r2),
                                                       translated(X2, (pd + margin) * w))
                               .distance;
      const bool still_in =
          pd <= margin || fcl_disk::intersectDisks(double(c.r1), X1, double(c.r2),
                                                   translated(X2, (pd - margin) * w));
      // The translated pose is stored in double: ulp(|c2|) per coordinate.
      const double stored = r.point_tol - r.pd_tol;
      if (!(apart > 0 && apart <= margin + kExactDistanceRelative * r.scale + stored && still_in)) {
        std::ostringstream m;
        m << std::setprecision(17) << "PD_ref " << pd << " distance after PD + margin " << apart
          << " still intersecting at PD - margin " << still_in << " " << describe(c);
        separation_log.add(m.str());
      }
    }
  }
  std::cout << "[ stats    ] reference " << familyName(GetParam())
            << ": max |PD_ref - known| / scale " << worst_known
            << ", max (PD_ref - PD_dense) / scale " << worst_dense << std::endl;
}

// ---- the solver against the reference -----------------------------------------

template <typename S>
struct FamilyStats {
  int cases = 0, apart = 0, ties = 0;
  MaxStat pd, points, consistency, value, symmetry_pd, symmetry_dir, motion_pd, motion_dir,
      separation;
};

/// Checks 1-4 of one family for scalar type S.
template <typename S>
void checkFamily(PenFamily family, int count) {
  const std::string type = Tol<S>::kFloat ? "<float>" : "<double>";
  FailureLog pd_log("PD" + type + " vs reference");
  FailureLog extension_log("diskPenetration" + type + " on a pair found apart: -distance");
  FailureLog beaten_log("REFERENCE beaten: F_ref(solver direction) < PD_ref" + type);
  FailureLog value_log("F_ref(direction" + type + ") - PD_ref");
  FailureLog points_log("witness points" + type + " on their disks");
  FailureLog consistency_log("p_W1 - p_W2 == PD direction, |direction| == 1" + type);
  FailureLog separation_log("translating by PD + margin separates" + type);
  FailureLog inside_log("translating by PD - margin still intersects" + type);
  FailureLog swap_log("swapped disks: same PD, negated direction" + type);
  FailureLog motion_log("common rigid motion: same PD, rotated direction" + type);
  FamilyStats<S> stats;
  fcl_disk_test::Random motion_rng(familySeed(family, Tol<S>::kFloat) + 5);

  for (const PenCase<S>& c : makeFamily<S>(family, count)) {
    const Referenced<S> r = reference(c);
    const double pd_ref = double(r.reference.pd);
    const fcl_disk::DiskSignedDistanceResult<S> res =
        fcl_disk::diskPenetration<S>(c.r1, c.X1, c.r2, c.X2);
    const double pd = -double(res.signed_distance);
    std::ostringstream head;
    head << std::setprecision(17) << "PD_ref " << pd_ref << " PD " << pd << " (error "
         << (pd - pd_ref) / r.length << " of length " << r.length << "); ";
    const std::string where = head.str() + describe(c);
    ++stats.cases;
    if (pd_ref < -r.pd_tol) {
      // Rounding to S left the pair apart: the documented extension, -distance.
      ++stats.apart;
      if (!(std::fabs(pd - pd_ref) <= r.pd_tol)) extension_log.add(where);
      continue;
    }

    // 1. PD.
    stats.pd.add(std::fabs(pd - pd_ref) / r.length, c.name);
    if (!(std::fabs(pd - pd_ref) <= r.pd_tol)) pd_log.add(where);

    // 2. Direction and witness points.
    const Vector3R dir = toReal<S>(res.direction);
    const double f_dir = double(ref::referenceF(r.disk1, r.disk2, dir));
    stats.value.add((f_dir - pd_ref) / r.length, c.name);
    if (f_dir < pd_ref - kReferenceBeatenRelative * r.scale) {
      std::ostringstream m;
      m << std::setprecision(20) << "F_ref(direction) " << f_dir << " direction "
        << res.direction.transpose().template cast<double>() << " reference w "
        << r.reference.w.transpose().template cast<double>() << "; " << where;
      beaten_log.add(m.str());
    }
    if (!(f_dir - pd_ref <= r.value_tol)) {
      std::ostringstream m;
      m << std::setprecision(17) << "F_ref(direction) - PD_ref = " << f_dir - pd_ref
        << " direction " << res.direction.transpose().template cast<double>() << " reference w "
        << r.reference.w.transpose().template cast<double>() << "; " << where;
      value_log.add(m.str());
    }
    const double off1 = double(ref::pointToDisk(toReal<S>(res.p_W1), r.disk1));
    const double off2 = double(ref::pointToDisk(toReal<S>(res.p_W2), r.disk2));
    stats.points.add(std::max(off1, off2) / r.length, c.name);
    if (!(off1 <= r.point_tol && off2 <= r.point_tol)) {
      std::ostringstream m;
      m << std::setprecision(17) << "p_W1 " << off1 << " from disk 1, p_W2 " << off2
        << " from disk 2 (tolerance " << r.point_tol << "); " << where;
      points_log.add(m.str());
    }
    const double gap = double((toReal<S>(res.p_W1) - toReal<S>(res.p_W2) - Real(pd) * dir).norm());
    const double unit = std::fabs(double(dir.norm()) - 1);
    stats.consistency.add(gap / r.length, c.name);
    if (!(gap <= r.pd_tol + 2 * (r.point_tol - r.pd_tol) && unit <= Tol<S>::kUnitDirection)) {
      std::ostringstream m;
      m << std::setprecision(17) << "|p_W1 - p_W2 - PD dir| = " << gap
        << ", | |dir| - 1 | = " << unit << "; " << where;
      consistency_log.add(m.str());
    }

    // 3. Separation, judged by the library's exact distance on the stored poses.
    {
      const Pose X1 = toDouble(c.X1), X2 = toDouble(c.X2);
      const Vec3 w = res.direction.template cast<double>();
      const double margin = Tol<S>::kSeparationMargin * r.scale;
      const auto apart = fcl_disk::exactDiskDistance(double(c.r1), X1, double(c.r2),
                                                     translated(X2, (pd + margin) * w));
      const bool apart_intersects = fcl_disk::intersectDisks(double(c.r1), X1, double(c.r2),
                                                             translated(X2, (pd + margin) * w));
      stats.separation.add(apart.distance / margin, c.name);
      // The disks touch after translating by rho_M(w) >= PD_true >= PD - pd_tol
      // (rho_M: the radial function of K1 - K2 along w), and the distance is
      // 1-Lipschitz in the translation, so margin further they are at most
      // margin + pd_tol apart (value_tol kept as spare), plus the judge's error
      // and ulp(|c2|) per stored coordinate. PD - margin still intersecting says
      // rho_M(w) >= PD - margin: with the first, (PD, w) is a touching
      // translation, as disk_penetration.h states.
      const double judge = kExactDistanceRelative * r.scale +
                           Tol<double>::kWorldRoundingEps * Tol<double>::kEps * r.world;
      if (!(apart.distance > 0 && !apart_intersects &&
            apart.distance <= margin + r.value_tol + r.pd_tol + judge)) {
        std::ostringstream m;
        m << std::setprecision(17) << "distance after PD + margin (" << margin
          << "): " << apart.distance << ", intersectDisks " << apart_intersects << "; " << where;
        separation_log.add(m.str());
      }
      if (pd > margin && !fcl_disk::intersectDisks(double(c.r1), X1, double(c.r2),
                                                   translated(X2, (pd - margin) * w))) {
        std::ostringstream m;
        m << std::setprecision(17) << "apart after PD - margin (" << margin << "): distance "
          << fcl_disk::exactDiskDistance(double(c.r1), X1, double(c.r2),
                                         translated(X2, (pd - margin) * w))
                 .distance
          << "; " << where;
        inside_log.add(m.str());
      }
    }

    // 4. Symmetry and rigid motion. The direction is compared only where the
    // minimiser is unique to the tolerance: no rival minimum of the reference
    // with a value within the level outside the sublevel set around w.
    const fcl_disk::DiskSignedDistanceResult<S> swapped =
        fcl_disk::diskPenetration<S>(c.r2, c.X2, c.r1, c.X1);
    const double pd_swapped = -double(swapped.signed_distance);
    fcl::Transform3<double> M = fcl::Transform3<double>::Identity();
    M.linear() = motion_rng.rotation();
    M.translation() = motion_rng.inBall(r.world);
    const fcl::Transform3<S> X1m = (M * toDouble(c.X1)).template cast<S>();
    const fcl::Transform3<S> X2m = (M * toDouble(c.X2)).template cast<S>();
    const fcl_disk::DiskSignedDistanceResult<S> moved =
        fcl_disk::diskPenetration<S>(c.r1, X1m, c.r2, X2m);
    const double pd_moved = -double(moved.signed_distance);
    const double world_moved = std::max(
        {r.world, X1m.translation().template cast<double>().norm() + double(c.r1) + double(c.r2),
         X2m.translation().template cast<double>().norm() + double(c.r1) + double(c.r2)});
    const double pose_rounding = Tol<S>::kPoseRoundingEps * Tol<S>::kEps * world_moved;

    const Uniqueness u = uniqueness(r, r.value_tol + pose_rounding);
    const bool unique = u.unique;
    const double direction_tol = u.direction_tol;
    if (!unique) ++stats.ties;

    stats.symmetry_pd.add(std::fabs(pd_swapped - pd) / r.length, c.name);
    const double swap_angle = angleBetween(-toReal<S>(swapped.direction), dir);
    if (unique) stats.symmetry_dir.add(swap_angle, c.name);
    if (!(std::fabs(pd_swapped - pd_ref) <= r.pd_tol) ||
        (unique && !(swap_angle <= direction_tol))) {
      std::ostringstream m;
      m << std::setprecision(17) << "swapped PD " << pd_swapped << ", angle(-dir_swapped, dir) "
        << swap_angle << " (tolerance " << direction_tol << ", unique " << unique << "); " << where;
      swap_log.add(m.str());
    }
    stats.motion_pd.add(std::fabs(pd_moved - pd) / r.length, c.name);
    const Vector3R rotated =
        (M.linear() * res.direction.template cast<double>()).template cast<Real>();
    const double motion_angle = angleBetween(toReal<S>(moved.direction), rotated);
    if (unique) stats.motion_dir.add(motion_angle, c.name);
    if (!(std::fabs(pd_moved - pd_ref) <= r.pd_tol + pose_rounding) ||
        (unique && !(motion_angle <= direction_tol))) {
      std::ostringstream m;
      m << std::setprecision(17) << "moved PD " << pd_moved << ", angle(dir_moved, Q dir) "
        << motion_angle << " (tolerance " << direction_tol << ", unique " << unique
        << "); motion Q="
        << M.linear().format(Eigen::IOFormat(17, Eigen::DontAlignCols, ", ", "; "))
        << " t=" << M.translation().transpose() << "; " << where;
      motion_log.add(m.str());
    }
  }

  const double unit = Tol<S>::kFloat ? Tol<S>::kEps : 1.0;
  std::cout << std::setprecision(3) << "[ stats    ] " << familyName(family) << type << ": cases "
            << stats.cases << " (apart after rounding " << stats.apart << ", ties " << stats.ties
            << "); max per length" << (Tol<S>::kFloat ? " in float eps" : "") << ": |PD - ref| "
            << stats.pd.value / unit << " [" << stats.pd.where << "]"
            << ", points off disks " << stats.points.value / unit << ", |p1 - p2 - PD dir| "
            << stats.consistency.value / unit << ", F_ref(dir) - PD_ref "
            << stats.value.value / unit << ", swap |dPD| " << stats.symmetry_pd.value / unit
            << " angle " << stats.symmetry_dir.value << ", motion |dPD| "
            << stats.motion_pd.value / unit << " angle " << stats.motion_dir.value
            << ", distance after PD+margin / margin " << stats.separation.value << std::endl;
}

TEST_P(FamilyTest, DiskPenetrationDoubleMatchesReference) {
  checkFamily<double>(GetParam(), kDoubleCases);
}

TEST_P(FamilyTest, DiskPenetrationFloatMatchesReference) {
  checkFamily<float>(GetParam(), kFloatCases);
}

// ---- signedDiskDistance ---------------------------------------------------------

/// Intersecting: -PD (as diskPenetration, judged by the reference). Apart (disk 2
/// moved along the reference minimiser by PD_ref + 1e-9..1 of scale):
/// exactDiskDistance's distance and points, judged by reference_distance.h, and
/// direction (p_W2 - p_W1) / d; diskPenetration's extension gives -distance too.
template <typename S>
void checkSignedDistance(PenFamily family) {
  const std::string type = Tol<S>::kFloat ? "<float>" : "<double>";
  FailureLog inside_log("signedDiskDistance" + type + " intersecting: -PD");
  FailureLog apart_log("signedDiskDistance" + type + " apart: exactDiskDistance's answer");
  FailureLog reference_log("signedDiskDistance" + type + " apart vs reference distance");
  FailureLog extension_log("diskPenetration" + type + " apart: -distance");
  fcl_disk_test::Random rng(familySeed(family, Tol<S>::kFloat) + 11);
  for (const PenCase<S>& c : makeFamily<S>(family, kSignedCases)) {
    const Referenced<S> r = reference(c);
    const double pd_ref = double(r.reference.pd);
    const auto sd = fcl_disk::signedDiskDistance<S>(c.r1, c.X1, c.r2, c.X2);
    const auto pen = fcl_disk::diskPenetration<S>(c.r1, c.X1, c.r2, c.X2);
    if (pd_ref > r.pd_tol) {
      const bool same = sd.signed_distance == pen.signed_distance && sd.p_W1 == pen.p_W1 &&
                        sd.p_W2 == pen.p_W2 && sd.direction == pen.direction;
      if (!(std::fabs(double(sd.signed_distance) + pd_ref) <= r.pd_tol && same)) {
        std::ostringstream m;
        m << std::setprecision(17) << "signed " << double(sd.signed_distance) << " PD_ref "
          << pd_ref << " same as diskPenetration " << same << "; " << describe(c);
        inside_log.add(m.str());
      }
    }
    // Apart: move disk 2 along the reference minimiser past contact.
    if (pd_ref < 0) continue;
    const double extra = r.scale * rng.logUniform(Tol<S>::kFloat ? 1e-5 : 1e-9, 1.0);
    fcl::Transform3<S> X2a = c.X2;
    X2a.translation() +=
        ((pd_ref + extra) * r.reference.w.template cast<double>()).template cast<S>();
    const auto sda = fcl_disk::signedDiskDistance<S>(c.r1, c.X1, c.r2, X2a);
    const auto exact = fcl_disk::exactDiskDistance<S>(c.r1, c.X1, c.r2, X2a);
    const double d_ref =
        double(fcl_disk_reference::referenceDiskDistance(c.r1, c.X1, c.r2, X2a).distance);
    const double length = std::max(
        r.length, Tol<S>::kFloat ? double(X2a.translation().template cast<double>().norm()) : 0.0);
    const double tol = Tol<S>::kPdRelative * (length + extra);
    // The points are stored in world coordinates: ulp(|c_i|) each.
    const double world = Tol<S>::kWorldRoundingEps * Tol<S>::kEps *
                         (r.world + double(X2a.translation().template cast<double>().norm()));
    const fcl::Vector3<S> chord = exact.p_W2 - exact.p_W1;
    const double direction_gap =
        double((toReal<S>(sda.direction) * Real(sda.signed_distance) - toReal<S>(chord)).norm());
    if (!(exact.distance > 0)) continue;  // rounding to S put it back in contact
    if (!(sda.signed_distance == exact.distance && sda.p_W1 == exact.p_W1 &&
          sda.p_W2 == exact.p_W2 && direction_gap <= tol + 2 * world &&
          std::fabs(double(sda.direction.norm()) - 1) <= Tol<S>::kUnitDirection)) {
      std::ostringstream m;
      m << std::setprecision(17) << "signed " << double(sda.signed_distance) << " exact "
        << double(exact.distance) << " |d dir - (p2 - p1)| " << direction_gap << "; "
        << describe(c.r1, c.X1, c.r2, X2a);
      apart_log.add(m.str());
    }
    if (!(std::fabs(double(sda.signed_distance) - d_ref) <= tol)) {
      std::ostringstream m;
      m << std::setprecision(17) << "signed " << double(sda.signed_distance) << " reference "
        << d_ref << "; " << describe(c.r1, c.X1, c.r2, X2a);
      reference_log.add(m.str());
    }
    const auto ext = fcl_disk::diskPenetration<S>(c.r1, c.X1, c.r2, X2a);
    if (!(std::fabs(double(ext.signed_distance) - d_ref) <= tol)) {
      std::ostringstream m;
      m << std::setprecision(17) << "diskPenetration signed " << double(ext.signed_distance)
        << " reference distance " << d_ref << "; " << describe(c.r1, c.X1, c.r2, X2a);
      extension_log.add(m.str());
    }
  }
}

TEST_P(FamilyTest, SignedDistanceDouble) { checkSignedDistance<double>(GetParam()); }
TEST_P(FamilyTest, SignedDistanceFloat) { checkSignedDistance<float>(GetParam()); }

/// A straight path of disk 2 from apart (3 scale along a random direction) to
/// the interlocked pose: consecutive signed distances differ by at most the step
/// (1-Lipschitz in translation) plus tolerance; the sign changes once (the set of
/// translations where the disks meet is convex, so a line meets it in an
/// interval); every few steps, the value equals minus the reference's min F.
template <typename S>
void checkContinuity() {
  const std::string type = Tol<S>::kFloat ? "<float>" : "<double>";
  FailureLog lipschitz_log("signed distance" + type + " 1-Lipschitz along a path");
  FailureLog sign_log("signed distance" + type + " changes sign once along a path");
  FailureLog reference_log("signed distance" + type + " along a path vs reference");
  fcl_disk_test::Random rng(kSeed + 3);
  MaxStat worst_jump;
  for (const PenCase<S>& c : makeFamily<S>(PenFamily::chain_links, kContinuityPaths)) {
    const Referenced<S> r = reference(c);
    const Vec3 v = rng.unitVector();
    const double travel = 3 * r.scale, step = travel / kContinuitySteps;
    double previous = std::numeric_limits<double>::quiet_NaN();
    int sign_changes = 0;
    for (int k = 0; k <= kContinuitySteps; ++k) {
      fcl::Transform3<S> X2 = c.X2;
      X2.translation() += ((travel - k * step) * v).template cast<S>();
      const double sd =
          double(fcl_disk::signedDiskDistance<S>(c.r1, c.X1, c.r2, X2).signed_distance);
      const double length = std::max(
          r.length, Tol<S>::kFloat ? double(X2.translation().template cast<double>().norm()) : 0.0);
      const double tol = Tol<S>::kPdRelative * (length + travel);
      if (k > 0) {
        worst_jump.add(std::fabs(sd - previous) / step, c.name);
        // Float: the stored translation moves by up to an ulp per coordinate.
        const double stored_step = step + 2 * Tol<S>::kEps * (length + travel);
        if (!(std::fabs(sd - previous) <= stored_step + 2 * tol)) {
          std::ostringstream m;
          m << std::setprecision(17) << "step " << k << ": " << previous << " -> " << sd
            << " (step " << step << "); " << describe(c.r1, c.X1, c.r2, X2);
          lipschitz_log.add(m.str());
        }
        if ((previous > 0) != (sd > 0)) ++sign_changes;
      }
      if (k % kContinuityReferenceEvery == 0) {
        const double expected = -double(ref::referencePenetration(c.r1, c.X1, c.r2, X2).pd);
        if (!(std::fabs(sd - expected) <= tol)) {
          std::ostringstream m;
          m << std::setprecision(17) << "step " << k << ": signed " << sd << " reference "
            << expected << "; " << describe(c.r1, c.X1, c.r2, X2);
          reference_log.add(m.str());
        }
      }
      previous = sd;
    }
    if (sign_changes != 1) {
      std::ostringstream m;
      m << sign_changes << " sign changes; path direction " << v.transpose() << "; " << describe(c);
      sign_log.add(m.str());
    }
  }
  std::cout << "[ stats    ] continuity" << type << ": max |delta signed distance| / step "
            << worst_jump.value << " [" << worst_jump.where << "]" << std::endl;
}

TEST(SignedDiskDistance, ContinuousThroughContactDouble) { checkContinuity<double>(); }
TEST(SignedDiskDistance, ContinuousThroughContactFloat) { checkContinuity<float>(); }

// ---- through FCL ----------------------------------------------------------------

/// fcl::distance with enable_signed_distance: min_distance = -PD, nearest points
/// {p_W1, p_W2} (on their disks, PD apart along a minimising direction; equal to
/// signedDiskDistance's where the minimiser is unique); without it: 0. fcl::collide
/// with contacts: one contact, depth PD, normal a minimiser (= direction where
/// unique), pos on both disks. Both GJK solver settings.
template <typename S>
void checkThroughFcl(PenFamily family) {
  const std::string type = Tol<S>::kFloat ? "<float>" : "<double>";
  FailureLog signed_log("fcl::distance" + type + " signed: -PD and witness points");
  FailureLog same_log("fcl::distance" + type + " signed == signedDiskDistance");
  FailureLog unsigned_log("fcl::distance" + type + " unsigned: 0 when intersecting");
  FailureLog contact_log("fcl::collide" + type + " contact: depth PD, normal, pos");
  for (const PenCase<S>& c : makeFamily<S>(family, kFclCases)) {
    const Referenced<S> r = reference(c);
    const double pd_ref = double(r.reference.pd);
    if (!(pd_ref > Tol<S>::kTouchingRelative * r.length)) continue;  // clearly intersecting only
    const Uniqueness u = uniqueness(r, r.value_tol);
    const bool unique = u.unique;
    const auto api = fcl_disk::signedDiskDistance<S>(c.r1, c.X1, c.r2, c.X2);
    const fcl::CollisionObject<S> o1(std::make_shared<fcl_disk::Disk<S>>(c.r1), c.X1);
    const fcl::CollisionObject<S> o2(std::make_shared<fcl_disk::Disk<S>>(c.r2), c.X2);
    for (auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
      const char* solver_name = solver == fcl::GST_LIBCCD ? "libccd" : "indep";
      fcl::DistanceRequest<S> request;
      request.enable_signed_distance = true;
      request.enable_nearest_points = true;
      request.gjk_solver_type = solver;
      fcl::DistanceResult<S> result;
      const S returned = fcl::distance(&o1, &o2, request, result);
      const Vector3R p1 = toReal<S>(result.nearest_points[0]),
                     p2 = toReal<S>(result.nearest_points[1]);
      const double pd = -double(result.min_distance);
      if (solver == fcl::GST_INDEP) {
        // FCL's entry, for the indep solver and a negative answer, asks
        // collide() for the depth and reports its contact point as both
        // nearest points (fcl/narrowphase/distance-inl.h); fcl_disk keeps that.
        fcl_disk::DiskContact<S> contact;
        const bool touching = fcl_disk::intersectDisks<S>(c.r1, c.X1, c.r2, c.X2, &contact);
        if (!(touching && std::fabs(pd - pd_ref) <= r.pd_tol &&
              result.nearest_points[0] == contact.pos && result.nearest_points[1] == contact.pos)) {
          std::ostringstream m;
          m << std::setprecision(17) << solver_name << ": min_distance "
            << double(result.min_distance) << " PD_ref " << pd_ref << ", points "
            << result.nearest_points[0].transpose() << " / " << result.nearest_points[1].transpose()
            << ", contact pos " << contact.pos.transpose() << "; " << describe(c);
          signed_log.add(m.str());
        }
      } else {
        const double off1 = double(ref::pointToDisk(p1, r.disk1));
        const double off2 = double(ref::pointToDisk(p2, r.disk2));
        const double chord = double((p1 - p2).norm());
        const double f_chord =
            chord > 0 ? double(ref::referenceF(r.disk1, r.disk2, p1 - p2)) : pd_ref;
        // The chord's direction is known to (2 point_tol) / |p1 - p2| radians and F
        // is Lipschitz with constant <= scale on the sphere.
        const double chord_value_tol =
            r.value_tol + (chord > 0 ? r.scale * 2 * r.point_tol / chord : 0.0);
        if (!(std::fabs(pd - pd_ref) <= r.pd_tol && double(returned) == double(result.min_distance) &&
              off1 <= r.point_tol && off2 <= r.point_tol &&
              std::fabs(chord - pd_ref) <= r.pd_tol + 2 * (r.point_tol - r.pd_tol) &&
              f_chord - pd_ref <= chord_value_tol)) {
          std::ostringstream m;
          m << std::setprecision(17) << solver_name << ": min_distance "
            << double(result.min_distance) << " (returned " << double(returned) << ") PD_ref "
            << pd_ref << ", points off disks " << off1 << " " << off2 << ", |p1 - p2| " << chord
            << ", F_ref((p1 - p2)) " << f_chord << "; " << describe(c);
          signed_log.add(m.str());
        }
        // Where the minimiser is unique, the points are the API's up to the
        // direction's ambiguity (witness points move by <= scale per radian).
        const double point_tol = 2 * r.point_tol + r.scale * u.direction_tol;
        if (unique &&
            !(std::fabs(double(result.min_distance) - double(api.signed_distance)) <= r.pd_tol &&
              double((p1 - toReal<S>(api.p_W1)).norm()) <= point_tol &&
              double((p2 - toReal<S>(api.p_W2)).norm()) <= point_tol)) {
          std::ostringstream m;
          m << std::setprecision(17) << solver_name << ": fcl " << double(result.min_distance)
            << " api " << double(api.signed_distance) << " points "
            << result.nearest_points[0].transpose() << " / " << api.p_W1.transpose() << "; "
            << describe(c);
          same_log.add(m.str());
        }

      }

      fcl::DistanceRequest<S> plain;
      plain.enable_nearest_points = true;
      plain.gjk_solver_type = solver;
      fcl::DistanceResult<S> plain_result;
      const S plain_d = fcl::distance(&o1, &o2, plain, plain_result);
      if (!(plain_d == 0 && plain_result.min_distance == 0)) {
        std::ostringstream m;
        m << solver_name << ": unsigned distance " << double(plain_d) << "; " << describe(c);
        unsigned_log.add(m.str());
      }

      fcl::CollisionRequest<S> creq(1, true);
      creq.gjk_solver_type = solver;
      fcl::CollisionResult<S> cres;
      const std::size_t n = fcl::collide(&o1, &o2, creq, cres);
      if (n != 1 || cres.numContacts() != 1) {
        contact_log.add(std::string(solver_name) + ": " + std::to_string(n) + " contacts; " +
                        describe(c));
        continue;
      }
      const fcl::Contact<S>& contact = cres.getContact(0);
      const Vector3R normal = toReal<S>(contact.normal);
      const double depth = double(contact.penetration_depth);
      const double f_normal = double(ref::referenceF(r.disk1, r.disk2, normal));
      const double touching = Tol<S>::kTouchingRelative * r.length + (r.point_tol - r.pd_tol);
      const double pos1 = double(ref::pointToDisk(toReal<S>(contact.pos), r.disk1));
      const double pos2 = double(ref::pointToDisk(toReal<S>(contact.pos), r.disk2));
      const double normal_angle = angleBetween(normal, toReal<S>(api.direction));
      const bool ok = std::fabs(depth - pd_ref) <= r.pd_tol &&
                      std::fabs(double(normal.norm()) - 1) <= Tol<S>::kUnitDirection &&
                      f_normal - pd_ref <= r.value_tol && pos1 <= touching && pos2 <= touching &&
                      (!unique || normal_angle <= u.direction_tol) &&
                      contact.o1 == o1.collisionGeometry().get() &&
                      contact.o2 == o2.collisionGeometry().get();
      if (!ok) {
        std::ostringstream m;
        m << std::setprecision(17) << solver_name << ": depth " << depth << " PD_ref " << pd_ref
          << ", F_ref(normal) - PD_ref " << f_normal - pd_ref << ", normal "
          << contact.normal.transpose() << " direction " << api.direction.transpose() << " (angle "
          << normal_angle << ", unique " << unique << "), pos off disks " << pos1 << " " << pos2
          << "; " << describe(c);
        contact_log.add(m.str());
      }
    }
  }
}

TEST_P(FamilyTest, ThroughFclDouble) { checkThroughFcl<double>(GetParam()); }
TEST_P(FamilyTest, ThroughFclFloat) { checkThroughFcl<float>(GetParam()); }

INSTANTIATE_TEST_SUITE_P(Penetration, FamilyTest, ::testing::ValuesIn(kFamilies), familyParamName);

// ---- invalid input --------------------------------------------------------------

template <typename S>
void expectAllNaN(const fcl_disk::DiskSignedDistanceResult<S>& r, const std::string& what) {
  EXPECT_TRUE(std::isnan(r.signed_distance)) << what << ": " << r.signed_distance;
  EXPECT_TRUE(r.p_W1.array().isNaN().all()) << what << ": p_W1 " << r.p_W1.transpose();
  EXPECT_TRUE(r.p_W2.array().isNaN().all()) << what << ": p_W2 " << r.p_W2.transpose();
  EXPECT_TRUE(r.direction.array().isNaN().all())
      << what << ": direction " << r.direction.transpose();
}

template <typename S>
void checkInvalidInput() {
  const S nan = std::numeric_limits<S>::quiet_NaN();
  const S inf = std::numeric_limits<S>::infinity();
  // An intersecting pair (chain link), then spoiled one way at a time.
  const fcl::Transform3<S> X1 = poseWithNormal(Vec3::Zero(), Vec3::UnitZ()).cast<S>();
  const fcl::Transform3<S> X2 = poseWithNormal(Vec3(1, 0, 0), Vec3::UnitY()).cast<S>();
  struct Spoiled {
    std::string what;
    S r1, r2;
    fcl::Transform3<S> X1, X2;
  };
  std::vector<Spoiled> cases;
  auto with = [&](std::string what, S r1, S r2, fcl::Transform3<S> A, fcl::Transform3<S> B) {
    cases.push_back({std::move(what), r1, r2, A, B});
  };
  fcl::Transform3<S> bad = X2;
  bad.translation().x() = nan;
  with("NaN translation of disk 2", 1, 1, X1, bad);
  bad = X1;
  bad.linear()(1, 2) = nan;
  with("NaN rotation entry of disk 1", 1, 1, bad, X2);
  bad = X2;
  bad.translation().z() = inf;
  with("infinite translation", 1, 1, X1, bad);
  bad = X2;
  bad.linear() *= S(2);
  with("scaled rotation", 1, 1, X1, bad);
  with("negative radius 1", -1, 1, X1, X2);
  with("negative radius 2", 1, -0.5, X1, X2);
  with("zero radius", 0, 1, X1, X2);
  with("NaN radius", nan, 1, X1, X2);
  for (const Spoiled& s : cases) {
    expectAllNaN(fcl_disk::diskPenetration<S>(s.r1, s.X1, s.r2, s.X2),
                 "diskPenetration: " + s.what);
    expectAllNaN(fcl_disk::signedDiskDistance<S>(s.r1, s.X1, s.r2, s.X2),
                 "signedDiskDistance: " + s.what);
  }
  // Through FCL (a Disk cannot have an invalid radius: NaN poses only): NaN, no crash.
  for (const bool nan_first : {true, false}) {
    fcl::Transform3<S> A = X1, B = X2;
    (nan_first ? A : B).translation().y() = nan;
    const fcl::CollisionObject<S> o1(std::make_shared<fcl_disk::Disk<S>>(S(1)), A);
    const fcl::CollisionObject<S> o2(std::make_shared<fcl_disk::Disk<S>>(S(1)), B);
    for (auto solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
      fcl::DistanceRequest<S> request;
      request.enable_signed_distance = true;
      request.enable_nearest_points = true;
      request.gjk_solver_type = solver;
      fcl::DistanceResult<S> result;
      EXPECT_TRUE(std::isnan(fcl::distance(&o1, &o2, request, result)));
      EXPECT_TRUE(std::isnan(result.min_distance));
      fcl::CollisionRequest<S> creq(1, true);
      creq.gjk_solver_type = solver;
      fcl::CollisionResult<S> cres;
      EXPECT_EQ(fcl::collide(&o1, &o2, creq, cres), 0u);
    }
  }
}

/// Disk pairs in double: (r1, X_W1, r2, X_W2).
using PosedPairs = std::vector<std::tuple<double, fcl::Transform3d, double, fcl::Transform3d>>;

/// diskPenetration on every pair, both orders, within the PD bound of the
/// long-double reference; prints the largest error and the pair it came from.
void expectPenetrationMatchesReference(const PosedPairs& cases, const char* what) {
  int worst_case = -1;
  double worst = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const auto& [r1, X1, r2, X2] = cases[i];
    const auto reference = ref::referencePenetration(r1, X1, r2, X2);
    const double scale = double(reference.scale);
    for (const bool swap : {false, true}) {
      const auto answer = swap ? fcl_disk::diskPenetration(r2, X2, r1, X1)
                               : fcl_disk::diskPenetration(r1, X1, r2, X2);
      const double error = std::abs(-answer.signed_distance - double(reference.pd)) / scale;
      EXPECT_LE(error, Tol<double>::kPdRelative)
          << what << " case " << i << (swap ? " swapped" : "") << ": PD "
          << -answer.signed_distance << " reference " << double(reference.pd);
      if (error > worst) worst = error, worst_case = int(i);
    }
  }
  std::cout << "  " << cases.size() << " " << what << ": largest |PD - PD_ref| / scale " << worst
            << " (case " << worst_case << ")\n";
}

/// Disks of very different sizes, the small one crossing the large one next to
/// its rim (where the large rim passes near the small disk's axis), both
/// orders, against the reference: the search must follow the smaller rim
/// (docs/penetration_depth.md, section 2). The first pose is the one
/// fuzz_disk_intersection found (corpus regression-depth-tiny-disk-on-huge-rim).
TEST(RadiusRatios, SmallDiskAcrossALargeRimMatchesReference) {
  using Pose = fcl::Transform3d;
  PosedPairs cases;
  {
    Pose X1 = Pose::Identity(), X2 = Pose::Identity();
    X1.linear() << 0.67098272989643681, -0.55247692072578025, 0.49452141333423089,
        0.20118130306279841, -0.50627493586560135, -0.83857723115538729, 0.71365836327943344,
        0.6621593021166744, -0.22855371172150973;
    X1.translation() << 0, 0, 0.32251739501953125;
    X2.linear() << 0.77398943515409824, 0.6135323587397401, 0.1565835210010649,
        -0.41431689383755127, 0.67771463495008222, -0.60749023453491036, -0.47883386027999675,
        0.40531582544199773, 0.77874078864255514;
    X2.translation() << -5200.5393027995451, 2783.8549917301411, 3217.621441349921;
    cases.emplace_back(0.084490776062011719, X1, 6719.125, X2);
  }
  fcl_disk_test::Random rng(kSeed + 77);
  constexpr int kRatioCases = 200;
  while (int(cases.size()) < kRatioCases) {
    const double big = 1.0, small = rng.logUniform(1e-6, 1e-1);
    Pose X_big = Pose::Identity(), X_small = Pose::Identity();
    X_big.linear() = rng.rotation();
    X_small.linear() = rng.rotation();
    // The small disk's centre within its radius of a point of the large rim.
    const double angle = rng.uniform(0, 2 * M_PI);
    const Eigen::Vector3d rim = big * (std::cos(angle) * X_big.linear().col(0) +
                                       std::sin(angle) * X_big.linear().col(1));
    X_small.translation() = rim + rng.inBall(small);
    if (!fcl_disk::intersectDisks(small, X_small, big, X_big)) continue;
    cases.emplace_back(small, X_small, big, X_big);
  }
  expectPenetrationMatchesReference(cases, "pairs of radius ratio 1e-6..1e-1 (and 1.3e-5)");
}

/// Perturbed symmetric chain links: disk 2 upright on disk 1's rim (its plane
/// holds disk 1's normal and the radial line; centred r2 from c1 along it, so
/// rim 2 runs through c1 along disk 1's axis), then turned by 1e-8..1e-1 rad
/// about a random axis and moved by 1e-9..1e-2 r1; equal radii (each centre
/// on the other's rim: F is then nearly constant along two arcs of
/// directions) and radius ratios 0.2..5, both orders. A rim point next to the
/// other disk's axis is where Q's roots lose their digits; the search runs
/// with the roles exchanged too, and F is polished by Newton's method on the
/// sphere (docs/penetration_depth.md, section 2). The first pose is the one
/// fuzz_disk_intersection found (corpus regression-depth-rim-next-to-the-axis).
TEST(PerturbedSymmetricChainLinks, MatchReference) {
  using Pose = fcl::Transform3d;
  PosedPairs cases;
  {
    Pose X1 = Pose::Identity(), X2 = Pose::Identity();
    X1.translation() << -0.125, 0, 0;
    X2.linear() << -0.99996936344906251, -0.0078276387644278991, 1.5318275468547554e-05,
        1.5318275468547554e-05, -0.0039138193822136902, -0.99999234086226552,
        0.0078276387644278991, -0.99996170431132847, 0.0039138193822141343;
    cases.emplace_back(0.125, X1, 0.125, X2);
  }
  fcl_disk_test::Random rng(kSeed + 79);
  constexpr int kLinkCases = 600;
  while (int(cases.size()) < kLinkCases) {
    const double r1 = rng.uniform(0.3, 2.0);
    const double r2 = cases.size() % 2 == 0 ? r1 : r1 * rng.logUniform(0.2, 5.0);
    Pose X1 = Pose::Identity(), X2 = Pose::Identity();
    X1.linear() = rng.rotation();
    X1.translation() = rng.inBall(1.0);
    Eigen::Matrix3d upright;  // in-plane axes: disk 1's x and normal
    upright.col(0) = X1.linear().col(0);
    upright.col(1) = X1.linear().col(2);
    upright.col(2) = -X1.linear().col(1);
    const double turn = rng.logUniform(1e-8, 1e-1);
    X2.linear() = Eigen::AngleAxisd(turn, rng.unitVector()).toRotationMatrix() * upright;
    X2.translation() = X1.translation() + r2 * X1.linear().col(0) +
                       rng.logUniform(1e-9, 1e-2) * r1 * rng.unitVector();
    if (!fcl_disk::intersectDisks(r1, X1, r2, X2)) continue;
    cases.emplace_back(r1, X1, r2, X2);
  }
  expectPenetrationMatchesReference(cases, "perturbed symmetric chain links");
}

/// Pairs symmetric under a reflection (disk 1 in the plane x = 0, disk 2
/// centred in it with its normal in it too): Q is even about the rim angle
/// on the symmetry plane and may touch zero there (a double root) exactly
/// where Bernstein subdivision halves its chart (docs/penetration_depth.md,
/// section 2), or have a double root at the end of an interval that brackets a
/// simple root (disks sharing an in-plane axis). The first poses are the ones
/// fuzz_disk_intersection found (corpus regression-depth-symmetric-double-root,
/// regression-depth-root-beside-a-double-root), the others random, both orders.
TEST(SymmetricPairs, DoubleRootsOnTheSymmetryPlaneMatchReference) {
  using Pose = fcl::Transform3d;
  PosedPairs cases;
  Pose X1 = Pose::Identity();
  X1.linear() << 0, 0, 1, 1, 0, 0, 0, 1, 0;  // normal +x
  {
    Pose X2 = Pose::Identity();
    X2.linear() << 0, 1, 0, 0, 0, 1, 1, 0, 0;  // normal +y
    X2.translation() << 0, 0.28241230364423245, -1.9799604264259688;
    cases.emplace_back(2.0, X1, 0.5, X2);
  }
  {
    // regression-depth-root-beside-a-double-root: the disks share an in-plane
    // axis, the small one centred on the large one's rim along it; Q is even,
    // with a double root at the end of the interval that brackets a simple one.
    Pose A = Pose::Identity(), B = Pose::Identity();
    A.linear() << 0.32854471452498946, 0.60876451032984147, 0.72212474096970358,
        -0.84146034107622192, -0.15857930288342859, 0.51652405470887242, 0.42895555125628276,
        -0.77734057893556174, 0.46015080070183978;
    A.translation() << 1, 1, -3.0636321753263474e-05;
    B.linear() << 0.32854471452498946, -0.43392982979449518, -0.83890599793553333,
        -0.84146034107622192, 0.26891771093622402, -0.46864459789984741, 0.42895555125628276,
        0.85987683278440608, -0.27678325001176751;
    B.translation() << 1.6570894290499789, -0.68292068215244384, 0.85788046619081226;
    cases.emplace_back(2.0, A, 0.125, B);
  }
  fcl_disk_test::Random rng(kSeed + 78);
  constexpr int kSymmetricCases = 400;
  while (int(cases.size()) < kSymmetricCases / 2) {
    // Sharing an in-plane axis u, centres apart along it.
    const double r1 = rng.uniform(0.3, 2.0), r2 = rng.uniform(0.05, 2.0);
    Pose A = Pose::Identity(), B = Pose::Identity();
    A.linear() = rng.rotation();
    B.linear() = A.linear() * Eigen::AngleAxisd(rng.uniform(0, 2 * M_PI), Eigen::Vector3d::UnitX())
                                  .toRotationMatrix();
    A.translation() = rng.inBall(1.0);
    B.translation() = A.translation() + rng.uniform(0, r1 + r2) * A.linear().col(0);
    if (!fcl_disk::intersectDisks(r1, A, r2, B)) continue;
    cases.emplace_back(r1, A, r2, B);
  }
  while (int(cases.size()) < kSymmetricCases) {
    const double r1 = rng.uniform(0.3, 2.0), r2 = rng.uniform(0.3, 2.0);
    const double tilt = rng.uniform(0, 2 * M_PI);
    // Disk 2's normal in the symmetry plane x = 0; its in-plane axes x and the rest.
    const Eigen::Vector3d n2(0, std::cos(tilt), std::sin(tilt));
    const Eigen::Vector3d u2 = Eigen::Vector3d::UnitX(), v2 = n2.cross(u2);
    Pose X2 = Pose::Identity();
    X2.linear().col(0) = u2;
    X2.linear().col(1) = v2;
    X2.linear().col(2) = n2;
    X2.translation() << 0, rng.uniform(-2, 2), rng.uniform(-2, 2);
    if (!fcl_disk::intersectDisks(r1, X1, r2, X2)) continue;
    cases.emplace_back(r1, X1, r2, X2);
  }
  expectPenetrationMatchesReference(cases, "symmetric pairs");
}

/// Nearly parallel (or antiparallel) overlapping disks, tilted 1e-4..1e-1 rad,
/// centres apart in the plane: minimisers next to the normals, and double roots
/// of Q whose rounding-level sign or slope sits beside a simple root. The first
/// poses are the ones fuzz_disk_intersection found (corpus
/// regression-depth-noise-sign-beside-a-double-root,
/// regression-depth-noise-slope-at-a-double-root), both orders.
TEST(NearlyParallelPairs, MatchReference) {
  using Pose = fcl::Transform3d;
  PosedPairs cases;
  {
    Pose A = Pose::Identity(), B = Pose::Identity();
    A.linear() << -0.98757087650754283, -0.12263991189188413, -0.098301657591698066,
        0.13839252542346403, -0.38202058194234123, -0.91373288431540611, 0.074506863986081306,
        -0.91598020010455816, 0.39424484807714788;
    A.translation() << 4.3852560338564217e-07, 2.384185791015625e-07, 0;
    B.linear() << -0.98463303826300386, 0.14412448397799871, 0.098620044002436277,
        0.14674818699744493, 0.37669818551179618, 0.91463842399337458, 0.094671799253683853,
        0.91505552298764725, -0.39205948563435356;
    B.translation() << 0.73847521722285625, -0.11006090182950461, -0.071003849440262889;
    cases.emplace_back(1.0, A, 0.75, B);
    // regression-depth-noise-slope-at-a-double-root: the same kind, where Q's
    // derivative is at rounding level at a double root that ends an interval.
    A.linear() << -0.98637267101094284, -0.12504822563495493, -0.10692004091042548,
        0.14231943926177043, -0.32244547707262261, -0.93582802454490721, 0.082547750368819228,
        -0.93829198844547201, 0.33584819982856706;
    B.linear() << -0.98639783051277019, 0.12468575316134521, 0.1071110774770177,
        0.14218299320681818, 0.3202261343179163, 0.93661049499914995, 0.082482218704697199,
        0.93909993390394353, -0.33359855775941055;
    B.translation() << 0.739798811410181, -0.10663700648653449, -0.061861664028522723;
    cases.emplace_back(1.0, A, 0.75, B);
  }
  fcl_disk_test::Random rng(kSeed + 79);
  constexpr int kNearlyParallelCases = 300;
  while (int(cases.size()) < kNearlyParallelCases) {
    const double r1 = rng.uniform(0.3, 2.0), r2 = rng.uniform(0.3, 2.0);
    Pose A = Pose::Identity(), B = Pose::Identity();
    A.linear() = rng.rotation();
    const Eigen::Vector3d axis = A.linear().col(0) * std::cos(rng.uniform(0, 2 * M_PI)) +
                                 A.linear().col(1) * std::sin(rng.uniform(0, 2 * M_PI));
    const double tilt = rng.logUniform(1e-4, 1e-1) + (rng.chance(0.5) ? M_PI : 0.0);
    B.linear() = Eigen::AngleAxisd(tilt, axis.normalized()).toRotationMatrix() * A.linear() *
                 Eigen::AngleAxisd(rng.uniform(0, 2 * M_PI), Eigen::Vector3d::UnitZ())
                     .toRotationMatrix();
    const double offset = rng.uniform(0, r1 + r2);
    const double angle = rng.uniform(0, 2 * M_PI);
    B.translation() = offset * (std::cos(angle) * A.linear().col(0) + std::sin(angle) * A.linear().col(1)) +
                      rng.uniform(-1e-2, 1e-2) * A.linear().col(2);
    if (!fcl_disk::intersectDisks(r1, A, r2, B)) continue;
    cases.emplace_back(r1, A, r2, B);
  }
  expectPenetrationMatchesReference(cases, "nearly parallel pairs");
}

// Rims that touch at one point with tangents 1e-8..1 rad apart, the disks on
// either side of the plane through that point normal to disk 1's radial (PD =
// 0): Q's root there is a near-double root, known to ~sqrt(eps), and the
// direction t1 x t2 it gives is off by far more than the 1e-12 promise allows
// (fuzz_disk_intersection findings, regression-depth-rims-touching-nearly-tangent
// and regression-touching-rims-nearly-parallel-tangents, are the first cases:
// depths 2.6e-7 and 2.1e-8 along n1 where F is 1e-17 along t1 x t2).
TEST(RimsTouchingNearlyTangent, MatchReference) {
  using Pose = fcl::Transform3d;
  PosedPairs cases;
  {
    Pose A = Pose::Identity(), B = Pose::Identity();
    B.linear() << -0.79999755860120048, 0.0031249904632859394, -0.59999511720240106,
        -0.0015624952316429699, -0.9999938965030013, -0.0031249904632859394,
        -0.60000122069939976, -0.0015624952316429699, 0.79999755860120059;
    B.translation() << 1.5999938676925824, 0.0023223657178145728, 0.45000218371555556;
    cases.emplace_back(1.0, A, 0.75, B);
    // regression-touching-rims-nearly-parallel-tangents: the same rotation,
    // touching to rounding where commonPoint finds no common point (depth
    // 2.1e-8 along n1 before the exact distance's nearest points stood in).
    B.translation() << 1.5999911876051804, 0.0028976109847180017, 0.45000242071205171;
    cases.emplace_back(1.0, A, 0.75, B);
  }
  fcl_disk_test::Random rng(kSeed + 83);
  constexpr int kTouchingCases = 300;
  while (int(cases.size()) < kTouchingCases) {
    // In disk 1's frame: the shared rim point p = (1, 0, 0) r1, rim 1's tangent
    // y, rim 2's tangent t2 turned from it by `turn` about x, and disk 2 on the
    // far side of x = r1 (its centre along d, d.x > 0, d normal to t2): disk 1
    // lies in x <= r1, disk 2 in x >= r1, and p is their only common point.
    const double r1 = rng.uniform(0.3, 2.0), r2 = rng.uniform(0.1, 3.0);
    const double turn = (rng.chance(0.5) ? 1.0 : -1.0) * rng.logUniform(1e-8, 1.0);
    const double lean = rng.uniform(-1.4, 1.4);
    const Eigen::Vector3d t2(0.0, std::cos(turn), std::sin(turn));
    const Eigen::Vector3d d = std::cos(lean) * Eigen::Vector3d::UnitX() +
                              std::sin(lean) * Eigen::Vector3d::UnitX().cross(t2);
    Eigen::Matrix3d local;  // disk 2's axes: -d (towards p), t2, their normal
    local.col(0) = -d;
    local.col(1) = t2;
    local.col(2) = (-d).cross(t2);
    const Pose motion = Pose(Eigen::Translation3d(rng.inBall(2.0))) * Pose(rng.rotation());
    Pose A = motion, B = motion;
    B.linear() = motion.linear() * local;
    B.translation() = motion * Eigen::Vector3d(r1 * Eigen::Vector3d::UnitX() + r2 * d);
    cases.emplace_back(r1, A, r2, B);
  }
  expectPenetrationMatchesReference(cases, "rims touching nearly tangent");
}

TEST(InvalidInput, NaNAndNoCrashDouble) { checkInvalidInput<double>(); }
TEST(InvalidInput, NaNAndNoCrashFloat) { checkInvalidInput<float>(); }

}  // namespace

// Deterministic generators of disk-pair configuration families, for tests and
// the speed/error report. Header-only; Eigen and the standard library only.
//
// Every case is built in a "family frame" F, where disk 1 is usually centred at
// the origin with normal +z and the defining property (coplanar, coaxial,
// touching, ...) holds exactly in long double; then a random common rigid motion
// (rotation Q, translation t) is applied so that nothing is axis-aligned by
// accident, and the poses are rounded once to S.
//
// What "exact" means after rounding to S (eps = epsilon of S):
// - Normals: if both rotations in F have third column exactly +-e_z (coplanar,
//   coaxial families), the world normals are Q's third column (negated) computed
//   with exact zeros, so the stored normals are BIT-IDENTICAL (or exact negatives).
// - Everything else (centres, other rotation entries, perpendicularity, contact,
//   tilt angles) holds to the rounding of the stored pose entries: each centre
//   is off by <= eps |c_i| and each rotation entry by <= eps/2. Moving a disk
//   by delta (Hausdorff) changes the distance by <= delta, so the distance of the
//   stored poses differs from known_distance by at most poseRoundingBound().
// - Radii are rounded to S first and the geometry is built from the rounded
//   values, so they add nothing.
// Random numbers: std::mt19937_64 (its output sequence is fixed by the
// standard) with our own uniform/normal transforms (the std distributions are
// implementation-defined), so a (family, count, seed) triple gives the same
// cases with every standard library.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace fcl_disk_families {

using Real = long double;
using Vector3R = Eigen::Matrix<Real, 3, 1>;
using Matrix3R = Eigen::Matrix<Real, 3, 3>;

/// The families. "Exact" below is in the family frame; the stored poses are
/// within poseRoundingBound() of it (see the file comment) unless stated.
enum class Family {
  /// Centres uniform in a ball of radius 3, radii 0.2-1.5, uniform random
  /// orientations (some pairs intersect). known_distance: none.
  random,
  /// Tilt 1e-12..1e-3 rad (log-uniform) between the normals, in four sub-kinds:
  /// "face" (projections overlap, disk 2's lowest rim point over disk 1's
  /// interior at d = 1e-10..1, known), "rim_rim" (projections apart, KKT
  /// construction, known), "crossing" (disk 2's projection inside disk 1 and
  /// plane 1 cutting disk 2 within +-0.9 of its height range: distance 0),
  /// "rims_crossing" (KKT construction with the separation within 1e-6..1e-2
  /// rad of disk 1's normal and closer still to disk 2's: the rims cross in
  /// projection, a thin lens, and the optimum is at one of its corners,
  /// d = 1e-12..1e-3 times the larger radius, radius ratio up to 100, known). The
  /// stored tilt matches the nominal one to ~eps absolute; in float, tilts below
  /// ~1e-7 are swamped by rounding (the stored disks are parallel or tilted by
  /// rounding), which the known distances' rounding bound accounts for.
  near_parallel,
  /// Same plane: "apart" (gap 1e-9..3), "touching" (D = r1 + r2), "overlapping",
  /// "inside" and "concentric". Normals bit-identical or exact negatives;
  /// centres in the common plane to the rounding of their coordinates.
  coplanar,
  /// Parallel or opposite normals (bit-identical / exact negatives), centres on
  /// the common axis (to rounding), height 0 (concentric coplanar) or +-1e-9..3;
  /// known_distance = |h|.
  coaxial,
  /// Distance 0: "rim_on_face" (disk 2's extreme rim point on disk 1's face,
  /// tilt >= 0.05 rad) and "rim_on_rim" (disk 2's plane contains rim 1's
  /// tangent at the contact point, so the disks meet there only). After rounding
  /// the stored disks touch, overlap or miss by up to poseRoundingBound().
  touching,
  /// Chain link: disk 2's plane contains a chord line of disk 1 and disk 2's
  /// chord on it straddles disk 1's rim (each disk crosses the other's plane
  /// inside the other); normals exactly perpendicular ("perpendicular") or
  /// 0-0.4 rad off ("tilted"). The chords overlap by >= 0.2 of disk 2's chord, so
  /// the stored disks intersect too: distance exactly 0.
  interlocked,
  /// n2 . n1 = 0 (to rounding), separated: "face" (disk 2 standing over disk 1's
  /// interior, known), "rim_rim" (KKT construction, known), "beside" (disk 2
  /// crossing plane 1 outside disk 1, or not reaching it; no known distance).
  perpendicular,
  /// Optimum rim-rim by construction: p on rim 1, w in disk 1's normal cone at p
  /// with a positive radial part, q = p + d w, disk 2 placed so -w is in its
  /// normal cone at q (mutual KKT => optimal); d = 1e-4..2, known.
  rim_rim,
  /// r2 / r1 = 1e-6..1e6 (log-uniform; slots swapped half of the time): KKT
  /// rim-rim and face constructions (known, d = 1e-6..1 times the larger
  /// radius) and random placements within 1.3 (r1 + r2).
  radius_ratio,
  /// The random family translated by up to 1e6 (half at 0.5e6..1e6, half
  /// log-uniform 1..1e6). The centres are stored rounded to ulp(1e6) = 1.2e-10
  /// (double) / 0.06 (float): the disks are those stored poses.
  far_from_origin,
  /// Three fixed shapes (rim-rim, rim over face, parallel faces; radii 1 and
  /// 0.75) at separations 1e-12..1e6 (log-uniform), known. In float,
  /// separations below ~1e-6 are below the pose rounding.
  separation_scale,
  /// A tiny disk next to a large one's rim: r_small / r_large = 1e-9..1e-6
  /// (log-uniform; the small disk in slot 2 or 1, alternately), the KKT rim-rim
  /// construction with d = 1e-3..10 times the small radius (known), the
  /// separation psi = -1.4..1.4 rad out of the large disk's plane, random
  /// orientation of the small disk.
  tiny_next_to_rim,
  /// Nearly parallel disks side by side, rims almost touching: tilt 1e-8..1e-2
  /// rad (log-uniform) between the normals, the KKT rim-rim construction with
  /// the separation within 0.1 rad of disk 1's plane and a rim gap of 1e-6..1
  /// times the larger radius (known), radii 0.3..1.5.
  side_by_side,
};

inline const std::vector<Family>& allFamilies() {
  static const std::vector<Family> families = {
      Family::random,      Family::near_parallel, Family::coplanar,     Family::coaxial,
      Family::touching,    Family::interlocked,   Family::perpendicular, Family::rim_rim,
      Family::radius_ratio, Family::far_from_origin, Family::separation_scale,
      Family::tiny_next_to_rim, Family::side_by_side};
  return families;
}

inline const char* familyName(Family f) {
  switch (f) {
    case Family::random: return "random";
    case Family::near_parallel: return "near_parallel";
    case Family::coplanar: return "coplanar";
    case Family::coaxial: return "coaxial";
    case Family::touching: return "touching";
    case Family::interlocked: return "interlocked";
    case Family::perpendicular: return "perpendicular";
    case Family::rim_rim: return "rim_rim";
    case Family::radius_ratio: return "radius_ratio";
    case Family::far_from_origin: return "far_from_origin";
    case Family::separation_scale: return "separation_scale";
    case Family::tiny_next_to_rim: return "tiny_next_to_rim";
    case Family::side_by_side: return "side_by_side";
  }
  return "?";
}

/// One disk pair. known_distance is the exact distance of the configuration in
/// the family frame (before rounding the poses to S), or NaN when the
/// construction does not determine it.
template <typename S>
struct DiskPairCase {
  std::string name;  ///< "family/subkind/index"
  S r1{1};
  Eigen::Transform<S, 3, Eigen::Isometry> X_W1{Eigen::Transform<S, 3, Eigen::Isometry>::Identity()};
  S r2{1};
  Eigen::Transform<S, 3, Eigen::Isometry> X_W2{Eigen::Transform<S, 3, Eigen::Isometry>::Identity()};
  Real known_distance{std::numeric_limits<Real>::quiet_NaN()};

  bool hasKnownDistance() const { return !std::isnan(known_distance); }
};

/// r1 + r2 + |c1 - c2|: the length the solvers' guarantees are relative to
/// (exact_distance.h), with no floor, so errors are judged relative at every
/// length scale.
template <typename S>
double sceneScale(const DiskPairCase<S>& c) {
  const double centre_gap =
      (c.X_W2.translation().template cast<double>() - c.X_W1.translation().template cast<double>())
          .norm();
  return double(c.r1) + double(c.r2) + centre_gap;
}

/// Bound on |distance(stored poses) - known_distance| from rounding the poses to
/// S: each centre moves by <= eps |c| (sqrt(3)/2 ulp per coordinate, rounded
/// up), each rotation by <= 1.5 eps in Frobenius norm (9 entries, 1/2 ulp each,
/// entries <= 1), which moves rim points by <= 1.5 eps r; re-orthonormalising
/// such a rotation (the reference does) moves it by about as much again. The
/// distance is 1-Lipschitz in each disk's Hausdorff displacement. Factor 2 spare.
template <typename S>
double poseRoundingBound(const DiskPairCase<S>& c) {
  const double eps = std::numeric_limits<S>::epsilon();
  const double c1 = c.X_W1.translation().template cast<double>().norm();
  const double c2 = c.X_W2.translation().template cast<double>().norm();
  return 2 * eps * (c1 + c2 + 3 * (double(c.r1) + double(c.r2)));
}

namespace family_detail {

/// Portable random source: mt19937_64 plus fixed transforms.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}
  /// Uniform in [0, 1) with 53 random bits.
  Real uniform01() { return Real(engine_() >> 11) * 0x1.0p-53L; }
  Real uniform(Real lo, Real hi) { return lo + (hi - lo) * uniform01(); }
  Real logUniform(Real lo, Real hi) {
    return std::exp(uniform(std::log(lo), std::log(hi)));
  }
  Real sign() { return (engine_() >> 63) ? Real(1) : Real(-1); }
  /// Standard normal by Box-Muller (the std distribution is implementation-defined).
  Real normal() {
    const Real u1 = 1 - uniform01();  // (0, 1]
    const Real u2 = uniform01();
    return std::sqrt(-2 * std::log(u1)) * std::cos(2 * kPi * u2);
  }
  Vector3R unitVector() {
    for (;;) {
      Vector3R v(normal(), normal(), normal());
      const Real len = v.norm();
      if (len > Real(1e-6)) return v / len;
    }
  }
  /// Uniform point in the ball of the given radius.
  Vector3R inBall(Real radius) { return radius * std::cbrt(uniform01()) * unitVector(); }
  /// Uniformly distributed rotation (normalised Gaussian quaternion).
  Matrix3R rotation() {
    Eigen::Quaternion<Real> q(normal(), normal(), normal(), normal());
    q.normalize();
    return q.toRotationMatrix();
  }
  Real angle() { return uniform(0, 2 * kPi); }

  static constexpr Real kPi = 3.141592653589793238462643383279502884L;

 private:
  std::mt19937_64 engine_;
};

/// Rotation about z by alpha, with exact zeros in its third row and column.
inline Matrix3R rotZ(Real alpha) {
  Matrix3R m = Matrix3R::Zero();
  m(0, 0) = std::cos(alpha);
  m(0, 1) = -std::sin(alpha);
  m(1, 0) = std::sin(alpha);
  m(1, 1) = std::cos(alpha);
  m(2, 2) = 1;
  return m;
}

/// diag(1, -1, -1): flips the normal exactly (a rotation by pi about x).
inline Matrix3R flipNormal() { return Eigen::Vector3<Real>(1, -1, -1).asDiagonal(); }

/// Rotation with the given unit normal as third column and a random spin.
inline Matrix3R frameWithNormal(const Vector3R& n, Rng& rng) {
  const Vector3R helper = std::fabs(n.x()) < Real(0.6) ? Vector3R::UnitX() : Vector3R::UnitY();
  const Vector3R u = (helper - n.dot(helper) * n).normalized();
  Matrix3R m;
  m.col(0) = u;
  m.col(1) = n.cross(u);
  m.col(2) = n;
  return m * rotZ(rng.angle());
}

/// Rotation taking +z to a direction tilted by `tilt` about a random horizontal
/// axis, with a random spin about its own normal. Built from sin/cos of the tilt
/// so a 1e-12 tilt is exact to long double precision.
inline Matrix3R tiltedFrame(Real tilt, Rng& rng) {
  const Real axis_angle = rng.angle();
  const Vector3R axis(std::cos(axis_angle), std::sin(axis_angle), 0);
  return Eigen::AngleAxis<Real>(tilt, axis).toRotationMatrix() * rotZ(rng.angle());
}

/// Projection of unit vector w onto the plane of frame R, from in-plane
/// components (accurate when w is nearly parallel to the normal).
inline Vector3R inPlane(const Matrix3R& R, const Vector3R& w) {
  return R.col(0).dot(w) * R.col(0) + R.col(1).dot(w) * R.col(1);
}

/// Family-frame description of a case before the common motion.
struct LocalPair {
  Real r1{1};
  Matrix3R R1{Matrix3R::Identity()};
  Vector3R c1{Vector3R::Zero()};
  Real r2{1};
  Matrix3R R2{Matrix3R::Identity()};
  Vector3R c2{Vector3R::Zero()};
  Real known{std::numeric_limits<Real>::quiet_NaN()};
};

template <typename S>
Real roundedRadius(Real r) {
  return static_cast<Real>(static_cast<S>(r));
}

/// Applies the common motion (Q, t) and rounds once to S.
template <typename S>
DiskPairCase<S> finish(const std::string& name, const LocalPair& local, const Matrix3R& Q,
                       const Vector3R& t) {
  DiskPairCase<S> c;
  c.name = name;
  c.r1 = static_cast<S>(local.r1);
  c.r2 = static_cast<S>(local.r2);
  const Matrix3R R1 = Q * local.R1;
  const Matrix3R R2 = Q * local.R2;
  c.X_W1.linear() = R1.cast<S>();
  c.X_W1.translation() = (Q * local.c1 + t).cast<S>();
  c.X_W2.linear() = R2.cast<S>();
  c.X_W2.translation() = (Q * local.c2 + t).cast<S>();
  c.known_distance = local.known;
  return c;
}

/// Rim-rim optimum by construction. Disk 1: centre 0, normal +z, radius r1.
/// p = rim point at angle a; w = cos(psi) rho1 + sin(psi) z (unit, in disk 1's
/// normal cone at p because cos(psi) > 0); q = p + d w. Disk 2 has normal n2
/// and centre q - r2 rho2, rho2 = P2(-w)/|P2 w|, so -w is in disk 2's normal
/// cone at q. Mutual KKT conditions of a convex problem => (p, q) is optimal and
/// the distance is d. Returns false when |P2 w| < min_in_plane (w ~ n2; rho2's
/// direction, hence c2, has a relative error of ~1e-19 / |P2 w| in long double).
/// w = cos(psi) rho1 + sin(psi) z, rho1 = (cos a, sin a, 0): the separation
/// direction of rimRimPair, in disk 1's normal cone at its rim point at angle a.
inline Vector3R rimRimSeparation(Real a, Real psi) {
  return Vector3R(std::cos(psi) * std::cos(a), std::cos(psi) * std::sin(a), std::sin(psi));
}

inline bool rimRimPair(Real r1, Real r2, Real d, Real a, Real psi, const Matrix3R& R2,
                       LocalPair* out, Real min_in_plane = Real(0.05)) {
  const Vector3R rho1(std::cos(a), std::sin(a), 0);
  const Vector3R p = r1 * rho1;
  const Vector3R w = rimRimSeparation(a, psi);
  const Vector3R minus_w_in_plane = inPlane(R2, -w);
  const Real len = minus_w_in_plane.norm();
  if (len < min_in_plane) return false;
  out->r1 = r1;
  out->R1 = Matrix3R::Identity();
  out->c1.setZero();
  out->r2 = r2;
  out->R2 = R2;
  out->c2 = p + d * w - r2 * (minus_w_in_plane / len);
  out->known = d;
  return true;
}

/// Rim point of disk 2 over disk 1's face, by construction: disk 2 (frame R2,
/// not parallel to +z) has its extreme rim point towards disk 1's plane at
/// foot + side d z, with foot inside disk 1 and all of disk 2 on that side.
/// Optimal by the KKT conditions (interior point of disk 1: normal cone +-z).
inline LocalPair faceRimPair(Real r1, Real r2, Real d, const Vector3R& foot, Real side,
                             const Matrix3R& R2) {
  const Vector3R toward_up = inPlane(R2, Vector3R::UnitZ());
  LocalPair local;
  local.r1 = r1;
  local.r2 = r2;
  local.R2 = R2;
  // Extreme point along -side z is c2 - side r2 P2 z / |P2 z|.
  local.c2 = foot + side * d * Vector3R::UnitZ() + side * r2 * toward_up.normalized();
  local.known = d;
  return local;
}

/// Random point inside the disk of radius r about the origin in the xy plane,
/// at most `fraction` of the radius from the centre.
inline Vector3R pointInDisk(Real r, Real fraction, Rng& rng) {
  const Real rho = r * fraction * std::sqrt(rng.uniform01());
  const Real phi = rng.angle();
  return Vector3R(rho * std::cos(phi), rho * std::sin(phi), 0);
}

/// A random (non-parallel to z) frame: tilt in [min_tilt, pi - min_tilt].
inline Matrix3R frameTiltedAtLeast(Real min_tilt, Rng& rng) {
  for (;;) {
    const Matrix3R R = rng.rotation();
    const Real sin_tilt = std::hypot(R(0, 2), R(1, 2));
    if (sin_tilt >= std::sin(min_tilt)) return R;
  }
}

inline LocalPair randomPair(Rng& rng) {
  LocalPair local;
  local.r1 = rng.uniform(Real(0.2), Real(1.5));
  local.r2 = rng.uniform(Real(0.2), Real(1.5));
  local.R1 = rng.rotation();
  local.R2 = rng.rotation();
  local.c1 = rng.inBall(3);
  local.c2 = rng.inBall(3);
  return local;
}

template <typename S>
LocalPair roundRadii(LocalPair local) {
  // Callers construct with already-rounded radii; this guards the rest.
  local.r1 = roundedRadius<S>(local.r1);
  local.r2 = roundedRadius<S>(local.r2);
  return local;
}

template <typename S>
void makeNearParallel(int i, Rng& rng, LocalPair* local, std::string* kind) {
  const Real tilt = rng.logUniform(Real(1e-12), Real(1e-3));
  const Real r1 = roundedRadius<S>(rng.uniform(Real(0.3), Real(1.5)));
  const Matrix3R R2 = tiltedFrame(tilt, rng);
  switch (i % 4) {
    case 0: {  // overlapping projections, separated: face of 1 vs lowest rim point of 2
      const Real r2 = roundedRadius<S>(rng.uniform(Real(0.3), Real(1.5)));
      const Real d = rng.logUniform(Real(1e-10), Real(1));
      *local = faceRimPair(r1, r2, d, pointInDisk(r1, Real(0.95), rng), rng.sign(), R2);
      *local = roundRadii<S>(*local);
      *kind = "face";
      break;
    }
    case 1: {  // projections apart: rim-rim with almost parallel normals
      const Real r2 = roundedRadius<S>(rng.uniform(Real(0.3), Real(1.5)));
      const Real d = rng.logUniform(Real(1e-10), Real(1));
      while (!rimRimPair(r1, r2, d, rng.angle(), rng.uniform(Real(-1.2), Real(1.2)), R2, local)) {
      }
      *kind = "rim_rim";
      break;
    }
    case 3: {  // rims crossing in projection: the optimum at a corner of their thin lens
      // w = sin(beta) rho1 +- cos(beta) z is in disk 1's normal cone at its rim
      // point; n2 is +-w turned by gamma <= beta, so |P2 w| = sin(gamma) is small
      // and disk 2's centre lands across rim 1 from p (the projections overlap).
      const Real r2 = roundedRadius<S>(r1 * rng.logUniform(Real(0.01), Real(1)));
      const Real beta = rng.logUniform(Real(1e-6), Real(1e-2));
      const Real gamma = std::max(Real(1e-6), beta * rng.logUniform(Real(1e-4), Real(1)));
      const Real d = std::max(r1, r2) * rng.logUniform(Real(1e-12), Real(1e-3));
      const Real a = rng.angle();
      const Real psi = rng.sign() * (Rng::kPi / 2 - beta);
      const Vector3R w = rimRimSeparation(a, psi);
      const Vector3R axis = w.cross(rng.unitVector()).normalized();
      const Vector3R n2 = rng.sign() * (Eigen::AngleAxis<Real>(gamma, axis) * w);
      // Always built: |P2 w| = sin(gamma) >= sin(1e-6) is above the 0.5e-6 minimum.
      rimRimPair(r1, r2, d, a, psi, frameWithNormal(n2, rng), local, Real(0.5e-6));
      if (rng.uniform01() < 0.5) {  // the small disk first, as often as second
        std::swap(local->r1, local->r2);
        std::swap(local->R1, local->R2);
        std::swap(local->c1, local->c2);
      }
      *kind = "rims_crossing";
      break;
    }
    default: {  // crossing: disk 2's projection inside disk 1, plane 1 cuts disk 2
      const Real r2 = roundedRadius<S>(r1 * rng.uniform(Real(0.1), Real(0.8)));
      local->r1 = r1;
      local->r2 = r2;
      local->R2 = R2;
      const Vector3R offset = pointInDisk((r1 - r2), Real(0.9), rng);
      // Disk 2 spans heights c2z +- r2 sin(tilt); |c2z| <= 0.9 of that crosses z = 0.
      local->c2 = offset + rng.uniform(Real(-0.9), Real(0.9)) * r2 * std::sin(tilt) *
                               Vector3R::UnitZ();
      local->known = 0;
      *kind = "crossing";
      break;
    }
  }
}

template <typename S>
void makeCoplanar(int i, Rng& rng, LocalPair* local, std::string* kind) {
  local->r1 = roundedRadius<S>(rng.uniform(Real(0.2), Real(1.5)));
  local->r2 = roundedRadius<S>(rng.uniform(Real(0.2), Real(1.5)));
  local->R1 = rotZ(rng.angle());
  local->R2 = rotZ(rng.angle());
  if (rng.uniform01() < 0.5) local->R2 = local->R2 * flipNormal();
  const Real sum = local->r1 + local->r2;
  const Real diff = std::fabs(local->r1 - local->r2);
  Real centre_gap = 0;
  switch (i % 4) {
    case 0: centre_gap = sum + rng.logUniform(Real(1e-9), Real(3)); *kind = "apart"; break;
    case 1: centre_gap = sum; *kind = "touching"; break;
    case 2: centre_gap = rng.uniform(diff, sum); *kind = "overlapping"; break;
    default:
      centre_gap = (i % 8 == 3) ? 0 : rng.uniform(0, diff);
      *kind = centre_gap == 0 ? "concentric" : "inside";
      break;
  }
  const Real beta = rng.angle();
  local->c2 = centre_gap * Vector3R(std::cos(beta), std::sin(beta), 0);
  local->known = std::max(Real(0), centre_gap - sum);
}

template <typename S>
void makeCoaxial(int i, Rng& rng, LocalPair* local, std::string* kind) {
  local->r1 = roundedRadius<S>(rng.uniform(Real(0.2), Real(1.5)));
  local->r2 = (i % 5 == 1) ? local->r1 : roundedRadius<S>(rng.uniform(Real(0.2), Real(1.5)));
  local->R1 = rotZ(rng.angle());
  local->R2 = rotZ(rng.angle());
  if (rng.uniform01() < 0.5) local->R2 = local->R2 * flipNormal();
  const Real height = (i % 4 == 0) ? 0 : rng.sign() * rng.logUniform(Real(1e-9), Real(3));
  local->c2 = Vector3R(0, 0, height);
  local->known = std::fabs(height);
  *kind = height == 0 ? "concentric_coplanar" : "stack";
}

template <typename S>
void makeTouching(int i, Rng& rng, LocalPair* local, std::string* kind) {
  const Real r1 = roundedRadius<S>(rng.uniform(Real(0.2), Real(1.5)));
  const Real r2 = roundedRadius<S>(rng.uniform(Real(0.2), Real(1.5)));
  if (i % 2 == 0) {
    *local = faceRimPair(r1, r2, 0, pointInDisk(r1, Real(0.95), rng), rng.sign(),
                         frameTiltedAtLeast(Real(0.05), rng));
    *kind = "rim_on_face";
    return;
  }
  // Rims touch at x: disk 2's plane contains rim 1's tangent t1 at x and the
  // direction w = cos(psi) rho1 + sin(psi) z; disk 2 = x + r2 w + (disk in
  // span(t1, w)), so it meets plane 1 only where its w-coordinate is -r2, i.e.
  // at x alone (sin(psi) != 0).
  const Real a = rng.angle();
  const Vector3R rho1(std::cos(a), std::sin(a), 0);
  const Vector3R t1(-std::sin(a), std::cos(a), 0);
  Real psi = rng.uniform(Real(0.05), Real(family_detail::Rng::kPi - 0.05));
  if (rng.uniform01() < 0.5) psi = -psi;
  const Vector3R w = std::cos(psi) * rho1 + std::sin(psi) * Vector3R::UnitZ();
  Matrix3R R2;
  R2.col(0) = t1;
  R2.col(1) = w;
  R2.col(2) = t1.cross(w);
  local->r1 = r1;
  local->r2 = r2;
  local->R2 = R2 * rotZ(rng.angle());
  local->c2 = r1 * rho1 + r2 * w;
  local->known = 0;
  *kind = "rim_on_rim";
}

template <typename S>
void makeInterlocked(int i, Rng& rng, LocalPair* local, std::string* kind) {
  // Both disks meet L = {y = b, z = 0} (direction x): disk 1 in the chord
  // |x| <= s1; disk 2's plane contains L (normal (0, cos chi, sin chi)), its
  // centre is delta from L in its plane, chord |x - x2| <= s2 with x2 chosen so
  // that disk 2's chord straddles disk 1's rim point (s1, b): chain link.
  const Real r1 = roundedRadius<S>(rng.uniform(Real(0.3), Real(1.5)));
  const Real r2 = roundedRadius<S>(r1 * rng.uniform(Real(0.5), Real(2)));
  const Real b = r1 * rng.uniform(Real(-0.7), Real(0.7));
  const Real s1 = std::sqrt(r1 * r1 - b * b);
  const Real chi = (i % 2 == 0) ? 0 : rng.uniform(Real(-0.4), Real(0.4));
  const Vector3R n2(0, std::cos(chi), std::sin(chi));
  const Vector3R across = n2.cross(Vector3R::UnitX());  // in plane 2, perpendicular to L
  const Real delta = r2 * rng.uniform(Real(-0.7), Real(0.7));
  const Real s2 = std::sqrt(r2 * r2 - delta * delta);
  const Real x2 = s1 + rng.uniform(Real(-0.8), Real(0.8)) * s2;
  Matrix3R R2;
  R2.col(0) = Vector3R::UnitX();
  R2.col(1) = across;
  R2.col(2) = n2;
  local->r1 = r1;
  local->r2 = r2;
  local->R1 = rotZ(rng.angle());
  local->R2 = R2 * rotZ(rng.angle());
  local->c2 = Vector3R(x2, b, 0) + delta * across;
  local->known = 0;
  *kind = chi == 0 ? "perpendicular" : "tilted";
}

template <typename S>
void makePerpendicular(int i, Rng& rng, LocalPair* local, std::string* kind) {
  const Real r1 = roundedRadius<S>(rng.uniform(Real(0.2), Real(1.5)));
  const Real r2 = roundedRadius<S>(rng.uniform(Real(0.2), Real(1.5)));
  const Real beta = rng.angle();
  const Vector3R n2(std::cos(beta), std::sin(beta), 0);
  Matrix3R R2;
  R2.col(0) = Vector3R::UnitZ();
  R2.col(1) = n2.cross(Vector3R::UnitZ());
  R2.col(2) = n2;
  R2 = R2 * rotZ(rng.angle());
  switch (i % 3) {
    case 0: {  // standing on disk 1's face, lowest point above its interior
      *local = faceRimPair(r1, r2, rng.logUniform(Real(1e-6), Real(2)),
                           pointInDisk(r1, Real(0.95), rng), rng.sign(), R2);
      *kind = "face";
      break;
    }
    case 1: {
      const Real d = rng.logUniform(Real(1e-6), Real(2));
      while (!rimRimPair(r1, r2, d, rng.angle(), rng.uniform(Real(-1.4), Real(1.4)), R2, local)) {
      }
      *kind = "rim_rim";
      break;
    }
    default: {  // beside: disk 2 straddles plane 1 outside disk 1 (or misses it)
      local->r1 = r1;
      local->r2 = r2;
      local->R2 = R2;
      for (;;) {
        const Real phi = rng.angle();
        const Real radial = rng.uniform(r1, r1 + 2 * r2);
        local->c2 = Vector3R(radial * std::cos(phi), radial * std::sin(phi),
                             rng.uniform(-1.5 * r2, 1.5 * r2));
        const Real z = local->c2.z();
        if (std::fabs(z) >= r2) break;  // disk 2 does not reach plane 1
        // Chord of disk 2 in plane 1: centre (x, y), direction along plane1 ∩ plane2.
        const Real half = std::sqrt(r2 * r2 - z * z);
        const Vector3R chord_dir = n2.cross(Vector3R::UnitZ());
        const Vector3R centre(local->c2.x(), local->c2.y(), 0);
        const Real t = std::max(-half, std::min(half, -centre.dot(chord_dir)));
        if ((centre + t * chord_dir).norm() > r1 * Real(1.02)) break;  // chord misses disk 1
      }
      local->known = std::numeric_limits<Real>::quiet_NaN();
      *kind = "beside";
      break;
    }
  }
}

template <typename S>
void makeRimRim(Rng& rng, LocalPair* local) {
  const Real r1 = roundedRadius<S>(rng.uniform(Real(0.2), Real(1.5)));
  const Real r2 = roundedRadius<S>(rng.uniform(Real(0.2), Real(1.5)));
  const Real d = rng.logUniform(Real(1e-4), Real(2));
  while (!rimRimPair(r1, r2, d, rng.angle(), rng.uniform(Real(-1.4), Real(1.4)), rng.rotation(),
                     local)) {
  }
}

template <typename S>
void makeRadiusRatio(int i, Rng& rng, LocalPair* local, std::string* kind) {
  const Real r1 = roundedRadius<S>(rng.uniform(Real(0.5), Real(2)));
  const Real r2 = roundedRadius<S>(r1 * rng.logUniform(Real(1e-6), Real(1e6)));
  const Real size = std::max(r1, r2);
  switch (i % 3) {
    case 0: {
      const Real d = size * rng.logUniform(Real(1e-6), Real(1));
      while (!rimRimPair(r1, r2, d, rng.angle(), rng.uniform(Real(-1.4), Real(1.4)),
                         rng.rotation(), local)) {
      }
      *kind = "rim_rim";
      break;
    }
    case 1: {
      const Real d = size * rng.logUniform(Real(1e-6), Real(1));
      *local = faceRimPair(r1, r2, d, pointInDisk(r1, Real(0.95), rng), rng.sign(),
                           frameTiltedAtLeast(Real(0.05), rng));
      *kind = "face";
      break;
    }
    default: {
      local->r1 = r1;
      local->r2 = r2;
      local->R1 = rng.rotation();
      local->R2 = rng.rotation();
      local->c2 = (r1 + r2) * rng.uniform(0, Real(1.3)) * rng.unitVector();
      local->known = std::numeric_limits<Real>::quiet_NaN();
      *kind = "random";
      break;
    }
  }
  // Swap roles half of the time so both disks get to be the large one in slot 1.
  if (rng.uniform01() < 0.5) {
    LocalPair swapped = *local;
    swapped.r1 = local->r2;
    swapped.R1 = local->R2;
    swapped.c1 = local->c2;
    swapped.r2 = local->r1;
    swapped.R2 = local->R1;
    swapped.c2 = local->c1;
    *local = swapped;
  }
}

template <typename S>
void makeSeparationScale(int i, Rng& rng, LocalPair* local, std::string* kind) {
  // Three fixed shapes (fixed radii and orientations) at separation d.
  const Real d = rng.logUniform(Real(1e-12), Real(1e6));
  const Real r1 = 1, r2 = Real(0.75);
  switch (i % 3) {
    case 0: {  // rim-rim, generic orientation
      const Matrix3R R2 = Eigen::AngleAxis<Real>(Real(0.9), Vector3R(1, 2, 3).normalized())
                              .toRotationMatrix();
      rimRimPair(r1, r2, d, Real(0.3), Real(0.4), R2, local);
      *kind = "rim_rim";
      break;
    }
    case 1: {  // rim of a tilted disk 2 over disk 1's face
      const Matrix3R R2 = Eigen::AngleAxis<Real>(Real(0.7), Vector3R(2, -1, 0).normalized())
                              .toRotationMatrix();
      *local = faceRimPair(r1, r2, d, Vector3R(Real(0.25), Real(-0.5), 0), 1, R2);
      *kind = "face";
      break;
    }
    default: {  // parallel faces, offset projections overlapping
      local->r1 = r1;
      local->r2 = r2;
      local->R2 = rotZ(Real(1.1));
      local->c2 = Vector3R(Real(0.6), Real(0.3), d);
      local->known = d;
      *kind = "parallel";
      break;
    }
  }
  (void)rng;
}

template <typename S>
void makeTinyNextToRim(int i, Rng& rng, LocalPair* local, std::string* kind) {
  const Real r1 = roundedRadius<S>(rng.uniform(Real(0.5), Real(2)));
  const Real r2 = roundedRadius<S>(r1 * rng.logUniform(Real(1e-9), Real(1e-6)));
  const Real d = r2 * rng.logUniform(Real(1e-3), Real(10));
  while (!rimRimPair(r1, r2, d, rng.angle(), rng.uniform(Real(-1.4), Real(1.4)), rng.rotation(),
                     local)) {
  }
  if (i % 2 == 1) {  // the small disk in slot 1
    std::swap(local->r1, local->r2);
    std::swap(local->R1, local->R2);
    std::swap(local->c1, local->c2);
  }
  *kind = "rim_rim";
}

template <typename S>
void makeSideBySide(Rng& rng, LocalPair* local, std::string* kind) {
  const Real r1 = roundedRadius<S>(rng.uniform(Real(0.3), Real(1.5)));
  const Real r2 = roundedRadius<S>(rng.uniform(Real(0.3), Real(1.5)));
  const Real tilt = rng.logUniform(Real(1e-8), Real(1e-2));
  const Real d = std::max(r1, r2) * rng.logUniform(Real(1e-6), Real(1));
  while (!rimRimPair(r1, r2, d, rng.angle(), rng.uniform(Real(-0.1), Real(0.1)),
                     tiltedFrame(tilt, rng), local)) {
  }
  *kind = "rim_rim";
}

inline std::uint64_t familySeed(Family f, std::uint64_t seed) {
  // Different families draw different streams from the same user seed.
  return seed * 0x9E3779B97F4A7C15ULL + static_cast<std::uint64_t>(f) * 0xD1B54A32D192ED03ULL + 1;
}

}  // namespace family_detail

/// Deterministic cases of family f: the same (f, count, seed) always gives the
/// same cases (and the first k cases of a longer list equal a shorter list).
template <typename S>
std::vector<DiskPairCase<S>> makeFamily(Family f, int count, std::uint64_t seed) {
  using namespace family_detail;
  Rng rng(familySeed(f, seed));
  std::vector<DiskPairCase<S>> cases;
  cases.reserve(count);
  for (int i = 0; i < count; ++i) {
    LocalPair local;
    std::string kind = "generic";
    switch (f) {
      case Family::random:
      case Family::far_from_origin:
        local = randomPair(rng);
        local = roundRadii<S>(local);
        kind = "random";
        break;
      case Family::near_parallel: makeNearParallel<S>(i, rng, &local, &kind); break;
      case Family::coplanar: makeCoplanar<S>(i, rng, &local, &kind); break;
      case Family::coaxial: makeCoaxial<S>(i, rng, &local, &kind); break;
      case Family::touching: makeTouching<S>(i, rng, &local, &kind); break;
      case Family::interlocked: makeInterlocked<S>(i, rng, &local, &kind); break;
      case Family::perpendicular: makePerpendicular<S>(i, rng, &local, &kind); break;
      case Family::rim_rim: makeRimRim<S>(rng, &local); kind = "rim_rim"; break;
      case Family::radius_ratio: makeRadiusRatio<S>(i, rng, &local, &kind); break;
      case Family::separation_scale: makeSeparationScale<S>(i, rng, &local, &kind); break;
      case Family::tiny_next_to_rim: makeTinyNextToRim<S>(i, rng, &local, &kind); break;
      case Family::side_by_side: makeSideBySide<S>(rng, &local, &kind); break;
    }
    // Common rigid motion. Far from origin: up to 1e6 (log-uniform magnitude,
    // half of the cases at 0.5e6..1e6); otherwise a unit-scale offset.
    const Matrix3R Q = rng.rotation();
    Vector3R t = rng.inBall(2);
    if (f == Family::far_from_origin) {
      const Real magnitude = (i % 2 == 0) ? rng.uniform(Real(5e5), Real(1e6))
                                          : rng.logUniform(Real(1), Real(1e6));
      t = magnitude * rng.unitVector();
    }
    cases.push_back(finish<S>(std::string(familyName(f)) + "/" + kind + "/" + std::to_string(i),
                              local, Q, t));
  }
  return cases;
}

}  // namespace fcl_disk_families

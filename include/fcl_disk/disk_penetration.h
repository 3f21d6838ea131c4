// Signed distance and exact penetration depth of two disks. Derivation and
// notation: docs/penetration_depth.md.
#pragma once

#include <fcl_disk/disk_pair.h>

namespace fcl_disk {

/// Signed distance between two disks, its witness points and its gradient.
///
/// Apart (signed_distance > 0): the distance and nearest points of
/// exactDiskDistance(). Intersecting (signed_distance <= 0): minus the
/// penetration depth PD, the length of the shortest translation that separates
/// the disks (after it they touch).
template <typename S>
struct DiskSignedDistanceResult {
  /// d > 0 when apart, -PD <= 0 when the disks share a point.
  S signed_distance{0};
  /// Apart: the nearest point of disk 1. Intersecting: disk 1's point deepest
  /// along `direction` (its support point; on the face when `direction` is
  /// +-n1), so that p_W1 - p_W2 = PD * direction. World frame.
  fcl::Vector3<S> p_W1{fcl::Vector3<S>::Zero()};
  /// Apart: the nearest point of disk 2. Intersecting: disk 2's point deepest
  /// along -`direction`. World frame.
  fcl::Vector3<S> p_W2{fcl::Vector3<S>::Zero()};
  /// Unit vector, world frame: the gradient of the signed distance with respect
  /// to a translation of disk 2 (where it is differentiable). Apart: (p_W2 -
  /// p_W1) / d, from disk 1 towards disk 2. Intersecting: translating disk 2 by
  /// PD * direction (or disk 1 by -PD * direction) separates the disks to touching.
  fcl::Vector3<S> direction{fcl::Vector3<S>::UnitZ()};
};

/// Penetration depth of two disks that share a point: the minimum over unit w
/// of F(w) = (c1 - c2).w + r1 |P1 w| + r2 |P2 w|, the support function of the
/// Minkowski difference K1 - K2 (translating disk 2 by t w separates the disks
/// for every t > F(w)), its minimiser w (`direction`) and the witness points,
/// as in DiskSignedDistanceResult (signed_distance = -PD).
///
/// Frames, units and pose convention as in exactDiskDistance(). Arithmetic in
/// double, in disk 1's frame relative to c1, lengths divided by the scene size
/// r1 + r2 + |c1 - c2|.
///
/// Method (docs/penetration_depth.md): F is convex and positively homogeneous,
/// smooth except at w = +-n1, +-n2. At a minimiser on the unit sphere that is
/// not one of these four kinks, the support points (rim points) a of disk 2
/// and b of disk 1 satisfy b - a = PD w with w normal to both rims' tangents, so
/// (b, a) is a critical pair of the distance between the two rim circles, and a's
/// rim angle theta is a root of the degree-4 trigonometric polynomial
/// Q(theta) = rho^2 L^2 - r1^2 K^2 (rho: distance of a from disk 1's axis;
/// L, K: halves of the derivatives of |a|^2 and rho^2). Every real root of Q is
/// found (two charts theta = 2 atan t and pi + 2 atan t, t in [-1, 1]; the
/// degree-8 polynomial's roots isolated by Bernstein subdivision, Descartes'
/// rule, and polished by Newton steps within their brackets; where the
/// coefficients cannot decide, the extremum between two roots is found too,
/// which catches double roots that do not change sign in rounding), and F is
/// evaluated at the directions each root gives (+-(b - a), +-t1 x t2) and at
/// the four kinks; when Q vanishes identically (coaxial disks, Villarceau
/// pairs) at 64 rim angles. Every value F(w) is an upper bound on PD, and the
/// candidate set contains a global minimiser, so the smallest value is PD (a
/// proof, not a local search). The best rim pair is then polished by
/// Newton's method on the two critical-pair equations, and its direction by
/// Newton's method on F over the sphere. Where a rim point of one disk comes
/// within 1e-3 of the scene of the other's axis, Q's roots there lose their
/// digits to rounding, and the search is run with the roles exchanged too.
///
/// Guarantee (double): |PD - PD_true| <= 1e-12 * (r1 + r2 + |c1 - c2|), tested
/// against an independent long-double reference; p_W1 on disk 1 and p_W2 on disk
/// 2 to the same bound (plus ulp(|c_i|)), p_W1 - p_W2 = PD * direction to that
/// bound. Float: inputs promoted to double, results rounded to float.
///
/// Degenerate cases and tie-breaks:
/// - Coplanar overlapping disks: PD = 0 (a shift along the common normal
///   separates them); direction = n1 (the first kink, a tie with -n1, n2 and
///   -n2), p_W1 = p_W2 = the common point intersectDisks() reports.
/// - Ties between distinct minimisers (symmetric pairs, e.g. a disk through
///   the centre of another at right angles): the first candidate in the order
///   +n1, -n1, +n2, -n2, then by rim angle; deterministic for a given input.
/// - A pair that does not share a point: the value is min F < 0 (minus the
///   distance), a consistent extension, but call signedDiskDistance() for pairs
///   that may be apart.
/// Invalid input (as exactDiskDistance): NaN signed distance, points and direction.
template <typename S>
DiskSignedDistanceResult<S> diskPenetration(S r1, const fcl::Transform3<S>& X_W1, S r2,
                                            const fcl::Transform3<S>& X_W2);

/// Signed distance of two disks: exactDiskDistance() when they are apart,
/// minus diskPenetration()'s depth when they share a point (touching pairs,
/// within exactDiskDistance's touching tolerance of 1e-13 * scale, get the
/// penetration answer, which is then within that tolerance of 0). Continuous
/// through contact. Frames, units, guarantees and invalid input as the two
/// functions it calls.
template <typename S>
DiskSignedDistanceResult<S> signedDiskDistance(S r1, const fcl::Transform3<S>& X_W1, S r2,
                                               const fcl::Transform3<S>& X_W2);

// Explicit instantiations, compiled into libfcl_disk (hidden from the API reference).
/// @cond
extern template DiskSignedDistanceResult<float> diskPenetration(float, const fcl::Transform3<float>&,
                                                                float,
                                                                const fcl::Transform3<float>&);
extern template DiskSignedDistanceResult<double> diskPenetration(
    double, const fcl::Transform3<double>&, double, const fcl::Transform3<double>&);
extern template DiskSignedDistanceResult<float> signedDiskDistance(
    float, const fcl::Transform3<float>&, float, const fcl::Transform3<float>&);
extern template DiskSignedDistanceResult<double> signedDiskDistance(
    double, const fcl::Transform3<double>&, double, const fcl::Transform3<double>&);
/// @endcond

}  // namespace fcl_disk

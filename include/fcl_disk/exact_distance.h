// Exact disk-disk distance, certified by convex duality. Derivation and notation:
// docs/exact_distance.md.
#pragma once

#include <fcl_disk/disk_pair.h>

namespace fcl_disk {

/// Exact distance between two disks and a pair of nearest points.
///
/// Frames: disk i is centred at the origin of its frame, lies in the local XY
/// plane with normal +Z and has pose X_Wi in the world frame W (rotation
/// columns u_i, v_i, n_i; translation c_i); p_W1, p_W2 are in W. Units: the
/// caller's length unit. All arithmetic is done in double relative to c1, so
/// translating both disks far from the origin costs no accuracy in distance.
///
/// Method (docs/exact_distance.md): (1) a closed-form intersection test; (2) the
/// two closed-form face cases, accepted only when their optimality (KKT)
/// conditions hold; (3) otherwise the rim-rim case: for nearly parallel planes
/// whose rims cross in projection, candidates at the corners of the lens the
/// projections overlap in, returned when certified; else Newton's method on the
/// convex psi(p) = dist(p, K2)^2 / 2 over disk 1 (Newton along the rim, or a
/// step minimising psi's quadratic model over the disk with an exact line
/// search), stopped by the duality gap between |p - q| and the certificate
/// g(w) = w.(c2 - c1) - r1|P1 w| - r2|P2 w| (a lower bound for every unit w);
/// while the gap stays open, searches along the rims as fallbacks.
///
/// Guarantee (double): |distance - d_true| <= 1e-12 * (r1 + r2 + |c1 - c2|): relative,
/// at every length scale in range (kMinDiskRadius..kMaxDiskLength; tested
/// against a long-double reference for radii 1e-9..1e9 and coordinates up to 1e9,
/// by property tests at scales 1e-90..1e90, and by fuzzing over the whole range),
/// and both points lie on their disks to the same bound plus the rounding of
/// storing them in world coordinates (ulp(|c_i|)); distance == |p_W2 - p_W1| up
/// to that rounding. lower_bound is the duality certificate (at the returned
/// separation direction, at the face normals and, for rim-rim pairs, along the
/// cross product of the two rim tangents, which is the separation's direction
/// at a rim-rim optimum and free of the cancellation in q - p): certifiedGap() is at most
/// 1e-14 * scale on well-conditioned pairs. For near-degenerate pairs the
/// certificate is an honest but pessimistic error bar: its direction is known
/// only to about eps * scale / d (tiny d) or sqrt(eps) (flat optima next to a
/// face case of nearly parallel disks), and g is only Lipschitz at its kinks, so
/// the gap may reach about (r1 + r2) (sqrt(eps) + 8 eps scale / d) while
/// the distance still meets the bound above (eps of the scalar type).
/// Float: inputs are promoted to double (each rotation rebuilt as the
/// orthonormal frame with its normal, so that the certificate closes as for
/// double input), results rounded to float, so the bound
/// is a few float ulps of max(r1 + r2 + |c1 - c2|, |c_i|) (property tests at
/// scales 1e-30..1e30).
///
/// Degenerate cases and tie-breaks (the optimum is unique in distance, not
/// always in points):
/// - Intersecting, touching: distance 0, p_W1 == p_W2 == a common point: the
///   midpoint of the common chord on the planes' intersection line; for coplanar
///   overlapping disks, the point of the segment c1-c2 halfway through the
///   overlap of the two disks along it (the common centre if concentric).
/// - Parallel planes with overlapping projections (coaxial stacks included):
///   a face-face optimum; returns the points over the middle of the overlap
///   along the line of centres (centre of the smaller disk's projection when one
///   projection contains the other's centre line point), feature face1_rim2.
/// - Face cases: when several extreme rim points tie (never, unless the planes
///   are parallel) the +u direction of the other disk is used.
/// - Rim-rim: the optimal pair is unique (a convex set of optimal points on a
///   circle is one point). For planes within sin 0.1 of parallel whose rims
///   cross in projection, a pair of rim points near each crossing is tried
///   first and returned when its certificate closes, along t1 x t2 and along
///   its own separation (up to the rounding of that direction).
///   Newton starts on disk 1's rim, towards where disk 2
///   comes nearest plane 1 (docs/exact_distance.md, section 4), and stops at a
///   certified gap of 1e-14 * scale, at the rounding floor (flat,
///   near-degenerate optima, e.g. next to a face case), or after 16 iterations.
///   While the gap stays open: a local search along disk 1's rim, the same on
///   disk 2's rim, a global search along disk 1's rim (docs/exact_distance.md,
///   section 4); the nearest pair found is returned and lower_bound says how
///   well it is proven.
/// Invalid input never crashes and never gets a made-up answer: a radius
/// rejected by isValidDiskRadius() or a pose rejected by isValidDiskPose() (NaN
/// or infinite entries, lengths outside kMinDiskRadius..kMaxDiskLength, where
/// squares would overflow or underflow, a rotation further than
/// kRotationDefectTolerance from orthonormal) gives NaN distance, lower_bound
/// and points (feature unspecified).
/// An accepted, slightly non-orthonormal rotation stands for the disk with its
/// normal R e_z / |R e_z| (kRotationDefectTolerance).
template <typename S>
DiskDistanceResult<S> exactDiskDistance(S r1, const fcl::Transform3<S>& X_W1, S r2,
                                        const fcl::Transform3<S>& X_W2);

// Explicit instantiations, compiled into libfcl_disk (hidden from the API reference).
/// @cond
extern template DiskDistanceResult<float> exactDiskDistance(float, const fcl::Transform3<float>&,
                                                            float, const fcl::Transform3<float>&);
extern template DiskDistanceResult<double> exactDiskDistance(
    double, const fcl::Transform3<double>&, double, const fcl::Transform3<double>&);
/// @endcond

}  // namespace fcl_disk

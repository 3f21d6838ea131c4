// Every tolerance of test_properties.cpp and test_gjk_crosscheck.cpp, in one
// place, each with the reason for its value (the FCL test-suite convention).
//
// Units: constants named "...Relative" or documented as relative multiply the
// scene size (sceneSize() below), so they are lengths per unit of scene size;
// the others are absolute lengths or pure numbers, as stated. Checks are
// evaluated in double even for float solvers, so the tolerances only have to
// cover the solver's own rounding, not the test's.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

namespace fcl_disk_test {

/// The length that relative tolerances scale with:
/// max(1, r1 + r2 + |c1 - c2|, |c1|, |c2|). The solvers' documented bounds are
/// relative to max(1, r1 + r2 + |c1 - c2|); |c_i| is included because points
/// stored in world coordinates carry ulp(|c_i|) of rounding (exact_distance.h).
inline double sceneSize(double r1, double r2, double centre_gap, double c1_norm,
                        double c2_norm) {
  return std::max({1.0, r1 + r2 + centre_gap, c1_norm, c2_norm});
}

template <typename S>
struct Eps {
  static constexpr bool kIsFloat = std::is_same<S, float>::value;
  /// Not a tolerance: the unit the float tolerances are counted in.
  static constexpr double kUnitRoundoff = std::numeric_limits<S>::epsilon();

  // ---------------------------------------------------------------- exact solver
  /// |distance - d_true| and | |p - q| - distance |, relative. double: the
  /// guarantee stated in exact_distance.h (1e-12 * scale). float: the solver runs
  /// in double and rounds p, q, distance to float; 16 ulps of scale covers those
  /// three roundings plus the non-orthonormality of a float rotation (~eps).
  static constexpr double kExactDistanceRelative = kIsFloat ? 16 * kUnitRoundoff : 1e-12;

  /// A returned point's offset from its disk (|local z|, in-plane radius - r),
  /// relative. Same budget as the distance: exact_distance.h states the points
  /// lie on their disks to the distance bound plus ulp(|c_i|) (in sceneSize()).
  static constexpr double kOnDiskRelative = kIsFloat ? 16 * kUnitRoundoff : 1e-12;

  /// Storing a rigidly moved pose in S perturbs centres by ~ulp(|c|) and rotation
  /// entries by ~eps/2; the distance is 1-Lipschitz in such moves, so a few ulps
  /// of the scene (relative) bound the change it causes.
  static constexpr double kPoseRoundingRelative = 4 * kUnitRoundoff;

  /// Points of two solves of the same (swapped or moved) problem, relative, per
  /// unit of conditioning (see kMinSineForUniquePoints). Derived from the
  /// distance guarantee, not measured: near a unique optimum the distance grows
  /// quadratically along the rims (curvature ~1/r), so a pair whose distance is
  /// within eps * scale of optimal may sit up to sqrt(2 eps) * scale from it.
  /// double: sqrt(2e-12) = 1.4e-6; float: sqrt(32 * 1.2e-7) = 2.0e-3. A frame,
  /// ordering or tie-break bug moves points by O(r) and is still caught.
  static inline const double kUniquePointsRelative = std::sqrt(2 * kExactDistanceRelative);

  /// Certificate: certifiedGap() = distance - lower_bound, relative. exact_distance.h
  /// says it "is 0 up to rounding" for the exact solver: the distance budget.
  static constexpr double kCertifiedGapRelative = kExactDistanceRelative;

  // -------------------------------------------------------------- intersection
  /// intersectDisks() and the exact solver's "distance == 0" may disagree only
  /// for poses that a translation of disk 2 by at most this (relative) flips.
  /// double: 10x the exact solver's 1e-12 (its zero/nonzero decision is only
  /// that good); disk_intersection.h itself claims 1e-15. float: the inputs are
  /// float and either routine may work in float; 64 ulps of scale.
  static constexpr double kIntersectionBandRelative = kIsFloat ? 64 * kUnitRoundoff : 1e-11;

  /// Extra translation past the reported penetration depth in the separation
  /// check, relative: 100x the band so that the separated pose is decided
  /// robustly by intersectDisks(), yet small enough that "distance ~ step"
  /// shows the disks were just touching at the reported depth.
  static constexpr double kSeparationStepRelative = 100 * kIntersectionBandRelative;

  /// | |normal| - 1 |, absolute. The normal may be a column of the input rotation,
  /// which is unit only as far as the input is orthonormal: our generated
  /// rotations (quaternion -> matrix, then products) are off by up to ~10 ulps
  /// (measured 2.3e-15 in double), plus one normalisation. 32 ulps.
  static constexpr double kUnitNormal = 32 * kUnitRoundoff;

  // ------------------------------------------------------- Almohamad-Selim solver
  /// Its points on the disks and | |p - q| - distance |, relative. It evaluates
  /// closed forms (no iteration), so only rounding: the same budget as the exact
  /// solver (its header promises a real pair with distance = |p_W2 - p_W1|).
  static constexpr double kAlmohamadSelimConsistencyRelative = kExactDistanceRelative;

  /// Its counterexample values are quoted to 6 decimals in the report and in
  /// facts.md (0.400000, 0.353553): half a unit of the 6th decimal plus rounding.
  static constexpr double kReportedValueAbsolute = 1e-6;

  /// "Clearly above" the GJK bracket, absolute: facts.md measures errors of
  /// 0.347 (A: 0.4 vs 0.0528) and 0.291 (B: 0.3536 vs 0.0624) on unit-size scenes,
  /// >100x the bracket width plus GJK tolerance; 0.1 leaves no doubt either way.
  static constexpr double kAlmohamadSelimVisibleError = 0.1;

  // ------------------------------------------------------------ GJK cross-check
  /// DistanceRequest::distance_tolerance (absolute). FCL passes it to libccd as
  /// dist_tolerance and to the indep solver as gjk_tolerance. libccd stops when an
  /// iteration improves the distance by less than it, so the default 1e-6 leaves
  /// errors up to ~2e-4 (facts.md: 3e-4); with 1e-9 we measured <= 2e-7 relative
  /// on 2000 random/parallel/coplanar pairs, at ~2-5 us per query.
  static constexpr double kGjkRequestTolerance = 1e-9;

  /// GJK (libccd) error on thin cylinders, relative, with kGjkRequestTolerance.
  /// Measured max 1.6e-7 (double) over 2000 pairs, float about the same plus
  /// float rounding of the poses and result (libccd runs in double internally);
  /// ~10x margin. Exactly coaxial stacks excluded: see kLibccdCoaxialSine.
  static constexpr double kGjkLibccdRelative = kIsFloat ? 4e-6 : 2e-6;

  /// GJK (indep) error on thin cylinders, relative. facts.md: up to 1e-6 of the
  /// scene (double); measured max 8e-7 with h = 1e-6 (the flat simplex is the
  /// hard case). In float the indep solver works in float: measured 1.3e-5
  /// (~110 ulps); ~6-8x margin.
  static constexpr double kGjkIndepRelative = kIsFloat ? 1e-4 : 5e-6;

  /// Below this |n1 x n2| (and the same for the centre offset against n1), a pair
  /// is an exactly coaxial stack, on which libccd's GJK (FCL 0.7, libccd 2.1)
  /// stalls on a wrong simplex: measured r1 = 1, r2 = 0.5, offset 2 along a rotated
  /// axis, h = 1e-6 gives d_cyl = 2.4999992 instead of 1.999999 (80 of 400 random
  /// coaxial stacks, none once tilted by 1e-6). GJK then OVERestimates, so only the
  /// lower half of the bracket (d_cyl <= d_disk) is skipped there; indep has no
  /// such failure and is checked on the full bracket.
  static constexpr double kLibccdCoaxialSine = 1e-5;

  /// Thin-cylinder heights (absolute) for the bracket d_cyl <= d_disk <= d_cyl + h.
  /// float: only 1e-3; h = 1e-6 is ~8 ulps at unit scale and far below float GJK's
  /// error (kGjkIndepRelative), so the bracket would only test |d_disk - d_cyl|
  /// <= GJK tolerance, i.e. nothing that h = 1e-3 does not already test.
  static constexpr double kThickHeight = 1e-3;
  static constexpr double kThinHeight = 1e-6;
  static constexpr bool kThinHeightMeaningful = !kIsFloat;

  // ---------------------------------------------------------------- conditioning
  /// Points of two solves are compared only where the nearest pair is unique and
  /// well conditioned: sin(angle between the normals) >= this. The pair stops
  /// being unique for parallel planes, and its sensitivity grows like 1/sin (the
  /// rim point of one disk extreme along the other's normal); the point
  /// tolerance is multiplied by 1/sin, at most 20 here.
  static constexpr double kMinSineForUniquePoints = 0.05;
};

}  // namespace fcl_disk_test

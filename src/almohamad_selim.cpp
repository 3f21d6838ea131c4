// The disk-disk algorithm of Almohamad & Selim, Univ. of Michigan IOE Tech.
// Report 94-8 (1994): Lemma 1 / Section V with the detailed steps of Appendix A,
// in the report's formulation (7), with the Appendix A errata fixed. The names
// (P, R, D1, D2, V0, W0, Mp, Vp, Wp, M0) are the report's so the code can be read
// next to the appendix. Lemma 1 is false in general, so the result is an upper
// bound, not the distance: docs/almohamad_selim.md.
//
// As in the report, d(A, B) below is a SQUARED distance (Prop. 1: d(M, W) = ||M - W||^2).
#include <fcl_disk/almohamad_selim.h>

#include <cmath>
#include <limits>

#include "pair_in_frame1.h"

namespace fcl_disk {
namespace {

using Vec3 = fcl::Vector3<double>;
using Mat3 = fcl::Matrix3<double>;

/// A point-disk answer in the disk's own frame (disk centred at the origin in
/// the XY plane): the optimal point, the report's squared distance d, and
/// whether the point lies on the rim (decided by the case taken, so exactly).
struct NearestPointOnDisk {
  Vec3 point{Vec3::Zero()};
  double d{0.0};
  bool on_rim{false};
};

/// Proposition 1: the nearest point M* of the disk {||M|| <= D, M_z = 0} to W.
///   Case 1, ||W||_xy > D:      M* = D W_xy / ||W||_xy, d = (||W||_xy - D)^2 + W_z^2.
///   Case 2, 0 <= ||W||_xy <= D: M* = W_xy,             d = W_z^2.
/// Tie-break: W on the axis (||W||_xy = 0) falls in Case 2 (M* = the centre), so
/// Case 1 never divides by zero; the extra `W_xy > 0` keeps that true even for
/// a radius D <= 0, which is outside the precondition. NaN fails both `>` tests,
/// takes Case 2 and propagates.
NearestPointOnDisk proposition1(double D, const Vec3& W) {
  const double W_xy = std::sqrt(W.x() * W.x() + W.y() * W.y());  // ||W||_xy
  NearestPointOnDisk result;
  if (W_xy > D && W_xy > 0.0) {  // Case 1: W projects outside the disk.
    const double scale = D / W_xy;
    result.point = Vec3(scale * W.x(), scale * W.y(), 0.0);
    result.d = (W_xy - D) * (W_xy - D) + W.z() * W.z();
    result.on_rim = true;
  } else {  // Case 2: W projects onto the disk.
    result.point = Vec3(W.x(), W.y(), 0.0);
    result.d = W.z() * W.z();
    result.on_rim = (W_xy == D);  // projects exactly onto the rim
  }
  return result;
}

/// Proposition 2, stated by the report for the point O and used by Step 4 for
/// the point Mp: the nearest point W* = R V* + P of K2 (centre P, rotation R,
/// radius D2) to a point X of K1's frame. ||R V + P - X|| = ||V - R^T (X - P)||,
/// so this is Proposition 1 in K2's frame at R^T (X - P). Returns V*.
/// Sign convention (facts.md): for X = O the argument is -R^T P, which is the
/// report's V* = -D2 (R^T P)_xy / ||R^T P||_xy; for X = Mp it is +R^T (Mp - P),
/// Appendix A Step 4's "+" sign. Both are right for what each computes.
NearestPointOnDisk proposition2(double D2, const Mat3& R, const Vec3& P, const Vec3& X) {
  return proposition1(D2, R.transpose() * (X - P));
}

}  // namespace

template <typename S>
DiskDistanceResult<S> almohamadSelimDiskDistance(S r1, const fcl::Transform3<S>& X_W1, S r2,
                                                 const fcl::Transform3<S>& X_W2) {
  // Computed in double whatever S is (float inputs are promoted).
  const double D1 = static_cast<double>(r1);
  const double D2 = static_cast<double>(r2);
  const fcl::Transform3<double> X_W1d = X_W1.template cast<double>();
  const fcl::Transform3<double> X_W2d = X_W2.template cast<double>();
  // Invalid input (NaN or infinite radius or pose, a rotation that is not
  // orthonormal): NaN out. Without this a NaN radius would fail every `>` test
  // of Props. 1-2 and quietly yield a finite, meaningless pair.
  if (!internal::checkDiskPair(r1, X_W1, r2, X_W2).valid) return internal::nanDistanceResult<S>();
  DiskDistanceResult<S> result;

  const Mat3 R1 = X_W1d.linear();
  const Mat3 R2 = X_W2d.linear();
  const Vec3 P1 = X_W1d.translation();
  const Vec3 P2 = X_W2d.translation();

  // Formulation (7): K1 centred at the origin O of the (X0, Y0) plane; K2 has
  // centre 0P = R1^T (P2 - P1) and rotation 0R = R1^T R2. The report's further
  // reduction to (13) (rotations A, B and the reflection I1) is skipped, as its
  // conclusion allows; so the Section III erratum about reflecting M and P by I1
  // when D11 = -1 cannot arise here.
  const Vec3 P = R1.transpose() * (P2 - P1);
  const Mat3 R = R1.transpose() * R2;

  // Step 1 (Proposition 2): W0* = R V0* + P, the nearest point of K2 to O.
  // Erratum: Appendix A Step 1 tests and subtracts D1; Proposition 2 is about
  // K2, so it is D2.
  const NearestPointOnDisk step1 = proposition2(D2, R, P, Vec3::Zero());
  const Vec3& V0 = step1.point;
  const Vec3 W0 = R * V0 + P;
  const double d_O_W0 = step1.d;

  // Step 2 (Proposition 1): Mp*, the nearest point of K1 to P.
  // Erratum: Appendix A Step 2 tests and subtracts D2; Proposition 1 is about
  // K1, so it is D1.
  const NearestPointOnDisk step2 = proposition1(D1, P);
  const Vec3& Mp = step2.point;
  const double d_Mp_P = step2.d;

  // Steps 3 / 4, with the report's strict `<`: a tie goes to Step 4.
  Vec3 M_star;  // the returned point of K1, in K1's frame
  Vec3 V_star;  // the returned point of K2, in K2's frame (W* = R V* + P)
  bool M_on_rim = false;
  bool V_on_rim = false;
  if (d_O_W0 < d_Mp_P) {
    // Step 3 (Proposition 1): M0*, the nearest point of K1 to W0*; answer (M0*, W0*).
    const NearestPointOnDisk step3 = proposition1(D1, W0);
    M_star = step3.point;
    M_on_rim = step3.on_rim;
    V_star = V0;
    V_on_rim = step1.on_rim;
  } else {
    // Step 4: Wp* = R Vp* + P, the nearest point of K2 to Mp*; answer (Mp*, Wp*).
    // Erratum: Appendix A says "using Proposition 2" for Mp* in K1; Mp* comes
    // from Proposition 1 (Step 2 above), and Vp* from Proposition 2 at Mp*.
    // Erratum: Case 1.2 assigns Mpx*, Mpy*; it is Vpx*, Vpy* (Mp* is unchanged).
    // Erratum: Case 2.1 subtracts D1; Vp* is on K2's rim, so it is D2.
    // proposition2() uses D2 and returns Vp* in both cases.
    const NearestPointOnDisk step4 = proposition2(D2, R, P, Mp);
    M_star = Mp;
    M_on_rim = step2.on_rim;
    V_star = step4.point;
    V_on_rim = step4.on_rim;
  }

  // Back to the world frame. Each point is mapped by its own disk's pose
  // (P2 + R2 V* equals P1 + R1 (R V* + P) in exact arithmetic) so that it lies
  // on its disk up to the rounding of this one product.
  const Vec3 p_W1 = P1 + R1 * M_star;
  const Vec3 p_W2 = P2 + R2 * V_star;
  result.p_W1 = p_W1.template cast<S>();
  result.p_W2 = p_W2.template cast<S>();

  // The distance is measured on the returned (rounded) pair, so it is the
  // length of a real pair of points: an upper bound on the true distance.
  const Vec3 returned_offset =
      result.p_W2.template cast<double>() - result.p_W1.template cast<double>();
  const double distance = returned_offset.norm();
  result.distance = static_cast<S>(distance);

  // The certificate's direction w is taken from the double pair before rounding
  // to S: the bound is non-smooth at w = +-n_i (r_i |P_i w| is a cone there), so
  // a direction perturbed by float rounding of the points would cost first-order
  // accuracy. At distance 0 the bound 0 is attained and w is undefined.
  const Vec3 w = p_W2 - p_W1;  // the certificate's direction, unnormalised
  const double w_norm = w.norm();
  result.lower_bound =
      (distance == 0.0 || w_norm == 0.0)
          ? S(0)
          : static_cast<S>(dualLowerBound<double>(w / w_norm, D1, X_W1d, D2, X_W2d));
  result.iterations = 0;  // closed form

  if (distance == 0.0) {
    result.feature = DiskPairFeature::intersecting;
  } else if (M_on_rim && V_on_rim) {
    result.feature = DiskPairFeature::rim_rim;
  } else if (!M_on_rim) {
    result.feature = DiskPairFeature::face1_rim2;  // p_W1 inside disk 1 (p_W2 on rim or face)
  } else {
    result.feature = DiskPairFeature::rim1_face2;
  }
  return result;
}

template DiskDistanceResult<float> almohamadSelimDiskDistance(float, const fcl::Transform3<float>&,
                                                              float, const fcl::Transform3<float>&);
template DiskDistanceResult<double> almohamadSelimDiskDistance(
    double, const fcl::Transform3<double>&, double, const fcl::Transform3<double>&);

}  // namespace fcl_disk

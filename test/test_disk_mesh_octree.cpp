// A Disk against triangle meshes (fcl::BVHModel, every BV type FCL traverses)
// and octrees (fcl::OcTree): fcl::distance and fcl::collide, in both argument
// orders, float and double, both gjk_solver_types, through objects, geometries
// and the broadphase, against brute force over every triangle or occupied cell:
//   - the independent long-double reference of reference_disk_shape.h (no code
//     shared with the solvers) on small meshes and octrees;
//   - fcl_disk::diskShapeDistance per triangle on larger meshes and more poses
//     (the leaf solver against itself: this checks FCL's traversal around it).
// FCL's GJK on the flat cylinder errs by ~1e-6 of the scene, so agreement to
// 1e-12 of the scene on these poses also shows that fcl_disk's solvers answer.
//
// Result conventions are FCL's: a shape-mesh pair is swapped into mesh-shape
// (fcl::distance / fcl::collide), and an octree is o1 of every octree-shape
// answer, so which of o1 / o2 is the disk depends on the pair, not on the
// argument order. The checks find the disk's side by identity and require the
// other side's id (b1 or b2) to be a triangle id or an occupied cell's id, with
// that side's point on that triangle or cell.
#include <fcl_disk/fcl_disk.h>

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/broadphase/default_broadphase_callbacks.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/octree/octree.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/bv/RSS.h>
#include <fcl/math/bv/kDOP.h>
#include <fcl/math/bv/kIOS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <set>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "disk_mesh_families.h"
#include "reference_disk_shape.h"
#include "test_random.h"

namespace {

namespace ref = fcl_disk_test::ref;
namespace fam = fcl_disk_test::mesh_families;
using fam::DiskPose;
using fam::Family;
using fam::bvhOf;
using fam::Mesh;
using ref::Real;
using ref::V3;
using Vector3d = Eigen::Vector3d;

// ---- tolerances -------------------------------------------------------------------

/// disk_shape_distance.h's guarantee for the disk-triangle and disk-box solvers
/// in double: 1e-12 of scale = r + R_E + |c_D - t_E|, with R_E the mesh's or
/// octree's bounding radius about its frame origin t_E (the largest |vertex|,
/// or |cell corner| over the occupied cells).
constexpr double kDoubleRelative = 1e-12;

/// Float: the solvers promote to double and round to float: 8 float ulps of
/// the scale, as test_disk_shape_accuracy.cpp (half an ulp per rounded
/// coordinate and distance, ~1 ulp for a float rotation being orthonormal only
/// to rounding).
constexpr double kFloatUlpsOfScale = 8;

/// Points are returned in world coordinates, each rounded by half an ulp of its
/// magnitude (up to max(|t_D|, |t_E|) + scale), so point checks get this many
/// eps of that magnitude on top of the relative bound (as
/// test_disk_shape_accuracy.cpp). Distances get no such term: every leaf sees
/// the disk posed relative to the mesh or octree (the difference of the
/// translations taken first), so nothing forces a world-scale rounding.
/// The term is ~1e-15 of the scale near the origin, 9e-11 (double) and 0.05
/// (float) at the far_away family's 1e5.
constexpr double kWorldRoundingEps = 4;

/// The traversal against the per-triangle brute force with the same leaf
/// solver: two answers, each within the bound of the truth.
constexpr double kTwoAnswers = 2;

/// The reference "says 0": its distance below this (relative to the scale; it
/// is good to ~1e-17 of the scale).
constexpr double kReferenceZeroRelative = 1e-15;

/// | |normal| - 1 |: the contact normal is normalised in double and stored in S
/// (test_tolerances.h, kUnitNormal).
constexpr double kUnitNormalUlps = 32;

/// Enough contacts for every triangle or cell a disk meets here.
constexpr std::size_t kAllContacts = 100000;

/// The reference against the distance fixed by construction (families
/// separated, touching, crossing): the construction is exact before the poses
/// are rounded to double, which moves the distance by a few eps of the world
/// coordinates involved (as test_disk_shape_accuracy.cpp's
/// kConstructionRoundingEps).
constexpr double kConstructionRoundingEps = 8;

/// At most this many failing cases are printed per check (the count always is).
constexpr int kMaxReportedFailures = 6;

constexpr std::uint64_t kSeed = 20250611;

template <typename S>
struct Tol {
  static constexpr bool kFloat = std::is_same<S, float>::value;
  static constexpr double kEps = std::numeric_limits<S>::epsilon();
  static constexpr double kRelative = kFloat ? kFloatUlpsOfScale * kEps : kDoubleRelative;
  static double relative(double scale) { return kRelative * scale; }
  static double world(double magnitude) { return kWorldRoundingEps * kEps * magnitude; }
};

const fcl::GJKSolverType kSolvers[] = {fcl::GST_LIBCCD, fcl::GST_INDEP};
const char* solverName(fcl::GJKSolverType s) { return s == fcl::GST_LIBCCD ? "libccd" : "indep"; }

// ---- printing -----------------------------------------------------------------------

std::string str(double x) {
  std::ostringstream out;
  out << std::setprecision(17) << x;
  return out.str();
}
template <typename Derived>
std::string str(const Eigen::MatrixBase<Derived>& m) {
  std::ostringstream out;
  out << std::setprecision(17) << "[";
  for (int i = 0; i < m.rows(); ++i) {
    if (i) out << "; ";
    for (int j = 0; j < m.cols(); ++j) out << (j ? ", " : "") << double(m(i, j));
  }
  out << "]";
  return out.str();
}
template <typename S>
std::string str(const fcl::Transform3<S>& X) {
  return "R " + str(X.linear()) + " t " + str(X.translation());
}

/// Collects the failures of one check; prints the first few in full.
class FailureLog {
 public:
  explicit FailureLog(std::string check) : check_(std::move(check)) {}
  FailureLog(const FailureLog&) = delete;
  void add(const std::string& message) {
    if (count_ < kMaxReportedFailures) ADD_FAILURE() << check_ << ": " << message;
    ++count_;
  }
  ~FailureLog() { EXPECT_EQ(count_, 0) << check_ << ": " << count_ << " failing cases in total"; }

 private:
  std::string check_;
  int count_ = 0;
};

// ---- FCL geometries -------------------------------------------------------------------


/// A mesh as a BVHModel of one BV type.
template <typename S>
struct BvMesh {
  const char* bv;
  std::shared_ptr<fcl::CollisionGeometry<S>> geometry;
};

template <typename S>
std::vector<BvMesh<S>> everyBv(const Mesh& mesh) {
  return {{"OBBRSS", bvhOf<fcl::OBBRSS<S>>(mesh)},
          {"RSS", bvhOf<fcl::RSS<S>>(mesh)},
          {"kIOS", bvhOf<fcl::kIOS<S>>(mesh)},
          {"OBB", bvhOf<fcl::OBB<S>>(mesh)},
          {"AABB", bvhOf<fcl::AABB<S>>(mesh)},
          {"KDOP16", bvhOf<fcl::KDOP<S, 16>>(mesh)},
          {"KDOP18", bvhOf<fcl::KDOP<S, 18>>(mesh)},
          {"KDOP24", bvhOf<fcl::KDOP<S, 24>>(mesh)}};
}

/// A mesh rounded to S with its BVHModels.
template <typename S>
struct MeshScene {
  Mesh mesh;
  std::vector<BvMesh<S>> bvs;
  explicit MeshScene(const Mesh& m) : mesh(fam::roundedMesh<S>(m)), bvs(everyBv<S>(mesh)) {}
};

/// An occupied leaf as FCL's octree traversals see it: the id FCL reports
/// (the node's offset from the root node) and the box in the tree's frame.
template <typename S>
struct OcCell {
  std::intptr_t id;
  fcl::AABB<S> box;
};

/// The leaves FCL's OcTreeShapeDistanceRecurse and OcTreeShapeIntersectRecurse
/// test (octree_solver-inl.h): from the root, through inner nodes that
/// fcl::OcTree::isNodeOccupied accepts, to leaves it accepts; boxes by FCL's
/// own getRootBV / computeChildBV, so they are FCL's to the last bit.
template <typename S>
std::vector<OcCell<S>> occupiedCells(const fcl::OcTree<S>& tree) {
  std::vector<OcCell<S>> out;
  const auto* root = tree.getRoot();
  const auto visit = [&](const auto& self, const typename fcl::OcTree<S>::OcTreeNode* node,
                         const fcl::AABB<S>& bv) -> void {
    if (!tree.isNodeOccupied(node)) return;
    if (!tree.nodeHasChildren(node)) {
      out.push_back({node - root, bv});
      return;
    }
    for (unsigned i = 0; i < 8; ++i) {
      if (!tree.nodeChildExists(node, i)) continue;
      fcl::AABB<S> child_bv;
      fcl::computeChildBV(bv, i, child_bv);
      self(self, tree.getNodeChild(node, i), child_bv);
    }
  };
  if (root) visit(visit, root, tree.getRootBV());
  return out;
}

/// An octree in S: FCL's wrapper of the octomap tree and its occupied cells.
template <typename S>
struct OcTreeScene {
  std::string name;
  std::shared_ptr<fcl::OcTree<S>> tree;
  std::vector<OcCell<S>> cells;
  std::map<std::intptr_t, int> index_of;  // FCL's id -> position in cells
  explicit OcTreeScene(const fam::OcTreeData& data)
      : name(data.name), tree(std::make_shared<fcl::OcTree<S>>(data.build())), cells(occupiedCells(*tree)) {
    for (int i = 0; i < int(cells.size()); ++i) index_of[cells[i].id] = i;
  }
  fam::Surface surface() const {
    std::vector<std::pair<Vector3d, Vector3d>> boxes;
    for (const auto& c : cells) boxes.emplace_back(c.box.min_.template cast<double>(), c.box.max_.template cast<double>());
    return fam::surfaceOfBoxes(boxes);
  }
};

// ---- the reference -------------------------------------------------------------------

template <typename S>
ref::Disk refDisk(S radius, const fcl::Transform3<S>& X_WD) {
  return ref::makeDisk(Real(radius), X_WD.linear().template cast<Real>(),
                       X_WD.translation().template cast<Real>());
}

template <typename S>
std::vector<ref::TriangleP> refTriangles(const Mesh& mesh, const fcl::Transform3<S>& X_WM) {
  std::vector<ref::TriangleP> out;
  for (int t = 0; t < int(mesh.triangles.size()); ++t) {
    ref::TriangleP tri;
    tri.R = X_WM.linear().template cast<Real>();
    tri.t = X_WM.translation().template cast<Real>();
    tri.a = mesh.vertex(t, 0).cast<Real>();
    tri.b = mesh.vertex(t, 1).cast<Real>();
    tri.c = mesh.vertex(t, 2).cast<Real>();
    out.push_back(tri);
  }
  return out;
}

template <typename S>
std::vector<ref::Box> refBoxes(const std::vector<OcCell<S>>& cells, const fcl::Transform3<S>& X_WO) {
  std::vector<ref::Box> out;
  for (const auto& c : cells) {
    ref::Box box;
    box.R = X_WO.linear().template cast<Real>();
    const V3 lo = c.box.min_.template cast<Real>(), hi = c.box.max_.template cast<Real>();
    box.t = box.R * ((lo + hi) / 2) + X_WO.translation().template cast<Real>();
    box.side = hi - lo;
    out.push_back(box);
  }
  return out;
}

std::vector<V3> worldCorners(const ref::TriangleP& t) {
  return {t.R * t.a + t.t, t.R * t.b + t.t, t.R * t.c + t.t};
}
std::vector<V3> worldCorners(const ref::Box& b) {
  std::vector<V3> out;
  for (int k = 0; k < 8; ++k) {
    const V3 local((k & 1 ? 1 : -1) * b.side.x() / 2, (k & 2 ? 1 : -1) * b.side.y() / 2,
                   (k & 4 ? 1 : -1) * b.side.z() / 2);
    out.push_back(b.R * local + b.t);
  }
  return out;
}

/// How far a reported point lies from a triangle, robust for slivers: the
/// reference's plane test needs the normal, known only to eps / sine for a
/// triangle of sine 1e-13 (1e-8 of its size in long double), while least
/// squares on the two edges (QR, backward stable) measures the point's
/// barycentric coordinates and its residual directly: inside (both >= 0, sum
/// <= 1) the residual is the distance, else the nearest edge.
Real offPiece(const V3& x, const ref::TriangleP& t) {
  const V3 y = t.R.transpose() * (x - t.t);
  Eigen::Matrix<Real, 3, 2> edges;
  edges.col(0) = t.b - t.a;
  edges.col(1) = t.c - t.a;
  const Eigen::Matrix<Real, 2, 1> vw = edges.colPivHouseholderQr().solve(y - t.a);
  if (vw.allFinite() && vw[0] >= 0 && vw[1] >= 0 && vw[0] + vw[1] <= 1) {
    return (edges * vw - (y - t.a)).norm();
  }
  V3 unused;
  return std::min({ref::detail::pointSegment(y, t.a, t.b, &unused), ref::detail::pointSegment(y, t.b, t.c, &unused),
                   ref::detail::pointSegment(y, t.c, t.a, &unused)});
}
Real offPiece(const V3& x, const ref::Box& b) { return ref::distanceToShape(x, b); }

/// A lower bound on the disk-piece distance from closed forms only: every disk
/// point is within r of the centre, and the disk lies in its plane while the
/// piece lies between its corners' heights over that plane.
template <typename Piece>
Real lowerBound(const ref::Disk& disk, const Piece& piece) {
  const Real by_centre = ref::distanceToShape(disk.c, piece) - disk.r;
  Real lo = std::numeric_limits<Real>::infinity(), hi = -lo;
  for (const V3& x : worldCorners(piece)) {
    const Real h = disk.n.dot(x - disk.c);
    lo = std::min(lo, h);
    hi = std::max(hi, h);
  }
  const Real by_plane = lo > 0 ? lo : hi < 0 ? -hi : Real(0);
  return std::max({by_centre, by_plane, Real(0)});
}

/// Brute force over the pieces (triangles or cells) of one set.
struct BruteForce {
  double distance = std::numeric_limits<double>::infinity();
  int nearest = -1;
  /// Per piece: its distance where evaluated, else a lower bound above the band.
  std::vector<double> piece;
  std::vector<bool> evaluated;
  /// Per piece: it meets the disk robustly, still at distance 0 when moved by
  /// sqrt(3) band along each of +-x, +-y, +-z. A pair that merely touches has a
  /// separating direction w, and one of those six moves has a component of at
  /// least band along w, leaving them >= band apart; so a robust piece must be
  /// reported by collide whatever the rounding within the band, and the others
  /// may go either way (the brief's band where either answer is right).
  std::vector<bool> robust;
  bool anyRobust() const { return std::find(robust.begin(), robust.end(), true) != robust.end(); }
};

template <typename Piece>
Piece moved(Piece piece, const V3& offset) {
  piece.t += offset;
  return piece;
}

/// The reference minimum over the pieces: every piece whose lower bound is
/// within max(best so far, band) gets the long-double reference, in order of
/// lower bounds (so the pruning never skips a piece that could be nearer or
/// that could touch within the band); pieces at distance 0 get the robustness
/// test above.
template <typename Piece>
BruteForce referenceBruteForce(const ref::Disk& disk, const std::vector<Piece>& pieces, double band,
                               double zero) {
  BruteForce out;
  const int n = int(pieces.size());
  out.piece.assign(n, 0);
  out.evaluated.assign(n, false);
  out.robust.assign(n, false);
  std::vector<Real> bound(n);
  for (int i = 0; i < n; ++i) bound[i] = lowerBound(disk, pieces[i]);
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return bound[a] < bound[b]; });
  Real best = std::numeric_limits<Real>::infinity();
  for (int i : order) {
    out.piece[i] = double(bound[i]);
    if (bound[i] > std::max(best, Real(band))) continue;
    const Real d = ref::referenceDistance(disk, pieces[i]).distance;
    out.piece[i] = double(d);
    out.evaluated[i] = true;
    if (d < best) best = d, out.nearest = i;
    if (d <= zero) {
      bool robust = true;
      for (int k = 0; k < 6 && robust; ++k) {
        V3 offset = V3::Zero();
        offset[k / 2] = (k % 2 ? -1 : 1) * std::sqrt(Real(3)) * band;
        robust = ref::referenceDistance(disk, moved(pieces[i], offset)).distance <= zero;
      }
      out.robust[i] = robust;
    }
  }
  out.distance = double(best);
  return out;
}

/// The same with fcl_disk::diskShapeDistance on every triangle (in S).
template <typename S>
BruteForce solverBruteForce(S radius, const fcl::Transform3<S>& X_WD, const Mesh& mesh,
                            const fcl::Transform3<S>& X_WM) {
  BruteForce out;
  for (int t = 0; t < int(mesh.triangles.size()); ++t) {
    const fcl::TriangleP<S> tri(mesh.vertex(t, 0).cast<S>(), mesh.vertex(t, 1).cast<S>(),
                                mesh.vertex(t, 2).cast<S>());
    const double d = double(fcl_disk::diskShapeDistance(radius, X_WD, tri, X_WM).distance);
    out.piece.push_back(d);
    out.evaluated.push_back(true);
    out.robust.push_back(false);
    if (d < out.distance) out.distance = d, out.nearest = t;
  }
  return out;
}

// ---- cases ------------------------------------------------------------------------------

template <typename S>
std::string sceneName(const MeshScene<S>& scene, double scale) {
  return "mesh " + scene.mesh.name + " (" + std::to_string(scene.mesh.triangles.size()) +
         " triangles, scaled by " + str(scale) + ")";
}
template <typename S>
std::string sceneName(const OcTreeScene<S>& scene, double) {
  return "octree " + scene.name + " (" + std::to_string(scene.cells.size()) + " occupied cells)";
}

/// One disk pose against a mesh or an octree, rounded to S, with its brute force.
template <typename S, typename Scene, typename Piece>
struct Case {
  std::shared_ptr<const Scene> scene;
  DiskPose pose;
  S radius;
  fcl::Transform3<S> X_WD, X_WE;
  ref::Disk disk;
  std::vector<Piece> pieces;  // the triangles or cells, posed in the world
  double scale;               // r + R_E + |c_D - t_E|
  double world;               // max(|t_D|, |t_E|) + scale: the world coordinates' magnitude
  BruteForce truth;

  std::string describe() const {
    return std::string(fam::familyName(pose.family)) + " (" + pose.detail + "): disk radius " +
           str(double(radius)) + " X_WD " + str(X_WD) + "; " + sceneName(*scene, pose.scale) + " X_WE " + str(X_WE) +
           "; scale " + str(scale) + ", reference distance " + str(truth.distance);
  }
};

template <typename S>
using MeshCase = Case<S, MeshScene<S>, ref::TriangleP>;
template <typename S>
using OcTreeCase = Case<S, OcTreeScene<S>, ref::Box>;

/// The pose, rounded to S, with its posed pieces and scale; no brute force yet.
template <typename S, typename Scene, typename Piece>
Case<S, Scene, Piece> makeCase(std::shared_ptr<const Scene> scene, const DiskPose& pose,
                               std::vector<Piece> pieces, double bounding_radius) {
  Case<S, Scene, Piece> c;
  c.scene = std::move(scene);
  c.pose = pose;
  c.radius = S(pose.radius);
  c.X_WD = pose.X_WD.cast<S>();
  c.X_WE = pose.X_WE.cast<S>();
  c.disk = refDisk(c.radius, c.X_WD);
  c.pieces = std::move(pieces);
  const Vector3d t_D = c.X_WD.translation().template cast<double>();
  const Vector3d t_E = c.X_WE.translation().template cast<double>();
  c.scale = double(c.radius) + bounding_radius + (t_D - t_E).norm();
  c.world = std::max(t_D.norm(), t_E.norm()) + c.scale;
  return c;
}

/// The band of the brute force: the largest tolerance any check applies.
template <typename S>
double widestBand(double scale, double world) {
  return kTwoAnswers * Tol<S>::relative(scale) + Tol<S>::world(world);
}

std::vector<Mesh> referenceMeshes() {
  return {fam::triangleSoup(30, kSeed), fam::boxMesh(), fam::sphereMesh(6, 4),
          fam::degenerateMesh(24, kSeed + 1), fam::terrainMesh(4)};
}

/// Disk poses against each mesh, every family; the scaled family gets its own
/// scaled copy of the mesh.
template <typename S>
std::vector<MeshCase<S>> meshCases(const std::vector<Mesh>& meshes, int per_family, bool with_reference) {
  std::vector<MeshCase<S>> out;
  for (int m = 0; m < int(meshes.size()); ++m) {
    const auto scene = std::make_shared<const MeshScene<S>>(meshes[m]);
    const fam::Surface surface = fam::surfaceOf(meshes[m]);
    const fcl::Transform3<double> X_WM = fam::randomFrame(kSeed + 100 + m);
    for (Family f : fam::allFamilies()) {
      for (const DiskPose& pose : fam::diskPoses(surface, X_WM, f, per_family, 0.15, 0.8, kSeed + 10 * m)) {
        const auto posed = pose.scale == 1
                               ? scene
                               : std::make_shared<const MeshScene<S>>(fam::scaledMesh(meshes[m], pose.scale));
        auto c = makeCase<S, MeshScene<S>, ref::TriangleP>(
            posed, pose, refTriangles(posed->mesh, fcl::Transform3<S>(pose.X_WE.cast<S>())),
            posed->mesh.boundingRadius());
        c.truth = with_reference ? referenceBruteForce(c.disk, c.pieces, widestBand<S>(c.scale, c.world),
                                                       kReferenceZeroRelative * c.scale)
                                 : solverBruteForce(c.radius, c.X_WD, posed->mesh, c.X_WE);
        out.push_back(std::move(c));
      }
    }
  }
  return out;
}

/// Reference cases are shared by the distance and the collision test (computed
/// once per process and scalar): 6 poses per family and mesh in double, 3 in
/// float.
template <typename S>
const std::vector<MeshCase<S>>& referencedMeshCases() {
  static const std::vector<MeshCase<S>> cases =
      meshCases<S>(referenceMeshes(), Tol<S>::kFloat ? 3 : 6, /*with_reference=*/true);
  return cases;
}

std::vector<fam::OcTreeData> referenceOcTrees() { return {fam::blobOcTree(kSeed), fam::wallOcTree()}; }

template <typename S>
const std::vector<OcTreeCase<S>>& referencedOcTreeCases() {
  static const std::vector<OcTreeCase<S>> cases = [] {
    std::vector<OcTreeCase<S>> out;
    const auto trees = referenceOcTrees();
    for (int m = 0; m < int(trees.size()); ++m) {
      const auto scene = std::make_shared<const OcTreeScene<S>>(trees[m]);
      const fam::Surface surface = scene->surface();
      const fcl::Transform3<double> X_WO = fam::randomFrame(kSeed + 200 + m);
      // The scaled family needs a scaled tree (octomap resolution): left to the
      // mesh cases, which cover the solver's length scales.
      for (Family f : fam::allFamilies()) {
        if (f == Family::scaled) continue;
        const int count = Tol<S>::kFloat ? 4 : 8;
        for (const DiskPose& pose : fam::diskPoses(surface, X_WO, f, count, 0.05, 0.3, kSeed + 20 * m)) {
          auto c = makeCase<S, OcTreeScene<S>, ref::Box>(
              scene, pose, refBoxes(scene->cells, fcl::Transform3<S>(pose.X_WE.cast<S>())),
              surface.bounding_radius);
          c.truth = referenceBruteForce(c.disk, c.pieces, widestBand<S>(c.scale, c.world),
                                        kReferenceZeroRelative * c.scale);
          out.push_back(std::move(c));
        }
      }
    }
    return out;
  }();
  return cases;
}

// ---- queries --------------------------------------------------------------------------

/// fcl::distance on objects in the given order, and on geometries, which must
/// agree bit for bit (the same traversal behind both entry points).
template <typename S>
fcl::DistanceResult<S> fclDistance(const std::shared_ptr<fcl_disk::Disk<S>>& disk,
                                   const fcl::Transform3<S>& X_WD,
                                   const std::shared_ptr<fcl::CollisionGeometry<S>>& other,
                                   const fcl::Transform3<S>& X_WE, bool disk_first,
                                   fcl::GJKSolverType solver, std::string* mismatch) {
  fcl::CollisionObject<S> a(disk, X_WD), b(other, X_WE);
  fcl::DistanceRequest<S> request(true);
  request.gjk_solver_type = solver;
  fcl::DistanceResult<S> by_objects, by_geometries;
  const S returned = disk_first ? fcl::distance(&a, &b, request, by_objects)
                                : fcl::distance(&b, &a, request, by_objects);
  if (disk_first) {
    fcl::distance(disk.get(), X_WD, other.get(), X_WE, request, by_geometries);
  } else {
    fcl::distance(other.get(), X_WE, disk.get(), X_WD, request, by_geometries);
  }
  const auto same = [](S x, S y) { return x == y || (std::isnan(x) && std::isnan(y)); };
  const auto same_point = [&](const fcl::Vector3<S>& x, const fcl::Vector3<S>& y) {
    return same(x[0], y[0]) && same(x[1], y[1]) && same(x[2], y[2]);
  };
  if (!same(returned, by_objects.min_distance)) {
    *mismatch = "fcl::distance returned " + str(double(returned)) + " but min_distance is " +
                str(double(by_objects.min_distance));
  } else if (!same(by_objects.min_distance, by_geometries.min_distance) ||
             !same_point(by_objects.nearest_points[0], by_geometries.nearest_points[0]) ||
             !same_point(by_objects.nearest_points[1], by_geometries.nearest_points[1]) ||
             by_objects.b1 != by_geometries.b1 || by_objects.b2 != by_geometries.b2) {
    *mismatch = "objects and geometries disagree: " + str(double(by_objects.min_distance)) + " vs " +
                str(double(by_geometries.min_distance));
  }
  return by_objects;
}

template <typename S>
fcl::CollisionResult<S> fclCollide(const std::shared_ptr<fcl_disk::Disk<S>>& disk,
                                   const fcl::Transform3<S>& X_WD,
                                   const std::shared_ptr<fcl::CollisionGeometry<S>>& other,
                                   const fcl::Transform3<S>& X_WE, bool disk_first,
                                   const fcl::CollisionRequest<S>& request, std::size_t* returned) {
  fcl::CollisionObject<S> a(disk, X_WD), b(other, X_WE);
  fcl::CollisionResult<S> result;
  *returned = disk_first ? fcl::collide(&a, &b, request, result) : fcl::collide(&b, &a, request, result);
  return result;
}

/// Which side (0 = o1, 1 = o2) of an answer is the disk: exactly one must be.
/// The other is the mesh or octree; only "not the disk" is required of it, as
/// FCL's own AABB, OBB and k-DOP traversals report a temporary copy of the mesh.
template <typename S>
int diskSide(const fcl::CollisionGeometry<S>* o1, const fcl::CollisionGeometry<S>* o2,
             const fcl::CollisionGeometry<S>* disk) {
  if ((o1 == disk) == (o2 == disk)) return -1;
  return o1 == disk ? 0 : 1;
}

/// Whether `id` names a piece of the case (a triangle index, an occupied cell's
/// id); its position in the pieces.
template <typename S>
int pieceIndex(const MeshCase<S>& c, std::intptr_t id) {
  return id >= 0 && id < std::intptr_t(c.pieces.size()) ? int(id) : -1;
}
template <typename S>
int pieceIndex(const OcTreeCase<S>& c, std::intptr_t id) {
  const auto it = c.scene->index_of.find(id);
  return it == c.scene->index_of.end() ? -1 : it->second;
}

// ---- distance checks ------------------------------------------------------------------

/// All distance checks on one answer, logged per kind.
struct DistanceLogs {
  FailureLog distance{"distance vs brute force"};
  FailureLog sides{"o1 / o2 / b1 / b2: the disk and a triangle or occupied cell"};
  FailureLog points{"nearest points on the disk and on the reported triangle or cell"};
  FailureLog pair{"|p - q| == distance"};
  FailureLog entry{"fcl::distance entry points agree"};
};

/// Checks an answer against the brute force: `distance_tolerance` on the
/// distance, `point_tolerance` on the points.
template <typename S, typename C>
void checkDistanceAnswer(const C& c, const fcl_disk::Disk<S>* disk, const fcl::DistanceResult<S>& r,
                         const std::string& mismatch, double distance_tolerance, double point_tolerance,
                         const std::string& what, DistanceLogs* logs) {
  const auto context = [&] { return " [" + what + "] " + c.describe(); };
  if (!mismatch.empty()) logs->entry.add(mismatch + context());
  const double d = double(r.min_distance);
  if (!(std::abs(d - c.truth.distance) <= distance_tolerance)) {
    logs->distance.add("got " + str(d) + ", error " + str((d - c.truth.distance) / c.scale) +
                       " * scale (tolerance " + str(distance_tolerance / c.scale) + " * scale)" + context());
  }
  const int side = diskSide<S>(r.o1, r.o2, disk);
  if (side < 0) {
    logs->sides.add("neither or both of o1, o2 is the disk" + context());
    return;
  }
  const std::intptr_t disk_id = side == 0 ? r.b1 : r.b2, other_id = side == 0 ? r.b2 : r.b1;
  const int piece = pieceIndex(c, other_id);
  if (disk_id != fcl::DistanceResult<S>::NONE || piece < 0) {
    logs->sides.add("disk side b = " + std::to_string(disk_id) + ", other side b = " +
                    std::to_string(other_id) + " (not a triangle or occupied cell)" + context());
    return;
  }
  const V3 p = r.nearest_points[side].template cast<Real>();
  const V3 q = r.nearest_points[1 - side].template cast<Real>();
  const double off_disk = double(ref::distanceToDisk(p, c.disk));
  const double off_piece = double(offPiece(q, c.pieces[piece]));
  if (!(off_disk <= point_tolerance && off_piece <= point_tolerance)) {
    logs->points.add("disk point " + str(p) + " is " + str(off_disk) + " from the disk, point " + str(q) +
                     " is " + str(off_piece) + " from piece " + std::to_string(piece) + " (tolerance " +
                     str(point_tolerance) + ")" + context());
  }
  const double gap = double((q - p).norm());
  if (!(std::abs(gap - d) <= point_tolerance + Tol<S>::world(c.world))) {
    logs->pair.add("|p - q| = " + str(gap) + ", distance " + str(d) + context());
  }
}

template <typename S>
void checkMeshDistances(const std::vector<MeshCase<S>>& cases, double brute_force_factor) {
  DistanceLogs logs;
  for (const auto& c : cases) {
    auto disk = std::make_shared<fcl_disk::Disk<S>>(c.radius);
    for (const auto& bv : c.scene->bvs) {
      const double distance_tolerance = brute_force_factor * Tol<S>::relative(c.scale);
      const double point_tolerance = brute_force_factor * Tol<S>::relative(c.scale) + Tol<S>::world(c.world);
      for (const bool disk_first : {true, false}) {
        for (const auto solver : kSolvers) {
          std::string mismatch;
          const auto r = fclDistance<S>(disk, c.X_WD, bv.geometry, c.X_WE, disk_first, solver, &mismatch);
          checkDistanceAnswer(c, disk.get(), r, mismatch, distance_tolerance, point_tolerance,
                              std::string(bv.bv) + (disk_first ? ", disk first, " : ", mesh first, ") +
                                  solverName(solver),
                              &logs);
        }
      }
    }
  }
}

// ---- collision checks ---------------------------------------------------------------

struct CollisionLogs {
  FailureLog decision{"collide: intersecting iff the brute force says distance 0"};
  FailureLog count{"number of contacts (<= num_max_contacts, every touching piece when unlimited)"};
  FailureLog sides{"contact o1 / o2 / b1 / b2: the disk and a touching triangle or cell"};
  FailureLog pos{"contact pos on the disk and on the reported triangle or cell"};
  FailureLog normal{"contact normal unit, depth finite and >= 0"};
};

/// Checks fcl::collide on one case against its brute force, every request
/// variant (contacts on / off, one / all contacts): a collision if some piece
/// meets the disk robustly (BruteForce::robust), none if the set is farther
/// than `band`; contacts only for pieces within `band`, and with all contacts
/// asked for, one for each robust piece.
template <typename S, typename C>
void checkCollisions(const C& c, const std::shared_ptr<fcl::CollisionGeometry<S>>& other, double band,
                     double point_tolerance, bool one_contact_per_piece, const std::string& what,
                     CollisionLogs* logs) {
  auto disk = std::make_shared<fcl_disk::Disk<S>>(c.radius);
  for (const bool disk_first : {true, false}) {
    for (const auto solver : kSolvers) {
      for (const bool enable_contact : {false, true}) {
        for (const std::size_t max_contacts : {std::size_t(1), kAllContacts}) {
          fcl::CollisionRequest<S> request(max_contacts, enable_contact);
          request.gjk_solver_type = solver;
          std::size_t returned = 0;
          const auto r = fclCollide<S>(disk, c.X_WD, other, c.X_WE, disk_first, request, &returned);
          const std::string context = " [" + what + (disk_first ? ", disk first, " : ", other first, ") +
                                      solverName(solver) + (enable_contact ? ", contacts" : ", no contacts") +
                                      ", max " + std::to_string(max_contacts) + "] " + c.describe();
          const bool hit = r.isCollision();
          if ((hit && c.truth.distance > band) || (!hit && c.truth.anyRobust())) {
            logs->decision.add(std::string("collide says ") + (hit ? "intersecting" : "apart") + context);
          }
          if (returned != r.numContacts() || r.numContacts() > max_contacts) {
            logs->count.add("returned " + std::to_string(returned) + ", " + std::to_string(r.numContacts()) +
                            " contacts" + context);
          }
          std::set<int> reported;
          for (std::size_t k = 0; k < r.numContacts(); ++k) {
            const fcl::Contact<S>& contact = r.getContact(k);
            const int side = diskSide<S>(contact.o1, contact.o2, disk.get());
            const std::intptr_t disk_id = side == 0 ? contact.b1 : contact.b2;
            const std::intptr_t other_id = side == 0 ? contact.b2 : contact.b1;
            const int piece = side < 0 ? -1 : pieceIndex(c, other_id);
            if (side < 0 || disk_id != fcl::Contact<S>::NONE || piece < 0 || !(c.truth.piece[piece] <= band) ||
                (one_contact_per_piece && reported.count(piece))) {
              logs->sides.add("contact " + std::to_string(k) + ": disk side " + std::to_string(side) +
                              ", ids " + std::to_string(contact.b1) + ", " + std::to_string(contact.b2) +
                              (piece >= 0 ? ", piece at distance " + str(c.truth.piece[piece]) : std::string()) +
                              context);
              continue;
            }
            reported.insert(piece);
            if (!enable_contact) continue;  // FCL leaves pos and normal unset then
            const V3 pos = contact.pos.template cast<Real>();
            const double off_disk = double(ref::distanceToDisk(pos, c.disk));
            const double off_piece = double(offPiece(pos, c.pieces[piece]));
            if (!(off_disk <= point_tolerance && off_piece <= point_tolerance)) {
              logs->pos.add("contact " + std::to_string(k) + " pos " + str(pos) + " is " + str(off_disk) +
                            " from the disk and " + str(off_piece) + " from piece " + std::to_string(piece) +
                            " (tolerance " + str(point_tolerance) + ")" + context);
            }
            const double length = double(contact.normal.norm());
            if (!(std::abs(length - 1) <= kUnitNormalUlps * Tol<S>::kEps) ||
                !(std::isfinite(double(contact.penetration_depth)) && contact.penetration_depth >= 0)) {
              logs->normal.add("contact " + std::to_string(k) + " |normal| " + str(length) + ", depth " +
                               str(double(contact.penetration_depth)) + context);
            }
          }
          if (max_contacts == kAllContacts) {
            for (int i = 0; i < int(c.pieces.size()); ++i) {
              if (c.truth.robust[i] && !reported.count(i)) {
                logs->count.add("piece " + std::to_string(i) + " meets the disk robustly but has no contact" +
                                context);
              }
            }
          }
        }
      }
    }
  }
}

// ---- typed suites ------------------------------------------------------------------

template <typename S>
class DiskMesh : public ::testing::Test {};
template <typename S>
class DiskOcTree : public ::testing::Test {};
template <typename S>
class DiskEnvironment : public ::testing::Test {};
using ScalarTypes = ::testing::Types<double, float>;
TYPED_TEST_SUITE(DiskMesh, ScalarTypes);
TYPED_TEST_SUITE(DiskOcTree, ScalarTypes);
TYPED_TEST_SUITE(DiskEnvironment, ScalarTypes);

// Distance to small meshes (a soup, a box, a sphere, degenerate triangles, a
// terrain the disks cut through) on every family of poses, every BV type, both
// orders, both solvers, objects and geometries, against the long-double
// reference over every triangle.
TYPED_TEST(DiskMesh, DistanceMatchesIndependentReferenceForEveryBv) {
  using S = TypeParam;
  checkMeshDistances<S>(referencedMeshCases<S>(), 1);
  if (Tol<S>::kFloat) return;  // float poses are rounded after the construction
  FailureLog construction("reference vs constructed distance");
  for (const auto& c : referencedMeshCases<S>()) {
    const double tolerance = kConstructionRoundingEps * std::numeric_limits<double>::epsilon() * c.world;
    if (!std::isnan(c.pose.known_distance) && !(std::abs(c.truth.distance - c.pose.known_distance) <= tolerance)) {
      construction.add("constructed " + str(c.pose.known_distance) + " " + c.describe());
    }
  }
}

// Larger meshes (a few hundred triangles) and more poses, against the minimum
// of diskShapeDistance over every triangle: the traversal finds the nearest
// triangle for every BV type.
TYPED_TEST(DiskMesh, DistanceTraversalFindsTheNearestTriangle) {
  using S = TypeParam;
  const std::vector<Mesh> meshes = {fam::triangleSoup(200, kSeed + 2), fam::sphereMesh(16, 12),
                                    fam::terrainMesh(10), fam::degenerateMesh(120, kSeed + 3)};
  checkMeshDistances<S>(meshCases<S>(meshes, Tol<S>::kFloat ? 6 : 12, /*with_reference=*/false), kTwoAnswers);
}

// fcl::collide against the reference cases: intersecting iff the reference says
// distance 0 (within the band), one contact per touching triangle, on both sets.
TYPED_TEST(DiskMesh, CollideAgreesWithReference) {
  using S = TypeParam;
  CollisionLogs logs;
  for (const auto& c : referencedMeshCases<S>()) {
    for (const auto& bv : c.scene->bvs) {
      const double band = Tol<S>::relative(c.scale);
      const double point_tolerance = Tol<S>::relative(c.scale) + Tol<S>::world(c.world);
      checkCollisions<S>(c, bv.geometry, band, point_tolerance, /*one_contact_per_piece=*/true, bv.bv, &logs);
    }
  }
}

// Distance to octrees (random blobs at resolution 0.05, a wall at 0.1; free,
// uncertain and exactly-at-threshold cells among the occupied ones) in a
// non-identity pose, on every family of poses but `scaled`, both orders, both
// solvers, objects and geometries, against the long-double reference over
// every occupied leaf as FCL's traversal finds them; the reported cell is one
// of those leaves and holds the reported point.
TYPED_TEST(DiskOcTree, DistanceMatchesIndependentReferenceOverOccupiedCells) {
  using S = TypeParam;
  DistanceLogs logs;
  for (const auto& c : referencedOcTreeCases<S>()) {
    auto disk = std::make_shared<fcl_disk::Disk<S>>(c.radius);
    const double tolerance = Tol<S>::relative(c.scale);
    const double point_tolerance = tolerance + Tol<S>::world(c.world);
    for (const bool disk_first : {true, false}) {
      for (const auto solver : kSolvers) {
        std::string mismatch;
        const auto r = fclDistance<S>(disk, c.X_WD, c.scene->tree, c.X_WE, disk_first, solver, &mismatch);
        checkDistanceAnswer(c, disk.get(), r, mismatch, tolerance, point_tolerance,
                            std::string(disk_first ? "disk first, " : "octree first, ") + solverName(solver),
                            &logs);
      }
    }
  }
}

// fcl::collide against the octree reference cases: intersecting iff the
// reference says distance 0 (within the band), contacts only on cells that meet
// the disk, each pos on the disk and in its cell.
TYPED_TEST(DiskOcTree, CollideAgreesWithReference) {
  using S = TypeParam;
  CollisionLogs logs;
  for (const auto& c : referencedOcTreeCases<S>()) {
    const double band = Tol<S>::relative(c.scale) + Tol<S>::world(c.world);
    checkCollisions<S>(c, c.scene->tree, band, band, /*one_contact_per_piece=*/false, "octree", &logs);
  }
}

// ---- hand-made contacts: the normal's direction ---------------------------------------

/// The unit vector from the disk towards o2's side when the disk is o1, and
/// the reverse when it is o2: FCL's normals point from o1 to o2.
Vector3d fromO1ToO2(int disk_side, const Vector3d& disk_to_other) {
  return disk_side == 0 ? disk_to_other : Vector3d(-disk_to_other);
}

// A horizontal disk of radius 0.3 poking 0.1 through a vertical plate (two
// triangles in the plane x = 0, the chord well inside one of them): the
// smallest separating move takes the disk 0.1 along +x, so the contact's
// normal is +x from the mesh to the disk (FCL: from o1 to o2) with depth at
// most 0.1. The same for an octree: a disk of radius 0.04 poking 0.01 into
// one cell of a wall, from its free side. In the mesh's / tree's frame, posed
// at random in the world.
TYPED_TEST(DiskEnvironment, ContactNormalPointsFromO1ToO2) {
  using S = TypeParam;
  const double tolerance = 64 * Tol<S>::kEps;  // unit-size scenes: a few ulps
  Mesh plate;
  plate.name = "plate";
  plate.vertices = {{0, -1, -1}, {0, 1, -1}, {0, 1, 1}, {0, -1, 1}};
  plate.triangles = {{0, 1, 2}, {0, 2, 3}};  // diagonal y = z
  const MeshScene<S> mesh(plate);
  const OcTreeScene<S> wall(fam::wallOcTree());
  // The wall's cell (0, 2, 1): x in [0, 0.1], y in [0.2, 0.3], z in [0.1, 0.2].
  std::intptr_t cell_id = 0;  // FCL's ids are node offsets from the root, of either sign
  bool found = false;
  for (const auto& c : wall.cells) {
    if (c.box.min_.x() < S(0.05) && c.box.max_.x() > S(0.05) && c.box.min_.y() < S(0.25) &&
        c.box.max_.y() > S(0.25) && c.box.min_.z() < S(0.15) && c.box.max_.z() > S(0.15)) {
      cell_id = c.id, found = true;
    }
  }
  ASSERT_TRUE(found) << "the wall's cell (0, 2, 1) is not occupied";
  for (int trial = 0; trial < int(mesh.bvs.size()); ++trial) {  // every BV type of the plate
    const fcl::Transform3<double> X_WE = fam::randomFrame(kSeed + 300 + trial);
    struct Setup {
      std::string name;
      std::shared_ptr<fcl::CollisionGeometry<S>> geometry;
      double radius, depth;
      Vector3d centre;       // frame E
      std::intptr_t piece;   // the one triangle or cell met
    };
    const Setup setups[] = {
        {std::string("plate ") + mesh.bvs[trial].bv, mesh.bvs[trial].geometry, 0.3, 0.1, Vector3d(0.2, 0.5, -0.4), 0},
        {"octree wall", wall.tree, 0.04, 0.01, Vector3d(0.13, 0.25, 0.15), cell_id}};
    for (const auto& setup : setups) {
      const fcl::Transform3<S> X_WES = X_WE.cast<S>();
      fcl::Transform3<S> X_WD = X_WES;  // horizontal in frame E
      X_WD.translation() = (X_WE * setup.centre).template cast<S>();
      const Vector3d plus_x = X_WE.linear().col(0);  // frame E's +x: from the set towards the disk
      auto disk = std::make_shared<fcl_disk::Disk<S>>(S(setup.radius));
      for (const bool disk_first : {true, false}) {
        for (const auto solver : kSolvers) {
          SCOPED_TRACE(setup.name + (disk_first ? ", disk first, " : ", other first, ") + solverName(solver) +
                       ", frame " + str(X_WES));
          fcl::CollisionRequest<S> request(kAllContacts, true);
          request.gjk_solver_type = solver;
          std::size_t returned = 0;
          const auto r = fclCollide<S>(disk, X_WD, setup.geometry, X_WES, disk_first, request, &returned);
          ASSERT_EQ(r.numContacts(), 1u);
          const auto& contact = r.getContact(0);
          const int side = diskSide<S>(contact.o1, contact.o2, disk.get());
          ASSERT_GE(side, 0);
          EXPECT_EQ(side == 0 ? contact.b2 : contact.b1, setup.piece);
          // From o1 to o2: out of the set towards the disk when the set is o1.
          const Vector3d expected = fromO1ToO2(side, -plus_x);
          EXPECT_GT(contact.normal.template cast<double>().dot(expected), 1 - tolerance)
              << "normal " << str(contact.normal) << ", expected " << str(expected);
          EXPECT_GT(double(contact.penetration_depth), 0.0);
          EXPECT_LE(double(contact.penetration_depth), setup.depth + tolerance);
        }
      }
    }
  }
}

// ---- cost sources ------------------------------------------------------------------

// With enable_cost, FCL reports cost sources where the disk meets the set
// (octree_solver-inl.h, mesh_shape_collision_traversal_node-inl.h): for a
// mesh, each triangle it crosses; for an octree, the unknown space (nodes
// that do not exist) inside occupied nodes, while existing free leaves cost
// nothing. So a disk cutting through the wall or the terrain gets some, one in
// the unknown space far from the wall gets some, one inside a free cell of the
// wall and one far from the terrain get none. Each source's box is the overlap
// of the disk's box with the triangle's or cell's, so it lies in the disk's
// bounding cube (half-width sqrt(2) r).
TYPED_TEST(DiskEnvironment, CostSourcesWhereTheDiskMeetsTheSet) {
  using S = TypeParam;
  const OcTreeScene<S> wall(fam::wallOcTree());
  const MeshScene<S> terrain(fam::terrainMesh(4));
  const fcl::Transform3<double> X_WE = fam::randomFrame(kSeed + 400);
  // A disk in frame E with the given centre and normal.
  const auto disk_at = [&](const Vector3d& centre, const Vector3d& normal) {
    fcl::Transform3<double> X = X_WE;
    X.linear() = X_WE.linear() * Eigen::Quaterniond::FromTwoVectors(Vector3d::UnitZ(), normal).toRotationMatrix();
    X.translation() = X_WE * centre;
    return X.cast<S>();
  };
  struct Setup {
    std::string name;
    std::shared_ptr<fcl::CollisionGeometry<S>> geometry;
    double radius;
    fcl::Transform3<S> X_WD;
    bool costs;
  };
  const Setup setups[] = {
      // Standing across the wall at its cell (0, 2, 1), reaching into the
      // unknown halves of the wall's nodes on both sides.
      {"across the wall", wall.tree, 0.3, disk_at({0.05, 0.25, 0.15}, Vector3d::UnitY()), true},
      {"unknown space far from the wall", wall.tree, 0.3, disk_at({5, 5, 5}, Vector3d::UnitZ()), true},
      // Inside the free cell (1, 0, 0): x in [0.1, 0.2], y and z in [0, 0.1].
      {"inside a free cell", wall.tree, 0.02, disk_at({0.15, 0.05, 0.05}, Vector3d::UnitZ()), false},
      {"across the terrain", terrain.bvs[0].geometry, 0.3, disk_at({0.1, 0.1, 0.0}, Vector3d::UnitX()), true},
      {"far from the terrain", terrain.bvs[0].geometry, 0.3, disk_at({5, 5, 5}, Vector3d::UnitZ()), false}};
  for (const auto& setup : setups) {
    auto disk = std::make_shared<fcl_disk::Disk<S>>(S(setup.radius));
    for (const bool disk_first : {true, false}) {
      SCOPED_TRACE(setup.name + (disk_first ? ", disk first" : ", other first"));
      fcl::CollisionRequest<S> request(kAllContacts, true, /*num_max_cost_sources=*/1000, /*enable_cost=*/true);
      std::size_t returned = 0;
      auto r = fclCollide<S>(disk, setup.X_WD, setup.geometry, fcl::Transform3<S>(X_WE.cast<S>()), disk_first,
                             request, &returned);
      std::vector<fcl::CostSource<S>> sources;
      r.getCostSources(sources);
      EXPECT_EQ(!sources.empty(), setup.costs) << sources.size() << " cost sources";
      const Vector3d c = setup.X_WD.translation().template cast<double>();
      const double half = std::sqrt(2.0) * setup.radius * (1 + 1e-5);
      for (const auto& source : sources) {
        for (int i = 0; i < 3; ++i) {
          EXPECT_LE(double(source.aabb_min[i]), double(source.aabb_max[i]));
          EXPECT_GE(double(source.aabb_min[i]), c[i] - half);
          EXPECT_LE(double(source.aabb_max[i]), c[i] + half);
        }
      }
    }
  }
}

// ---- broadphase ----------------------------------------------------------------------

// A DynamicAABBTreeCollisionManager holding three meshes (OBBRSS, AABB, KDOP24),
// an octree and three disks; disks queried against it with FCL's default
// callbacks: the nearest distance is the minimum over the objects of the
// brute force (diskShapeDistance per triangle and per occupied cell,
// exactDiskDistance per disk), and collide reports a collision iff that is 0.
TYPED_TEST(DiskEnvironment, BroadphaseNearestDistanceAndCollisionMatchBruteForce) {
  using S = TypeParam;
  using Transform = fcl::Transform3<S>;
  struct Placed {
    Mesh mesh;  // rounded to S
    Transform X;
    std::shared_ptr<fcl::CollisionGeometry<S>> geometry;
  };
  const MeshScene<S> box(fam::boxMesh()), sphere(fam::sphereMesh(8, 6)), soup(fam::triangleSoup(40, kSeed + 5));
  const std::vector<Placed> meshes = {
      {box.mesh, fam::randomFrame(kSeed + 500).cast<S>(), box.bvs[0].geometry},
      {sphere.mesh, (fam::randomFrame(kSeed + 501) * Eigen::Translation3d(2.5, 0, 0)).cast<S>(), sphere.bvs[4].geometry},
      {soup.mesh, (fam::randomFrame(kSeed + 502) * Eigen::Translation3d(0, -2.5, 0)).cast<S>(), soup.bvs[7].geometry}};
  const OcTreeScene<S> blobs(fam::blobOcTree(kSeed + 6));
  const Transform X_WO = (fam::randomFrame(kSeed + 503) * Eigen::Translation3d(0, 0, 2.5)).cast<S>();
  fcl_disk_test::Random rng(kSeed + 7);
  std::vector<std::pair<S, Transform>> scene_disks;
  for (int i = 0; i < 3; ++i) {
    scene_disks.emplace_back(S(rng.uniform(0.2, 0.6)),
                             fam::poseOf(rng.rotation(), Vector3d(-2.5, 0, 0) + rng.inBall(1.0)).cast<S>());
  }

  fcl::DynamicAABBTreeCollisionManager<S> manager;
  std::vector<std::unique_ptr<fcl::CollisionObject<S>>> objects;  // (no virtual destructor)
  std::vector<std::unique_ptr<fcl_disk::DiskCollisionObject<S>>> disk_objects;
  for (const auto& m : meshes) objects.push_back(std::make_unique<fcl::CollisionObject<S>>(m.geometry, m.X));
  objects.push_back(std::make_unique<fcl::CollisionObject<S>>(blobs.tree, X_WO));
  for (const auto& [r, X] : scene_disks) {
    disk_objects.push_back(
        std::make_unique<fcl_disk::DiskCollisionObject<S>>(std::make_shared<fcl_disk::Disk<S>>(r), X));
  }
  for (auto& o : objects) manager.registerObject(o.get());
  for (auto& o : disk_objects) manager.registerObject(o.get());
  manager.setup();

  FailureLog distance_log("broadphase nearest distance vs brute force");
  FailureLog collide_log("broadphase collide vs brute force");
  for (int q = 0; q < 40; ++q) {
    const double radius = rng.uniform(0.1, 0.8);
    // Every other query centred on a triangle of the first mesh (crossing it).
    Vector3d centre = Vector3d(rng.uniform(-3.5, 3.5), rng.uniform(-3.5, 3.5), rng.uniform(-1.5, 3.5));
    if (q % 2 == 1) {
      Vector3d point, normal;
      fam::surfaceOf(box.mesh).sample_face(rng, &point, &normal);
      centre = meshes[0].X.template cast<double>() * point;
    }
    const Transform X_WD = fam::poseOf(rng.rotation(), centre).cast<S>();
    const S r = S(radius);
    // Brute force over every object.
    double truth = std::numeric_limits<double>::infinity(), scale = 0, world = 0;
    const Vector3d c_D = X_WD.translation().template cast<double>();
    for (const auto& m : meshes) {
      truth = std::min(truth, solverBruteForce(r, X_WD, m.mesh, m.X).distance);
      const Vector3d t = m.X.translation().template cast<double>();
      scale = std::max(scale, radius + m.mesh.boundingRadius() + (c_D - t).norm());
      world = std::max(world, t.norm());
    }
    for (const auto& cell : blobs.cells) {
      const fcl::Vector3<S> side = cell.box.max_ - cell.box.min_;
      Transform X_WC = X_WO;
      X_WC.translation() = X_WO * cell.box.center();
      truth = std::min(truth, double(fcl_disk::diskShapeDistance(r, X_WD, fcl::Box<S>(side), X_WC).distance));
    }
    scale = std::max(scale, radius + blobs.surface().bounding_radius +
                                (c_D - X_WO.translation().template cast<double>()).norm());
    for (const auto& [r2, X2] : scene_disks) {
      truth = std::min(truth, double(fcl_disk::exactDiskDistance(r, X_WD, r2, X2).distance));
      scale = std::max(scale, radius + double(r2) + (c_D - X2.translation().template cast<double>()).norm());
    }
    world = std::max(world, c_D.norm()) + scale;
    const double tolerance = kTwoAnswers * Tol<S>::relative(scale) + Tol<S>::world(world);

    fcl_disk::DiskCollisionObject<S> query(std::make_shared<fcl_disk::Disk<S>>(r), X_WD);
    fcl::DefaultDistanceData<S> distance_data;
    manager.distance(&query, &distance_data, fcl::DefaultDistanceFunction<S>);
    const double d = double(distance_data.result.min_distance);
    const std::string context = " (query " + std::to_string(q) + ": radius " + str(double(r)) + " X_WD " +
                                str(X_WD) + ", brute force " + str(truth) + ")";
    if (!(std::abs(d - truth) <= tolerance)) distance_log.add("got " + str(d) + context);
    fcl::DefaultCollisionData<S> collision_data;
    manager.collide(&query, &collision_data, fcl::DefaultCollisionFunction<S>);
    const bool hit = collision_data.result.isCollision();
    if ((hit && truth > tolerance) || (!hit && truth == 0)) {
      collide_log.add(std::string("collide says ") + (hit ? "intersecting" : "apart") + context);
    }
  }
}

// ---- bad input ---------------------------------------------------------------------

// NaN in the disk's pose or the mesh's / octree's pose, or a mesh / octree
// pose that is not rigid: NaN distance and no contact (never a crash: Debian's
// FCL asserts in GJK on NaN), every BV type, both orders, both solvers, objects
// and geometries, as for every Disk pair (test_disk_shape_cases.cpp,
// docs/robustness.md).
TYPED_TEST(DiskEnvironment, NaNPoseGivesNaNDistanceAndNoContact) {
  using S = TypeParam;
  const S nan = std::numeric_limits<S>::quiet_NaN();
  const MeshScene<S> soup(fam::triangleSoup(20, kSeed + 8));
  const OcTreeScene<S> wall(fam::wallOcTree());
  std::vector<std::pair<std::string, std::shared_ptr<fcl::CollisionGeometry<S>>>> others;
  for (const auto& bv : soup.bvs) others.emplace_back(bv.bv, bv.geometry);
  others.emplace_back("octree", wall.tree);
  auto disk = std::make_shared<fcl_disk::Disk<S>>(S(0.5));
  const fcl::Transform3<S> X_WE = fam::randomFrame(kSeed + 600).cast<S>();
  const fcl::Transform3<S> X_WD = X_WE;  // at the sets' frame origin, among triangles and cells
  // 0: NaN in the disk's pose; 1: in the other's; 2: the other's rotation
  // scaled by 2 (not rigid; the disk's is covered by every Disk pair's tests).
  for (int corrupt = 0; corrupt < 3; ++corrupt) {
    fcl::Transform3<S> disk_pose = X_WD, other_pose = X_WE;
    if (corrupt == 2) {
      other_pose.linear() *= S(2);
    } else {
      (corrupt == 0 ? disk_pose : other_pose).translation().x() = nan;
    }
    for (const auto& [name, other] : others) {
      for (const bool disk_first : {true, false}) {
        for (const auto solver : kSolvers) {
          SCOPED_TRACE(name + (corrupt == 0   ? ": disk pose NaN, "
                               : corrupt == 1 ? ": other pose NaN, "
                                              : ": other pose not rigid, ") +
                       (disk_first ? "disk first, " : "other first, ") + solverName(solver));
          std::string mismatch;
          const auto r = fclDistance<S>(disk, disk_pose, other, other_pose, disk_first, solver, &mismatch);
          EXPECT_TRUE(std::isnan(r.min_distance)) << r.min_distance;
          EXPECT_EQ(mismatch, "");
          for (const bool enable_contact : {false, true}) {
            fcl::CollisionRequest<S> request(kAllContacts, enable_contact);
            request.gjk_solver_type = solver;
            std::size_t returned = 0;
            const auto c = fclCollide<S>(disk, disk_pose, other, other_pose, disk_first, request, &returned);
            EXPECT_EQ(returned, 0u);
            EXPECT_FALSE(c.isCollision());
          }
        }
      }
    }
  }
}

}  // namespace

// A BVHModel built from points only (BVH_MODEL_POINTCLOUD) has no triangles:
// no answer, as FCL means it (the result untouched, no contact), and no crash,
// for every BV type and either order (FCL's oriented traversals would run on a
// node their initialize() left unset).
TEST(DiskEnvironment, PointCloudModelsGetNoAnswer) {
  const auto check = [](auto mesh, const char* name) {
    const std::vector<fcl::Vector3d> points = {fcl::Vector3d(0, 0, 0), fcl::Vector3d(1, 0, 0),
                                               fcl::Vector3d(0, 1, 0)};
    mesh->beginModel();
    mesh->addSubModel(points);
    mesh->endModel();
    ASSERT_EQ(mesh->getModelType(), fcl::BVH_MODEL_POINTCLOUD) << name;
    auto disk = std::make_shared<fcl_disk::Diskd>(0.3);
    fcl::Transform3d X_WD = fcl::Transform3d::Identity();
    X_WD.translation() << 0.2, 0.2, 0.0;  // through the points' plane
    fcl::CollisionObjectd disk_object(disk, X_WD), cloud(mesh);
    for (const bool disk_first : {true, false}) {
      fcl::CollisionObjectd* o1 = disk_first ? &disk_object : &cloud;
      fcl::CollisionObjectd* o2 = disk_first ? &cloud : &disk_object;
      fcl::DistanceResultd distance;
      fcl::distance(o1, o2, fcl::DistanceRequestd(), distance);
      EXPECT_EQ(distance.min_distance, std::numeric_limits<double>::max()) << name;
      fcl::CollisionResultd contacts;
      fcl::collide(o1, o2, fcl::CollisionRequestd(10, true), contacts);
      EXPECT_EQ(contacts.numContacts(), 0u) << name;
    }
  };
  check(std::make_shared<fcl::BVHModel<fcl::OBBRSS<double>>>(), "OBBRSS");
  check(std::make_shared<fcl::BVHModel<fcl::RSS<double>>>(), "RSS");
  check(std::make_shared<fcl::BVHModel<fcl::kIOS<double>>>(), "kIOS");
  check(std::make_shared<fcl::BVHModel<fcl::OBB<double>>>(), "OBB");
  check(std::make_shared<fcl::BVHModel<fcl::AABB<double>>>(), "AABB");
  check(std::make_shared<fcl::BVHModel<fcl::KDOP<double, 16>>>(), "KDOP16");
  check(std::make_shared<fcl::BVHModel<fcl::KDOP<double, 18>>>(), "KDOP18");
  check(std::make_shared<fcl::BVHModel<fcl::KDOP<double, 24>>>(), "KDOP24");
}

// The collision traversals prune a volume only beyond the leaf test's touching
// tolerance (1e-13 of the leaf's scene): a disk lying on a face, or a hair
// above it (1e-15 here, scenes ~0.3-1), collides; 1e-9 above it does not. A
// disk parallel to a 10 x 10 grid of triangles in z = 0 (every BV type, so
// that the pair goes through inner volumes) and over the top faces z = 0.125
// of a layer of occupied octree cells (resolution 0.125: every cell boundary
// exact); then tilted, its lowest rim point at that height; and crossing the
// face. Both argument orders, contacts on and off.
TEST(DiskEnvironment, CollisionTraversalsKeepPairsWithinTheTouchingTolerance) {
  struct Case {
    double height;  // of the disk's lowest point over the face
    double tilt;    // about x, radians
    bool collides;
  };
  const std::vector<Case> cases = {{0.0, 0.0, true},   {1e-15, 0.0, true}, {1e-9, 0.0, false},
                                   {0.0, 0.3, true},   {1e-15, 0.3, true}, {1e-9, 0.3, false},
                                   {-1e-3, 0.3, true}};
  const double radius = 0.04;
  // The disk's lowest point at (x, y, face + height).
  const auto diskPose = [&](double x, double y, double face, const Case& c) {
    fcl::Transform3d X_WD = fcl::Transform3d::Identity();
    X_WD.linear() = Eigen::AngleAxisd(c.tilt, Eigen::Vector3d::UnitX()).toRotationMatrix();
    // Tilted about x, the disk's lowest point is c - r sign(v_z) v (v = R e_y).
    const Eigen::Vector3d v = X_WD.linear().col(1);
    const Eigen::Vector3d offset = c.tilt == 0.0 ? Eigen::Vector3d::Zero()
                                                 : Eigen::Vector3d(-radius * (v.z() > 0 ? 1.0 : -1.0) * v);
    X_WD.translation() = Eigen::Vector3d(x, y, face + c.height) - offset;
    return X_WD;
  };
  const auto check = [&](const std::shared_ptr<fcl::CollisionGeometry<double>>& environment,
                         double x, double y, double face, const std::string& name) {
    auto disk = std::make_shared<fcl_disk::Diskd>(radius);
    for (const Case& c : cases) {
      fcl::CollisionObjectd disk_object(disk, diskPose(x, y, face, c)), other(environment);
      for (const bool disk_first : {true, false}) {
        for (const bool enable_contact : {false, true}) {
          fcl::CollisionResultd result;
          fcl::collide(disk_first ? &disk_object : &other, disk_first ? &other : &disk_object,
                       fcl::CollisionRequestd(1, enable_contact), result);
          EXPECT_EQ(result.isCollision(), c.collides)
              << name << ": height " << c.height << ", tilt " << c.tilt
              << (disk_first ? ", disk first" : ", other first")
              << (enable_contact ? ", contacts" : "");
        }
      }
    }
  };
  std::vector<fcl::Vector3d> vertices;
  std::vector<fcl::Triangle> triangles;
  for (int i = 0; i <= 10; ++i) {
    for (int j = 0; j <= 10; ++j) vertices.emplace_back(0.1 * i, 0.1 * j, 0.0);
  }
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 10; ++j) {
      const int k = 11 * i + j;
      triangles.emplace_back(k, k + 11, k + 12);
      triangles.emplace_back(k, k + 12, k + 1);
    }
  }
  const auto mesh = [&](auto model) {
    model->beginModel();
    model->addSubModel(vertices, triangles);
    model->endModel();
    return std::shared_ptr<fcl::CollisionGeometry<double>>(model);
  };
  check(mesh(std::make_shared<fcl::BVHModel<fcl::OBBRSS<double>>>()), 0.43, 0.57, 0.0, "OBBRSS");
  check(mesh(std::make_shared<fcl::BVHModel<fcl::RSS<double>>>()), 0.43, 0.57, 0.0, "RSS");
  check(mesh(std::make_shared<fcl::BVHModel<fcl::kIOS<double>>>()), 0.43, 0.57, 0.0, "kIOS");
  check(mesh(std::make_shared<fcl::BVHModel<fcl::OBB<double>>>()), 0.43, 0.57, 0.0, "OBB");
  check(mesh(std::make_shared<fcl::BVHModel<fcl::AABB<double>>>()), 0.43, 0.57, 0.0, "AABB");
  check(mesh(std::make_shared<fcl::BVHModel<fcl::KDOP<double, 16>>>()), 0.43, 0.57, 0.0, "KDOP16");
  check(mesh(std::make_shared<fcl::BVHModel<fcl::KDOP<double, 18>>>()), 0.43, 0.57, 0.0, "KDOP18");
  check(mesh(std::make_shared<fcl::BVHModel<fcl::KDOP<double, 24>>>()), 0.43, 0.57, 0.0, "KDOP24");
  auto tree = std::make_shared<octomap::OcTree>(0.125);
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) tree->updateNode(octomap::point3d(0.0625 + 0.125 * i, 0.0625 + 0.125 * j, 0.0625), true);
  }
  check(std::make_shared<fcl::OcTree<double>>(tree), 0.25, 0.25, 0.125, "octree");
}

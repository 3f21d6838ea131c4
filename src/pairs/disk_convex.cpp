// Disk - fcl::Convex: its nearest feature paired with the disk in closed form
// (ConvexTraits::closedForm: found through the face planes, or for hulls of
// kSupportSearchVertexCount vertices or more through the vertices' support
// alone), else the generic solver with the polytope's projection (the nearest
// of the faces whose planes see the point) and support (a vertex); large hulls
// climb their face graph and keep their vertices in clusters.
// docs/disk_shape_distance.md, section 4.
#include "../disk_shape_pair.h"
#include "feature_candidates.h"
#include "point_to_hull.h"
#include "polygon_projection.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace fcl_disk {
namespace internal {
namespace {

/// Faces whose normals are within this sine of one line are parallel: a Convex
/// whose faces are all parallel (or of zero area) is flat, a polygon, and its
/// plane tests cannot tell its inside. Far above the rounding of Newell normals
/// (a few eps), far below any real dihedral angle.
constexpr double kParallelFaceSine = 1e-12;

/// The rounding of w.v for a vertex v of a hull of bounding radius B, relative
/// to |w|_1 B: a few eps (three products and two sums). The projection's
/// optimality test compares w.v with w.q where q lies on an edge or at a
/// vertex, whose ends tie with q exactly: without this slack rounding fails
/// the test where q is optimal and sends the projection on through the other
/// faces (docs/disk_shape_distance.md, section 4). Accepting q within it moves
/// the distance by its square, far below eps.
constexpr double kDotRounding = 4 * std::numeric_limits<double>::epsilon();

/// The closed form's passes (ConvexTraits::closedForm): each moves to the
/// hull's feature nearest the disk point of the last feature's pair.
constexpr int kFeaturePasses = 3;
/// ... and for a meeting the face planes found off the vertices' hull
/// (answerOffSupportSet): the pair nearly touches, where the passes converge
/// slowly. With 3, none of the 78 such meetings of
/// FacePlanesReachingBeyondTheVerticesAtACorner (4,000 near-corner pairs)
/// settles and the generic solver on the vertices answers them (the test
/// takes 413 ms, against 393 ms with 16, which settles them: docs/
/// disk_shape_distance.md, section 4, "Convex"). Only such
/// meetings of hulls with a thickness pay for it.
constexpr int kOffSupportSetPasses = 16;

/// How many faces' thicknesses beyond the vertices' hull the face planes are
/// taken to reach at most, for hulls too thin for the search of
/// answerOffSupportSet: the corners measured reach 1.25
/// (FacePlanesReachingBeyondTheVerticesAtACorner) and 1.8 thicknesses
/// (fuzz_disk_shapes, regression-float-hull-vertex-on-rim). Edges sharper than
/// 2 asin(1 / 16) ~ 7 degrees reach farther, 1 / sin(alpha / 2) thicknesses
/// (docs/disk_shape_distance.md, section 4, "Convex", for what that costs).
constexpr double kPlanesReach = 16.0;

/// Hulls with at least this many vertices keep them in clusters of at most
/// kClusterSize, each with a bounding ball, for their extreme values along a
/// direction (ConvexTarget::mostAlong): a cluster whose ball cannot beat the
/// best vertex found is skipped. Below, one vectorised scan of every vertex
/// costs less (a ball bounds a patch of a hull's surface loosely, so a
/// support call scans 40% of a 200-vertex hull's vertices by cluster), and
/// each cluster's scan has a fixed cost about that of 16 vertices' products,
/// which clusters of 32 spread over more vertices than clusters of 16
/// (measured in docs/disk_shape_distance.md, section 4).
constexpr std::size_t kClusteringVertexCount = 128;
constexpr int kClusterSize = 32;

/// Hulls with at least this many vertices find the nearest feature of the
/// closed form by the support search of point_to_hull.h (ConvexTraits::
/// closedFormBySupport), which reads the vertices only, on every query: a hull
/// not kept (ConvexGeometryCache) then computes no face planes unless the
/// generic solver needs them, which cost more than GJK's whole query from
/// ~100 vertices on. Below, the planes' one scan costs fewer instructions
/// than the search's several vertex scans (docs/disk_shape_distance.md,
/// section 4), and a hull's planes less than a query of GJK.
constexpr std::size_t kSupportSearchVertexCount = 64;

/// Hulls with at least this many faces find a point's nearest feature by
/// climbing the face graph first (ConvexTarget::nearestOverFaces): a scan of
/// every plane costs more than the climb there; below, the vectorised scan
/// is faster than the climb's dependent steps even on a hull a thread keeps,
/// and the graph's construction costs more than it saves where hulls change
/// often (docs/disk_shape_distance.md, section 4).
constexpr std::size_t kClimbingFaceCount = 100;

/// The penetration depth's edge candidates (ConvexTraits::contactDirections)
/// skip an edge whose arc of directions cannot beat the best depth found: the
/// arc is that of the edge's two face normals, known to their rounding, so the
/// bound over it is lowered by what a widening of the arc by this angle (rad)
/// could lower F, far above the normals' rounding (at most ~1e-10 rad for
/// normals of faces at least kWellConditionedFace wide, relative to their size).
constexpr double kEdgeArcMargin = 1e-9;
/// A face whose Newell normal is at least this times the square of its size
/// (twice its ball's radius) has a normal known to ~eps / this: its edges' arcs
/// may be pruned.
constexpr double kWellConditionedFace = 1e-6;

/// A face of the polytope: where its vertex indices start in FCL's face list,
/// how many, its outward unit normal (zero for a face of zero area) and the
/// length of its Newell normal (twice its area), the plane's offset (normal .
/// vertex). Computed on the first query that needs them (a hull met once
/// computes a few faces'): a ball holding the polygon (centre the vertices'
/// mean), whose distance bounds the polygon's from below (ConvexTarget::ballOf),
/// and its edges and triangle projection (ConvexTarget::detailOf).
struct ConvexFace {
  std::size_t start;  ///< the face's first vertex index in FCL's face list
  int count;
  Vec3 unit_normal;
  double offset;
  double newell_length;
  /// Its edges are ConvexGeometry::edges[first_edge, + count), its triangle
  /// projection (count 3) ConvexGeometry::triangles[triangle]; -1 until computed.
  mutable int first_edge = -1, triangle = -1;
  mutable bool has_ball = false;
  mutable Vec3 centre = Vec3::Zero();
  mutable double radius = 0.0;
};

/// An edge of the hull's faces, listed once: its vertices and, where exactly
/// two faces share it, those two (else -1).
struct ConvexHullEdge {
  int from, to;
  int face_a = -1, face_b = -1;
  /// The arc of directions -w where it is the hull's support, from n1 to n2 =
  /// cos alpha n1 + sin alpha m (its faces' outward normals), and the angle it
  /// is widened by (ConvexTraits::edgeArcCannotBeat); `prunable` where that
  /// arc is known: two faces, both well conditioned, not back to back.
  bool prunable = false;
  Vec3 n1{Vec3::Zero()}, n2{Vec3::Zero()}, m{Vec3::Zero()};
  double cos_alpha = 1.0, sin_alpha = 0.0, widening = 0.0;
};

/// A face's edge from its vertex i to the next, with what the nearest-feature
/// projection (ConvexTarget::nearestOnFace) reads of it: the edge vector and
/// 1 / its squared length (0 for a zero-length edge), and its normal in the
/// face's plane pointing into the face, unit normal x edge, with its offset:
/// a point's foot lies on the edge's inner side iff inwards . y >=
/// inwards_offset.
struct ConvexEdge {
  Vec3 from, to;
  Vec3 along;
  double inverse_length_squared;
  Vec3 inwards;
  double inwards_offset;
};

/// What a query needs of a Convex beyond FCL's lists, computed from them: the
/// face planes and balls (Newell's normals), whether the polytope is flat, and
/// its largest face.
struct ConvexGeometry {
  bool valid = false;  ///< ConvexTraits::valid's verdict on the lists
  /// Whether the faces, their planes, flatness, largest face and thickness
  /// are computed: with the rest for hulls below kSupportSearchVertexCount
  /// vertices, else when a query first needs them (ConvexTarget::ensureFaces).
  bool has_faces = false;
  std::vector<ConvexFace> faces;
  /// The faces' edges and triangle projections, appended as queries reach
  /// them (ConvexTarget::detailOf). They grow while a query runs, so a
  /// reference into them is read before the next face's detail is asked for.
  mutable std::vector<ConvexEdge> edges;
  mutable std::vector<TriangleProjection> triangles;
  /// The face planes again, one column per coordinate (n_x, n_y, n_z, offset),
  /// so that the height scan of every projection runs vectorised.
  Eigen::Matrix<double, Eigen::Dynamic, 4> planes;
  /// The vertices in double, one column per coordinate: the support's scan
  /// runs vectorised.
  Eigen::Matrix<double, Eigen::Dynamic, 3> points;
  /// A group of vertices, rows [begin, end) of clustered_points, inside the
  /// ball (centre, radius).
  struct VertexCluster {
    Vec3 centre;
    double radius;
    int begin, end;
  };
  /// The vertices by cluster (hulls of kClusteringVertexCount vertices or
  /// more, from their second query on a thread: only speed depends on them),
  /// with each clustered row's index in `points`.
  std::vector<VertexCluster> clusters;
  Eigen::Matrix<double, Eigen::Dynamic, 3> clustered_points;
  std::vector<int> cluster_order;
  /// Faces sharing an edge, face f's from face_neighbours[neighbour_start[f]]
  /// to before [neighbour_start[f + 1]] (hulls of kClimbingFaceCount faces or
  /// more): built by the first climb (ConvexTarget::climbToHighestPlane), so
  /// that a hull whose faces only a contact's candidates read (a large hull,
  /// found by its vertices) does not build it.
  mutable std::vector<int> neighbour_start, face_neighbours;
  /// Faces whose normals are extreme along +-x, +-y, +-z: where a climb on
  /// the face graph starts, the one whose plane is farthest from the point.
  mutable std::array<int, 6> climb_starts{};
  int largest_face = -1;  ///< the face of largest area
  bool flat = true;       ///< every face parallel or of zero area: a polygon
  double bounding_radius = 0.0;  ///< the largest vertex norm
  Vec3 centre = Vec3::Zero();    ///< the vertices' mean, where the closed form starts
  /// Scratch for the height and support scans (one entry per face, per
  /// vertex): the geometry is this thread's own (ConvexGeometryCache), so its
  /// buffers need no thread_local lookup per scan.
  mutable Eigen::VectorXd heights, along;
  /// The largest spread of a face's vertices along its normal: 0 for
  /// triangles (their vertices define the plane) and planar polygons up to
  /// rounding; ~1e-7 of the size for quadrilaterals whose vertices were
  /// rounded to float, or data planar only to its precision.
  double face_thickness = 0.0;
  /// The hull's edges with their faces, for the penetration depth's candidates
  /// only: built on the first contact query of the hull on this thread.
  mutable std::vector<ConvexHullEdge> hull_edges;
  /// The vertices extreme along 14 directions (the axes and the cube's
  /// diagonals, both signs), whose greatest value along w bounds the hull's
  /// support from below: built with hull_edges.
  mutable std::array<Vec3, 14> probes{};
  mutable bool hull_edges_built = false;

  /// The heap memory a hull's geometry holds at most, in bytes, once its
  /// faces, clusters and every face's edges and triangle projection are
  /// computed: `vertex_count` vertices, `face_count` faces listing
  /// `edge_count` vertex indices in all (one edge each). hull_edges, built
  /// only for contacts, is not counted.
  static std::size_t budgetBytes(std::size_t vertex_count, std::size_t face_count,
                                 std::size_t edge_count) {
    const std::size_t most_clusters = 2 * vertex_count / kClusterSize + 1;  // leaves >= half full
    return face_count * (sizeof(ConvexFace) + sizeof(TriangleProjection) + 5 * sizeof(double) +
                         sizeof(int)) +
           edge_count * (sizeof(ConvexEdge) + sizeof(int)) +
           vertex_count * (7 * sizeof(double) + sizeof(int)) +
           most_clusters * sizeof(VertexCluster);
  }
};

/// How many hulls, and how much memory for them, each thread keeps the
/// geometry of (ConvexGeometryCache): a planner's scene holds many hulls and a
/// broadphase queries those near a disk in turn, and a hull whose geometry was
/// dropped costs several queries (40 vertices, 76 faces: ~20k instructions
/// against ~4k; docs/disk_shape_distance.md, section 4). The budget counts
/// every face's details, which a hull holds only once queries have reached
/// them all: ~47 KB for 40 random points on a sphere (~15 KB before any),
/// so 1024 such hulls fit; hulls of 100 points (~128 KB) stop at it at ~390,
/// of 1000 points (~1.3 MB) at ~38.
constexpr std::size_t kMaxCachedHulls = 1024;
constexpr std::size_t kCachedHullBytes = std::size_t(48) << 20;

/// The geometry of up to kMaxCachedHulls hulls this thread queried, each with
/// a copy of the lists it was computed from. A hit needs the address and the
/// lists equal bit for bit, so a hull destroyed and another built at the same
/// address, or one whose shared lists were changed in place, is recomputed.
/// A new hull takes a free slot while the count and kCachedHullBytes allow;
/// else one new hull in kCacheAdmission replaces a pseudo-random slot, and the
/// others are computed into one slot of their own (kQuerySlot), kept until the
/// next such hull: of hulls queried in turn, more of them than fit, those kept
/// keep hitting (about as many hits as slots), where replacing the least
/// recently used, or a random slot on every miss, would miss on nearly every
/// query; and a hull queried many times in a row hits from its second query
/// on, kept or not.
constexpr std::uint64_t kCacheAdmission = 8;

/// The largest entry of `values` (a contiguous Eigen vector) and the index
/// of the first entry equal to it, values.size() when none is (NaN entries):
/// Eigen's vectorised maximum, then a search for it. maxCoeff(&index)
/// compares one entry at a time on a serial chain, which costs the 40-vertex
/// hull's query a fifth of its time (docs/performance.md).
template <typename Vector>
std::pair<double, Eigen::Index> largestWithFirstIndex(const Vector& values) {
  const double largest = values.maxCoeff();
  const double* const begin = values.data();
  return {largest, Eigen::Index(std::find(begin, begin + values.size(), largest) - begin)};
}

template <typename S>
struct ConvexGeometryCache {
  struct Entry {
    std::vector<fcl::Vector3<S>> vertices;
    std::vector<int> face_list;
    int face_count = -1;
    ConvexGeometry geometry;
    std::size_t bytes = 0;  ///< held by the three above
  };
  /// The slot of the last new hull not kept.
  static constexpr std::size_t kQuerySlot = kMaxCachedHulls;
  /// Each slot's hull address (never dereferenced; null while rebuilt).
  std::array<const void*, kMaxCachedHulls + 1> shapes{};
  /// Each slot's entry, made when the slot is first filled; on the heap, so
  /// the geometry a query holds stays where it is while another slot is
  /// filled.
  std::array<std::unique_ptr<Entry>, kMaxCachedHulls + 1> entries;
  std::size_t filled = 0;       ///< kept slots in use, the first ones
  std::size_t bytes = 0;        ///< held by the kept entries
  std::uint64_t new_hulls = 0;  ///< new hulls met with every slot in use
  std::size_t verified = kQuerySlot;  ///< the slot geometryOf() compared last
  /// The kept slots by address: open addressing with linear probing over
  /// twice as many buckets as slots, each 1 + its slot (0: empty).
  static constexpr std::size_t kIndexBuckets = 2 * kMaxCachedHulls;
  std::array<std::uint16_t, kIndexBuckets> index{};
  static_assert(kMaxCachedHulls < 0xffff, "a bucket holds 1 + a slot");

  /// Whether `slot` holds a hull: a kept slot or kQuerySlot.
  bool holds(std::size_t slot) const { return slot < filled || slot == kQuerySlot; }

  /// What slotOf() returns for an address no slot keeps.
  static constexpr std::size_t kNoSlot = kMaxCachedHulls + 1;

  /// The bucket where the search for `shape` starts: the address's bits
  /// above an allocation's alignment, mixed by a multiplicative hash.
  static std::size_t homeBucket(const void* shape) {
    const std::uint64_t bits = std::uint64_t(reinterpret_cast<std::uintptr_t>(shape)) >> 4;
    return std::size_t((bits * 0x9E3779B97F4A7C15ull) >> 32) % kIndexBuckets;
  }
  static std::size_t nextBucket(std::size_t bucket) { return (bucket + 1) % kIndexBuckets; }

  /// The slot keeping `shape`'s address (the last one compared first, then
  /// kQuerySlot, then the index), or kNoSlot.
  std::size_t slotOf(const void* shape) const {
    if (holds(verified) && shapes[verified] == shape) return verified;
    if (shapes[kQuerySlot] == shape) return kQuerySlot;
    for (std::size_t bucket = homeBucket(shape); index[bucket] != 0; bucket = nextBucket(bucket)) {
      if (shapes[index[bucket] - 1u] == shape) return index[bucket] - 1u;
    }
    return kNoSlot;
  }

  /// Lists kept slot `slot` under its address (shapes[slot], not listed).
  void addToIndex(std::size_t slot) {
    std::size_t bucket = homeBucket(shapes[slot]);
    while (index[bucket] != 0) bucket = nextBucket(bucket);
    index[bucket] = std::uint16_t(slot + 1);
  }
  /// Unlists kept slot `slot` (listed under shapes[slot]), moving back the
  /// entries after it whose search would otherwise pass the gap (deletion
  /// without tombstones).
  void removeFromIndex(std::size_t slot) {
    std::size_t gap = homeBucket(shapes[slot]);
    while (index[gap] != slot + 1) gap = nextBucket(gap);
    index[gap] = 0;
    for (std::size_t bucket = nextBucket(gap); index[bucket] != 0; bucket = nextBucket(bucket)) {
      const std::size_t home = homeBucket(shapes[index[bucket] - 1u]);
      // Moved back when its home is not within (gap, bucket], cyclically.
      const bool home_after_gap = gap < bucket ? (home > gap && home <= bucket)
                                               : (home > gap || home <= bucket);
      if (!home_after_gap) {
        index[gap] = index[bucket];
        index[bucket] = 0;
        gap = bucket;
      }
    }
  }

  Entry& entry(std::size_t slot) {
    if (!entries[slot]) entries[slot] = std::make_unique<Entry>();
    return *entries[slot];
  }

  /// Where a new hull of `new_bytes` goes: a free slot while the count and the
  /// budget allow, else (see kCacheAdmission) one in kCacheAdmission a slot of
  /// a fixed pseudo-random sequence (splitmix64's finaliser of a counter), the
  /// others kQuerySlot.
  std::size_t slotForNewHull(std::size_t new_bytes) {
    if (filled < kMaxCachedHulls && (filled == 0 || bytes + new_bytes <= kCachedHullBytes)) {
      return filled++;
    }
    std::uint64_t z = (++new_hulls) * 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return z % kCacheAdmission == 0 ? std::size_t((z / kCacheAdmission) % filled) : kQuerySlot;
  }
};

/// FCL's Convex: vertices, and faces encoded [k, i_1..i_k, k', ...], each listed
/// counter-clockwise seen from outside. Projection works in the shape frame,
/// with the face planes of ConvexGeometry (computed once per hull and thread,
/// not per projection). One query at a time per thread holds the geometry.
template <typename S>
struct ConvexTarget {
  const fcl::Convex<S>* convex;
  const int* list;                   ///< FCL's face list
  const std::vector<ConvexFace>& faces;
  const Eigen::Matrix<double, Eigen::Dynamic, 4>& planes;
  const Eigen::Matrix<double, Eigen::Dynamic, 3>& points;
  const ConvexGeometry& geometry;
  int largest_face;
  bool flat;
  double face_thickness;

  explicit ConvexTarget(const fcl::Convex<S>& shape, const ConvexGeometry& geometry)
      : convex(&shape),
        list(shape.getFaces().data()),
        faces(geometry.faces),
        planes(geometry.planes),
        points(geometry.points),
        geometry(geometry),
        largest_face(geometry.largest_face),
        flat(geometry.flat),
        face_thickness(geometry.face_thickness) {}

  /// This thread's cache, on the heap: a library's thread-local block must fit
  /// the static TLS a process gives a library it loads with dlopen (the hook's
  /// initial-exec counter puts the whole block there), a few hundred bytes.
  /// Read through an initial-exec pointer (8 bytes there), without the call a
  /// thread_local object of a shared library costs on every access (a query
  /// reads the cache four to six times); its owner frees the cache at the
  /// thread's exit and clears the pointer.
  static ConvexGeometryCache<S>& cache() {
    __attribute__((tls_model("initial-exec"))) static thread_local ConvexGeometryCache<S>* current =
        nullptr;
    if (current == nullptr) {
      struct Owner {
        std::unique_ptr<ConvexGeometryCache<S>> cache;
        ~Owner() { current = nullptr; }
      };
      thread_local Owner owner;
      owner.cache = std::make_unique<ConvexGeometryCache<S>>();
      current = owner.cache.get();
    }
    return *current;
  }

  /// Whether two lists hold the same values bit for bit (one memcmp: a
  /// vertex is three packed scalars). Stricter than ==, never looser: -0 and
  /// +0 differ (the geometry is then recomputed), and so do NaNs of other bits.
  template <typename T>
  static bool sameBytes(const std::vector<T>& a, const std::vector<T>& b) {
    static_assert(sizeof(fcl::Vector3<S>) == 3 * sizeof(S), "a vertex has no padding bytes");
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
  }

  /// This thread's geometry of `shape`: its cache entry's when the lists are
  /// unchanged (compared bit for bit, sameBytes), else computed into its
  /// entry or a new one (ConvexGeometryCache::slotForNewHull); that entry is
  /// then the verified one.
  static const ConvexGeometry& geometryOf(const fcl::Convex<S>& shape) {
    ConvexGeometryCache<S>& cached = cache();
    std::size_t slot = cached.slotOf(&shape);
    const auto& vertices = shape.getVertices();
    const auto& face_list = shape.getFaces();
    if (cached.holds(slot)) {
      auto& entry = *cached.entries[slot];
      if (entry.face_count == shape.getFaceCount() && sameBytes(entry.vertices, vertices) &&
          sameBytes(entry.face_list, face_list)) {
        cached.verified = slot;
        if (entry.geometry.valid && entry.geometry.clusters.empty() &&
            std::size_t(entry.geometry.points.rows()) >= kClusteringVertexCount) {
          buildClusters(&entry.geometry);  // a hull met again
        }
        return entry.geometry;
      }
    }
    ConvexGeometry geometry = computeGeometry(shape);
    const std::size_t face_count = std::size_t(shape.getFaceCount());  // >= 0 when valid
    const std::size_t bytes =
        (geometry.valid ? ConvexGeometry::budgetBytes(vertices.size(), face_count,
                                                      face_list.size() - face_count)
                        : 0) +
        vertices.size() * sizeof(vertices[0]) + face_list.size() * sizeof(int);
    if (slot == ConvexGeometryCache<S>::kNoSlot) slot = cached.slotForNewHull(bytes);
    auto& entry = cached.entry(slot);
    const bool kept = slot != ConvexGeometryCache<S>::kQuerySlot;
    if (kept && cached.shapes[slot] != nullptr) cached.removeFromIndex(slot);
    cached.shapes[slot] = nullptr;  // invalid while rebuilt
    cached.verified = ConvexGeometryCache<S>::kQuerySlot;
    if (kept) cached.bytes -= entry.bytes;
    entry.bytes = 0;
    entry.vertices = vertices;
    entry.face_list = face_list;
    entry.geometry = std::move(geometry);
    entry.face_count = shape.getFaceCount();
    entry.bytes = bytes;
    if (kept) cached.bytes += bytes;
    cached.shapes[slot] = &shape;
    if (kept) cached.addToIndex(slot);
    cached.verified = slot;
    return entry.geometry;
  }

  /// The geometry of the hull geometryOf() verified last on this thread, when
  /// that is `shape`: within one query (ConvexTraits::valid first, then
  /// boundingRadius and target) the lists are compared once.
  static const ConvexGeometry& verifiedGeometryOf(const fcl::Convex<S>& shape) {
    const ConvexGeometryCache<S>& cached = cache();
    return cached.shapes[cached.verified] == &shape
               ? cached.entries[cached.verified]->geometry
               : geometryOf(shape);
  }

  /// |v| without overflow or underflow: the plain square root where the
  /// square is a normal double (almost always), stableNorm otherwise.
  static double safeNorm(const Vec3& v) {
    const double squared = v.squaredNorm();
    if (squared >= std::numeric_limits<double>::min() && squared <= std::numeric_limits<double>::max()) {
      return std::sqrt(squared);
    }
    return v.stableNorm();
  }

  static ConvexGeometry computeGeometry(const fcl::Convex<S>& shape) {
    ConvexGeometry geometry;
    geometry.valid = listsAreValid(shape);
    if (!geometry.valid) return geometry;
    // The vertex array read once, not through the shape at every read.
    const fcl::Vector3<S>* const vertices = shape.getVertices().data();
    const auto vertex = [vertices](int index) { return vertices[index].template cast<double>(); };
    geometry.points.resize(Eigen::Index(shape.getVertices().size()), 3);
    for (std::size_t i = 0; i < shape.getVertices().size(); ++i) {
      const Vec3 v = vertex(int(i));
      geometry.points.row(Eigen::Index(i)) = v.transpose();
      geometry.bounding_radius = std::max(geometry.bounding_radius, safeNorm(v));
    }
    geometry.centre = geometry.points.colwise().mean().transpose();
    if (std::size_t(geometry.points.rows()) < kSupportSearchVertexCount) {
      computeFaces(shape, &geometry);
    }
    return geometry;
  }

  /// The faces' part of `shape`'s geometry where it is not computed yet: a
  /// hull's own geometry, this thread's (ConvexGeometryCache), so it is
  /// completed in place.
  static void ensureFaces(const fcl::Convex<S>& shape, const ConvexGeometry& geometry) {
    if (!geometry.has_faces) computeFaces(shape, &const_cast<ConvexGeometry&>(geometry));
  }

  /// ConvexGeometry's faces, planes, flatness, largest face and thickness,
  /// for valid lists.
  static void computeFaces(const fcl::Convex<S>& shape, ConvexGeometry* geometry_out) {
    ConvexGeometry& geometry = *geometry_out;
    const fcl::Vector3<S>* const vertices = shape.getVertices().data();
    const auto vertex = [vertices](int index) { return vertices[index].template cast<double>(); };
    const std::vector<int>& list = shape.getFaces();
    std::vector<ConvexFace>& faces = geometry.faces;
    int& largest_face = geometry.largest_face;
    bool& flat = geometry.flat;
    faces.resize(std::size_t(shape.getFaceCount()));
    geometry.planes.resize(shape.getFaceCount(), 4);
    std::size_t at = 0;
    double largest_area = -1.0;
    Vec3 first_normal = Vec3::Zero();
    for (int f = 0; f < shape.getFaceCount(); ++f) {
      const int count = list[at];
      const int* index = &list[at + 1];
      // Newell's normal; for a triangle it is the one cross product (b - a) x (c - a).
      Vec3 normal;
      if (count == 3) {
        const Vec3 a = vertex(index[0]);
        normal = (vertex(index[1]) - a).cross(vertex(index[2]) - a);
      } else {
        normal = vertex(index[count - 1]).cross(vertex(index[0]));
        for (int i = 0; i + 1 < count; ++i) normal += vertex(index[i]).cross(vertex(index[i + 1]));
      }
      // |normal| is a squared length and the cross product of two normals a
      // fourth power, beyond double at 1e100: safeNorm and unit normals.
      const double area = safeNorm(normal);
      if (area > largest_area) largest_area = area, largest_face = f;
      const Vec3 unit = area > 0.0 ? Vec3(normal / area) : Vec3::Zero();
      if (flat && area > 0.0) {  // until a face is not parallel to the first
        if (first_normal.squaredNorm() == 0.0) first_normal = unit;
        flat = first_normal.cross(unit).squaredNorm() <= kParallelFaceSine * kParallelFaceSine;
      }
      const double offset = unit.dot(vertex(index[0]));
      if (count > 3) {  // a triangle lies in its plane: its vertices define it
        double lowest = 0.0, highest = 0.0;
        for (int i = 1; i < count; ++i) {
          const double height = unit.dot(vertex(index[i])) - offset;
          lowest = std::min(lowest, height), highest = std::max(highest, height);
        }
        geometry.face_thickness = std::max(geometry.face_thickness, highest - lowest);
      }
      ConvexFace& face = faces[std::size_t(f)];
      face.start = at + 1, face.count = count;
      face.unit_normal = unit, face.offset = offset, face.newell_length = area;
      geometry.planes(f, 0) = unit.x(), geometry.planes(f, 1) = unit.y();
      geometry.planes(f, 2) = unit.z(), geometry.planes(f, 3) = offset;
      at += count + 1;
    }
    geometry.has_faces = true;
  }

  /// ConvexGeometry's vertex clusters: the vertices split at the median of
  /// their bounding box's longest side until at most kClusterSize remain.
  static void buildClusters(ConvexGeometry* geometry) {
    const auto& points = geometry->points;
    std::vector<int> order(std::size_t(points.rows()));
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = int(i);
    std::vector<std::array<int, 2>> pending{{0, int(order.size())}};
    std::vector<std::array<int, 2>> leaves;
    while (!pending.empty()) {
      const auto [begin, end] = pending.back();
      pending.pop_back();
      if (end - begin <= kClusterSize) {
        std::sort(order.begin() + begin, order.begin() + end);  // index order within a cluster
        leaves.push_back({begin, end});
        continue;
      }
      Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity()), high = -low;
      for (int i = begin; i < end; ++i) {
        low = low.cwiseMin(points.row(order[i]).transpose());
        high = high.cwiseMax(points.row(order[i]).transpose());
      }
      Eigen::Index axis = 0;
      (high - low).maxCoeff(&axis);
      const int middle = begin + (end - begin) / 2;
      std::nth_element(order.begin() + begin, order.begin() + middle, order.begin() + end,
                       [&](int a, int b) { return points(a, axis) < points(b, axis); });
      pending.push_back({begin, middle});
      pending.push_back({middle, end});
    }
    geometry->clustered_points.resize(points.rows(), 3);
    for (std::size_t i = 0; i < order.size(); ++i) {
      geometry->clustered_points.row(Eigen::Index(i)) = points.row(order[i]);
    }
    geometry->cluster_order = std::move(order);
    for (const auto& [begin, end] : leaves) {
      const auto rows = geometry->clustered_points.middleRows(begin, end - begin);
      const Vec3 centre = rows.colwise().mean().transpose();
      double radius = 0.0;
      for (Eigen::Index i = 0; i < rows.rows(); ++i) {
        radius = std::max(radius, safeNorm(rows.row(i).transpose() - centre));
      }
      geometry->clusters.push_back({centre, radius, begin, end});
    }
  }

  /// Two 32-bit indices as one sortable 64-bit key.
  static std::uint64_t pairKey(int high, int low) {
    return std::uint64_t(std::uint32_t(high)) << 32 | std::uint32_t(low);
  }

  /// Every face's edges as (smaller, larger vertex) keys with their face, in
  /// the faces' order.
  static std::vector<std::pair<std::uint64_t, int>> faceEdges(const std::vector<int>& list,
                                                               const ConvexGeometry& geometry) {
    std::vector<std::pair<std::uint64_t, int>> edges;
    edges.reserve(list.size() - geometry.faces.size());  // one per index
    for (std::size_t f = 0; f < geometry.faces.size(); ++f) {
      const int* index = &list[geometry.faces[f].start];
      const int count = geometry.faces[f].count;
      for (int i = 0; i < count; ++i) {
        const int from = index[i], to = index[i + 1 < count ? i + 1 : 0];
        edges.emplace_back(pairKey(std::min(from, to), std::max(from, to)), int(f));
      }
    }
    return edges;
  }
  /// faceEdges sorted: the faces sharing an edge are adjacent.
  static std::vector<std::pair<std::uint64_t, int>> sortedFaceEdges(
      const std::vector<int>& list, const ConvexGeometry& geometry) {
    std::vector<std::pair<std::uint64_t, int>> edges = faceEdges(list, geometry);
    std::sort(edges.begin(), edges.end());
    return edges;
  }

  /// ConvexGeometry's face graph (faces sharing an edge, each face's list in
  /// ascending order) and the climb's start faces. Linear in the edges, since
  /// a hull not kept computes it on every query (docs/performance.md, "Hulls
  /// queried in turn").
  static void buildFaceGraph(const std::vector<int>& list, const ConvexGeometry* geometry) {
    const std::vector<ConvexFace>& faces = geometry->faces;
    // Each face's use of an edge: (pairKey(smaller vertex, larger vertex), face).
    const std::vector<std::pair<std::uint64_t, int>> uses = faceEdges(list, *geometry);
    // The uses grouped by a hash of their edge (a counting sort into at least
    // twice as many slots as uses, linear in the edges): the faces sharing an
    // edge are in one slot, with few other edges there.
    int bits = 1;
    while ((std::size_t(1) << bits) < 2 * uses.size()) ++bits;
    const auto slot_of = [bits](std::uint64_t key) {
      return std::size_t((key * 0x9E3779B97F4A7C15ull) >> (64 - bits));
    };
    std::vector<int> slot_start((std::size_t(1) << bits) + 1, 0);
    for (const auto& use : uses) ++slot_start[slot_of(use.first) + 1];
    for (std::size_t k = 1; k < slot_start.size(); ++k) slot_start[k] += slot_start[k - 1];
    std::vector<std::pair<std::uint64_t, int>> grouped(uses.size());
    {
      std::vector<int> next(slot_start.begin(), slot_start.end() - 1);
      for (const auto& use : uses) grouped[std::size_t(next[slot_of(use.first)]++)] = use;
    }
    // (face, neighbour) for every two faces sharing an edge, both ways.
    std::vector<std::pair<int, int>> pairs;
    pairs.reserve(uses.size());  // two faces an edge: one pair per use
    for (std::size_t k = 0; k + 1 < slot_start.size(); ++k) {
      for (int a = slot_start[k]; a < slot_start[k + 1]; ++a) {
        for (int b = slot_start[k]; b < slot_start[k + 1]; ++b) {
          const auto &use_a = grouped[std::size_t(a)], &use_b = grouped[std::size_t(b)];
          if (use_a.first == use_b.first && use_a.second != use_b.second) {
            pairs.emplace_back(use_a.second, use_b.second);
          }
        }
      }
    }
    // Placed by face, then each face's list sorted and made unique (the climb
    // reads it in that order).
    std::vector<int>& start = geometry->neighbour_start;
    std::vector<int>& neighbours = geometry->face_neighbours;
    start.assign(faces.size() + 1, 0);
    for (const auto& pair : pairs) ++start[std::size_t(pair.first) + 1];
    for (std::size_t f = 0; f < faces.size(); ++f) start[f + 1] += start[f];
    neighbours.resize(pairs.size());
    {
      std::vector<int> next(start.begin(), start.end() - 1);
      for (const auto& [face, neighbour] : pairs) {
        neighbours[std::size_t(next[std::size_t(face)]++)] = neighbour;
      }
    }
    int kept = 0;
    for (std::size_t f = 0; f < faces.size(); ++f) {
      const int begin = start[f], end = start[f + 1];
      std::sort(neighbours.begin() + begin, neighbours.begin() + end);
      start[f] = kept;
      for (int k = begin; k < end; ++k) {
        if (k == begin || neighbours[std::size_t(k)] != neighbours[std::size_t(k) - 1]) {
          neighbours[std::size_t(kept++)] = neighbours[std::size_t(k)];
        }
      }
    }
    start[faces.size()] = kept;
    neighbours.resize(std::size_t(kept));
    for (int axis = 0; axis < 6; ++axis) {
      const double sign = axis < 3 ? 1.0 : -1.0;
      Eigen::Index extreme = 0;
      (sign * geometry->planes.col(axis % 3)).maxCoeff(&extreme);
      geometry->climb_starts[axis] = int(extreme);
    }
  }

  /// The face's ball (ConvexFace), computed on first use: centre the
  /// vertices' mean, radius the farthest vertex's distance.
  static const ConvexFace& ballOf(const ConvexGeometry& geometry, const int* list,
                                  const ConvexFace& face) {
    if (face.has_ball) return face;
    const auto vertex = [&](int i) {
      return geometry.points.row(list[face.start + i]).transpose();
    };
    Vec3 centre = Vec3::Zero();
    for (int i = 0; i < face.count; ++i) centre += vertex(i);
    centre /= face.count;
    double radius = 0.0;
    for (int i = 0; i < face.count; ++i) radius = std::max(radius, safeNorm(vertex(i) - centre));
    face.centre = centre, face.radius = radius, face.has_ball = true;
    return face;
  }

  /// Whether the face's normal is known to ~eps / kWellConditionedFace: its
  /// Newell normal at least kWellConditionedFace times its size squared.
  static bool wellConditioned(const ConvexGeometry& geometry, const int* list,
                              const ConvexFace& face) {
    const double radius = ballOf(geometry, list, face).radius;
    return face.newell_length > 0.0 &&
           face.newell_length >= kWellConditionedFace * 4.0 * radius * radius;
  }

  /// An edge's arc of directions from its two faces (ConvexHullEdge).
  static void setEdgeArc(const ConvexGeometry& geometry, const int* list, ConvexHullEdge* edge) {
    const ConvexFace& face_a = geometry.faces[std::size_t(edge->face_a)];
    const ConvexFace& face_b = geometry.faces[std::size_t(edge->face_b)];
    edge->n1 = face_a.unit_normal, edge->n2 = face_b.unit_normal;
    edge->cos_alpha = edge->n1.dot(edge->n2);
    const Vec3 m_raw = edge->n2 - edge->cos_alpha * edge->n1;
    edge->sin_alpha = m_raw.norm();
    if (edge->sin_alpha > 0.0) edge->m = m_raw / edge->sin_alpha;
    const double smallest_face =
        std::min(ballOf(geometry, list, face_a).radius, ballOf(geometry, list, face_b).radius);
    if (smallest_face > 0.0) {
      edge->widening = kEdgeArcMargin + 2.0 * geometry.face_thickness / smallest_face;
    }
    constexpr double kBackToBack = 1e-6;  // 1 + cos alpha: the arc is nearly a half circle
    edge->prunable = wellConditioned(geometry, list, face_a) &&
                     wellConditioned(geometry, list, face_b) &&
                     smallest_face > 0.0 &&
                     edge->cos_alpha > kBackToBack - 1.0;
  }

  /// The hull's edges with their faces (ConvexGeometry::hull_edges), built on
  /// first use from sortedFaceEdges.
  static const std::vector<ConvexHullEdge>& hullEdgesOf(const fcl::Convex<S>& shape,
                                                        const ConvexGeometry& geometry) {
    if (geometry.hull_edges_built) return geometry.hull_edges;
    const std::vector<std::pair<std::uint64_t, int>> keys =
        sortedFaceEdges(shape.getFaces(), geometry);
    std::vector<ConvexHullEdge>& edges = geometry.hull_edges;
    edges.clear();
    for (std::size_t i = 0; i < keys.size();) {
      std::size_t end = i + 1;
      while (end < keys.size() && keys[end].first == keys[i].first) ++end;
      ConvexHullEdge edge{int(keys[i].first >> 32), int(keys[i].first & 0xffffffffu)};
      if (end - i == 2 && keys[i].second != keys[i + 1].second) {
        edge.face_a = keys[i].second, edge.face_b = keys[i + 1].second;
        setEdgeArc(geometry, shape.getFaces().data(), &edge);
      }
      edges.push_back(edge);
      i = end;
    }
    static const std::array<Vec3, 14> kProbeDirections = {
        Vec3(1, 0, 0),   Vec3(-1, 0, 0),  Vec3(0, 1, 0),   Vec3(0, -1, 0),  Vec3(0, 0, 1),
        Vec3(0, 0, -1),  Vec3(1, 1, 1),   Vec3(1, 1, -1),  Vec3(1, -1, 1),  Vec3(1, -1, -1),
        Vec3(-1, 1, 1),  Vec3(-1, 1, -1), Vec3(-1, -1, 1), Vec3(-1, -1, -1)};
    for (std::size_t k = 0; k < kProbeDirections.size(); ++k) {
      Eigen::Index extreme = 0;
      (geometry.points * kProbeDirections[k]).maxCoeff(&extreme);
      geometry.probes[k] = geometry.points.row(extreme).transpose();
    }
    geometry.hull_edges_built = true;
    return edges;
  }

  /// Vertices finite and in range; faces well encoded (at least three in-range
  /// indices each, exactly filling the face list).
  static bool listsAreValid(const fcl::Convex<S>& convex) {
    const auto& vertices = convex.getVertices();
    if (vertices.empty() || convex.getFaceCount() < 1) return false;
    for (const auto& v : vertices) {
      if (!((v.array().abs() <= kMaxDiskLength<S>).all())) return false;
    }
    const std::vector<int>& faces = convex.getFaces();
    std::size_t at = 0;
    for (int f = 0; f < convex.getFaceCount(); ++f) {
      if (at >= faces.size()) return false;
      const int count = faces[at];
      if (count < 3 || at + 1 + std::size_t(count) > faces.size()) return false;
      for (int i = 1; i <= count; ++i) {
        if (faces[at + i] < 0 || std::size_t(faces[at + i]) >= vertices.size()) return false;
      }
      at += count + 1;
    }
    return true;
  }

  Vec3 vertex(int index) const { return convex->getVertices()[index].template cast<double>(); }

  /// The face's edges (and, for a triangle, its projection), computed on
  /// first use: each edge from vertex i to the next, with its inward normal
  /// in the face's plane (ConvexEdge).
  const ConvexFace& detailOf(const ConvexFace& face) const {
    if (face.first_edge >= 0) return face;
    const int* index = &list[face.start];
    const int count = face.count;
    face.first_edge = int(geometry.edges.size());
    for (int i = 0; i < count; ++i) {
      const Vec3 from = vertex(index[i]), to = vertex(index[i + 1 < count ? i + 1 : 0]);
      const Vec3 along = to - from, inwards = face.unit_normal.cross(along);
      const double length_squared = along.squaredNorm();
      geometry.edges.push_back(ConvexEdge{from, to, along,
                                          length_squared > 0.0 ? 1.0 / length_squared : 0.0,
                                          inwards, inwards.dot(from)});
    }
    if (count == 3) {
      face.triangle = int(geometry.triangles.size());
      geometry.triangles.emplace_back(vertex(index[0]), vertex(index[1]), vertex(index[2]));
    }
    return face;
  }

  Projection ontoFace(const Vec3& y, const ConvexFace& face) const {
    if (face.count == 3) return geometry.triangles[std::size_t(detailOf(face).triangle)].project(y);
    return projectOntoPolygon(y, face.count, [&](int i) { return vertex(list[face.start + i]); },
                              face.unit_normal);
  }

  /// Where on a face its nearest point to y lies: inside it (`face`), on the
  /// edge from its vertex `index` to the next (`edge`), or at its vertex
  /// `index` (`vertex`); positions in the face's own list.
  enum class Feature { face, edge, vertex };
  struct NearestOnFace {
    Vec3 q;
    Feature feature;
    int index;
  };

  /// The nearest point of the face's polygon to y, and its feature: the foot on
  /// the plane when it lies inside every edge, else the nearest point of the
  /// nearest edge among those y lies beyond (an end of it: a vertex). Only
  /// those can hold it: at the nearest point of a convex polygon, y minus
  /// that point is an outward normal of the polygon. A face of zero area is
  /// its edges.
  NearestOnFace nearestOnFace(const Vec3& y, const ConvexFace& face) const {
    const ConvexEdge* edge = &geometry.edges[std::size_t(detailOf(face).first_edge)];
    const bool has_area = face.unit_normal.squaredNorm() > 0.0;
    bool inside = has_area;
    for (int i = 0; i < face.count && inside; ++i) {
      inside = edge[i].inwards.dot(y) >= edge[i].inwards_offset;
    }
    if (inside) {
      return {y - (face.unit_normal.dot(y) - face.offset) * face.unit_normal, Feature::face, 0};
    }
    NearestOnFace best{edge[0].from, Feature::vertex, 0};
    double best_squared = std::numeric_limits<double>::infinity();
    for (int i = 0; i < face.count; ++i) {
      const ConvexEdge& e = edge[i];
      if (has_area && e.inwards.dot(y) >= e.inwards_offset) continue;
      const double t = e.along.dot(y - e.from) * e.inverse_length_squared;
      const int next = i + 1 < face.count ? i + 1 : 0;
      const NearestOnFace on_edge = t <= 0.0   ? NearestOnFace{e.from, Feature::vertex, i}
                                    : t >= 1.0 ? NearestOnFace{e.to, Feature::vertex, next}
                                               : NearestOnFace{e.from + t * e.along, Feature::edge, i};
      const double squared = (y - on_edge.q).squaredNorm();
      if (squared < best_squared) best = on_edge, best_squared = squared;
    }
    return best;
  }

  /// A common point of the disk and the face, in the disk's in-plane
  /// coordinates, given a disk point m on the face's plane: the disk meets
  /// that plane along the chord through m whose in-plane direction is normal
  /// to the face normal's in-plane part; the middle of the chord's stretch
  /// inside every edge (the polygon is convex, counter-clockwise seen from
  /// outside), if that stretch is not empty. None when it is, or when the
  /// disk is parallel to the plane (no chord).
  std::optional<Vec2> chordWithinRim(const DiskInShape& disk, const ConvexFace& face,
                                     const Vec3& m) const {
    const Vec2 s_m = disk.inPlane(m - disk.c);
    const Vec2 normal_in_disk = disk.inPlane(face.unit_normal);
    const Vec2 along(-normal_in_disk.y(), normal_in_disk.x());
    const auto chord = stretchWithinRim(disk, s_m, along);
    if (!chord) return std::nullopt;
    auto [low, high] = *chord;
    const Vec3 direction = along.x() * disk.u + along.y() * disk.v;  // the chord's, in 3-D
    for (int i = 0; i < face.count; ++i) {  // clip to each edge's inner side
      const ConvexEdge& edge = geometry.edges[std::size_t(detailOf(face).first_edge + i)];
      const double start = edge.inwards.dot(m) - edge.inwards_offset;
      const double rate = edge.inwards.dot(direction);
      if (rate == 0.0) {
        if (!(start >= 0.0)) return std::nullopt;
        continue;
      }
      const double bound = -start / rate;
      if (rate > 0.0) {
        low = std::max(low, bound);
      } else {
        high = std::min(high, bound);
      }
    }
    if (!(low <= high)) return std::nullopt;
    return Vec2(s_m + (0.5 * (low + high)) * along);
  }

  /// The polytope's nearest point to y as `onto_face` gives it on the face
  /// holding it (any type with a point q), and that face; nullopt when y lies
  /// inside every face plane. Only faces whose planes have y strictly outside
  /// can hold the nearest point, and a face's plane distance bounds its
  /// polygon's distance from below: the face whose plane is farthest first
  /// (usually the answer: y's foot on it lies inside it), then the others
  /// whose plane distance can still beat the best.
  template <typename OntoFace>
  auto nearestOverFaces(const Vec3& y, OntoFace&& onto_face, int start_face = -1) const
      -> std::optional<std::pair<decltype(onto_face(faces[0])), int>> {
    const std::size_t face_count = faces.size();
    // A large hull: the face reached by climbing the face graph to a plane
    // height of y that no neighbour exceeds. Its nearest point is the
    // polytope's when its plane's distance is reached or no vertex lies
    // beyond it (the tests below); else every plane is scanned.
    if (face_count >= kClimbingFaceCount) {
      const int climbed = climbToHighestPlane(y, start_face);
      const double height = planeHeight(climbed, y);
      if (height > 0.0) {
        auto on_face = onto_face(faces[climbed]);
        if (isNearestPoint(y, on_face.q, height)) return std::pair(on_face, climbed);
      }
    }
    const Eigen::VectorXd& heights = planeHeights(y);
    const double* height_of = heights.data();
    const auto [farthest_height, farthest_index] = largestWithFirstIndex(heights);
    if (!(farthest_height > 0.0)) return std::nullopt;
    const int farthest = int(farthest_index);
    auto best = onto_face(faces[farthest]);
    int best_face = farthest;
    if (isNearestPoint(y, best.q, farthest_height)) return std::pair(best, best_face);
    double best_distance = (y - best.q).norm();
    for (std::size_t f = 0; f < face_count; ++f) {
      if (int(f) == farthest) continue;
      const double height = height_of[f];
      if (!(height > 0.0) || !(height < best_distance)) continue;
      const ConvexFace& ball = ballOf(geometry, list, faces[f]);
      const double reach = best_distance + ball.radius;
      if (!((y - ball.centre).squaredNorm() < reach * reach)) continue;
      const auto on_face = onto_face(faces[f]);
      const double distance = (y - on_face.q).norm();
      if (distance < best_distance) best = on_face, best_distance = distance, best_face = int(f);
    }
    return std::pair(best, best_face);
  }

  /// y's height over face f's plane (its signed distance, outwards).
  double planeHeight(int f, const Vec3& y) const {
    return planes(f, 0) * y.x() + planes(f, 1) * y.y() + planes(f, 2) * y.z() - planes(f, 3);
  }

  /// From `start` (or, for -1, the farthest of the climb's start faces), the
  /// neighbour whose plane is farthest from y while that is farther: a face
  /// whose plane height of y no neighbour exceeds (usually, not always, the
  /// farthest plane: nearestOverFaces proves what it finds).
  int climbToHighestPlane(const Vec3& y, int start) const {
    if (geometry.neighbour_start.empty()) buildFaceGraph(convex->getFaces(), &geometry);
    int at = start < 0 ? geometry.climb_starts[0] : start;
    double height = planeHeight(at, y);
    if (start < 0) {
      for (const int f : geometry.climb_starts) {
        const double h = planeHeight(f, y);
        if (h > height) at = f, height = h;
      }
    }
    for (;;) {  // heights increase strictly: no face twice
      int next = -1;
      for (int k = geometry.neighbour_start[at]; k < geometry.neighbour_start[at + 1]; ++k) {
        const int f = geometry.face_neighbours[k];
        const double h = planeHeight(f, y);
        if (h > height) next = f, height = h;
      }
      if (next < 0) return at;
      at = next;
    }
  }

  /// Whether q, a point of a face whose plane lies `height` below y, is the
  /// polytope's point nearest y: when |y - q| reaches that plane's distance
  /// (every face plane bounds the polytope's distance from below), or when
  /// no vertex lies beyond q along y - q (the optimality condition
  /// (y - q).(v - q) <= 0 for every point v of the hull, checked at its
  /// vertices), up to the rounding of the scan's products: mostly q is on
  /// the face's boundary and this one support scan settles it.
  bool isNearestPoint(const Vec3& y, const Vec3& q, double height) const {
    const Vec3 away = y - q;
    if (away.norm() <= height) return true;
    const double slack = kDotRounding * away.cwiseAbs().sum() * geometry.bounding_radius;
    return supportValue(away) <= away.dot(q) + slack;
  }

  /// The polytope's nearest point to y, with psi's Hessian (nearestOverFaces
  /// with the faces' projections). y inside every face plane is inside the
  /// solid (its own nearest point), unless the polytope is flat: then its
  /// largest face (the polygon) decides, or, when every face has zero area (a
  /// polytope collapsed to a segment or a point), the nearest of the faces'
  /// edges.
  Projection project(const Vec3& y) const {
    if (const auto nearest =
            nearestOverFaces(y, [&](const ConvexFace& face) { return ontoFace(y, face); })) {
      return nearest->first;
    }
    if (!flat || largest_face < 0) return Projection{y, FactoredHessian()};
    if (faces[largest_face].unit_normal.squaredNorm() > 0.0) {
      return ontoFace(y, faces[largest_face]);
    }
    Projection best = ontoFace(y, faces[0]);
    for (std::size_t f = 1; f < faces.size(); ++f) {
      const Projection on_face = ontoFace(y, faces[f]);
      if ((y - on_face.q).squaredNorm() < (y - best.q).squaredNorm()) best = on_face;
    }
    return best;
  }

  /// The polytope's nearest feature to y (nearestOverFaces with
  /// nearestOnFace), nullopt when y lies inside every face plane.
  std::optional<std::pair<NearestOnFace, int>> nearestFeature(const Vec3& y,
                                                              int start_face = -1) const {
    return nearestOverFaces(
        y, [&](const ConvexFace& face) { return nearestOnFace(y, face); }, start_face);
  }

  /// w.v for every vertex v, in one vectorised pass (this thread's buffer,
  /// valid until the next call).
  const Eigen::VectorXd& alongVertices(const Vec3& w) const {
    Eigen::VectorXd& along = geometry.along;
    along.noalias() = points.col(0) * w.x() + points.col(1) * w.y() + points.col(2) * w.z();
    return along;
  }

  /// How far apart the polytope of the face planes (project) and the hull of
  /// the vertices (support) may be: the faces' thickness, by which a
  /// certificate comparing the two cannot close (supportMismatch in
  /// disk_shape_solver.h).
  double supportMismatch() const { return face_thickness; }

  /// The support search's start for y: the vertex most towards y from the
  /// centre.
  HullSimplex simplexTowards(const Vec3& y) const {
    HullSimplex start;
    start.count = 1;
    start.index[0] = supportIndex(y - geometry.centre);
    return start;
  }

  /// The simplex of vertices whose hull holds y's nearest point of the
  /// vertices' hull (nearestHullSimplex with their support), from `start`.
  HullSimplex nearestVertexSimplex(const Vec3& y, const HullSimplex& start) const {
    return nearestHullSimplex(
        y, start, [&](const Vec3& w) { return supportIndex(w); },
        [&](int index) -> Vec3 { return points.row(index).transpose(); });
  }

  /// An upper bound of the distance from x to the hull of the vertices: |x -
  /// q| for the point q of that hull that the support search reaches, 0 for
  /// x inside a tetrahedron of vertices.
  double supportSetDistanceAbove(const Vec3& x) const {
    const HullSimplex nearest = nearestVertexSimplex(x, simplexTowards(x));
    return nearest.inside() ? 0.0 : nearest.v.norm();
  }

  /// Every face plane's height of y, in one vectorised pass over the plane
  /// columns (this thread's buffer, valid until the next call).
  const Eigen::VectorXd& planeHeights(const Vec3& y) const {
    Eigen::VectorXd& heights = geometry.heights;
    heights.noalias() = planes.col(0) * y.x() + planes.col(1) * y.y() + planes.col(2) * y.z() -
                        planes.col(3);
    return heights;
  }

  /// How deep y lies inside every face plane: the least of minus its plane
  /// heights (negative beyond a plane).
  double depthInsidePlanes(const Vec3& y) const { return -planeHeights(y).maxCoeff(); }

  /// The vertices' mean (the hull's own frame origin may lie anywhere).
  Vec3 centre() const { return geometry.centre; }

  /// max over the vertices of w.v.
  double supportValue(const Vec3& w) const { return mostAlong(w); }

  /// A cluster's rows of clustered_points.
  auto clusterRows(const typename ConvexGeometry::VertexCluster& cluster) const {
    return geometry.clustered_points.middleRows(cluster.begin, cluster.end - cluster.begin);
  }

  /// Visits the hull's clusters for the largest w.v: first the cluster whose
  /// ball reaches farthest along w, then every other whose ball bound
  /// w.c + |w| r, plus twice the products' rounding (kDotRounding |w|_1 B
  /// each), reaches best(), the largest value found: a skipped cluster holds
  /// no vertex whose w.v reaches it.
  template <typename Scan, typename Best>
  void scanClustersAlong(const Vec3& w, Scan&& scan, Best&& best) const {
    const auto& clusters = geometry.clusters;
    const double w_length = w.norm();
    const double slack = 2.0 * kDotRounding * w.cwiseAbs().sum() * geometry.bounding_radius;
    std::size_t first = 0;
    double first_bound = -std::numeric_limits<double>::infinity();
    for (std::size_t g = 0; g < clusters.size(); ++g) {
      const double bound = w.dot(clusters[g].centre) + w_length * clusters[g].radius;
      if (bound > first_bound) first = g, first_bound = bound;
    }
    scan(clusters[first]);
    for (std::size_t g = 0; g < clusters.size(); ++g) {
      if (g == first) continue;
      const double bound = w.dot(clusters[g].centre) + w_length * clusters[g].radius;
      if (bound + slack >= best()) scan(clusters[g]);
    }
  }

  /// max over the vertices of w.v, as alongVertices(w).maxCoeff() gives it
  /// (the same products, so the same value): by clusters where the hull has
  /// them (scanClustersAlong).
  double mostAlong(const Vec3& w) const {
    if (geometry.clusters.empty()) return alongVertices(w).maxCoeff();
    double best = 0.0;
    bool scanned = false;
    scanClustersAlong(
        w,
        [&](const typename ConvexGeometry::VertexCluster& cluster) {
          const auto rows = clusterRows(cluster);
          const double most =
              (rows.col(0) * w.x() + rows.col(1) * w.y() + rows.col(2) * w.z()).maxCoeff();
          best = scanned ? std::max(best, most) : most;
          scanned = true;
        },
        [&] { return best; });
    return best;
  }

  /// The index of the vertex maximising w.v, the first of those that tie:
  /// the same whether the hull has its clusters yet or not (the same
  /// products, and scanClustersAlong skips no cluster that could tie), so
  /// that answers do not depend on the queries before. 0 for a w whose
  /// products are all NaN.
  int supportIndex(const Vec3& w) const {
    if (geometry.clusters.empty()) {
      const Eigen::VectorXd& along = alongVertices(w);
      const Eigen::Index at = largestWithFirstIndex(along).second;
      return at == along.size() ? 0 : int(at);
    }
    double best = -std::numeric_limits<double>::infinity();
    int best_index = -1;
    // A cluster's largest value, and its first vertex reaching it, the least
    // index among them (a cluster's rows are in index order); on the stack: a
    // cluster holds kClusterSize at most.
    scanClustersAlong(
        w,
        [&](const typename ConvexGeometry::VertexCluster& cluster) {
          const auto rows = clusterRows(cluster);
          const Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kClusterSize, 1> along =
              rows.col(0) * w.x() + rows.col(1) * w.y() + rows.col(2) * w.z();
          const auto [most, at] = largestWithFirstIndex(along);
          if (most < best || at == along.size()) return;
          const int index = geometry.cluster_order[std::size_t(cluster.begin + at)];
          if (most > best || index < best_index) best = most, best_index = index;
        },
        [&] { return best; });
    return best_index < 0 ? 0 : best_index;
  }

  Vec3 support(const Vec3& w) const { return points.row(supportIndex(w)).transpose(); }

  /// The faces of nonzero area, for the nearly-parallel candidates.
  template <typename Visit>
  void forEachFace(Visit&& visit) const {
    for (const ConvexFace& face : faces) {
      if (!(face.unit_normal.squaredNorm() > 0.0)) continue;
      visit(face.unit_normal, face.count, [&](int i) { return vertex(list[face.start + i]); });
    }
  }
};

/// The hull of a Convex's vertices alone as the generic solver's Target, in
/// the hull's frame: the projection by the support search (nearestVertexSimplex,
/// its nearest simplex: a vertex, an edge or a triangle of vertices), the
/// support a vertex (ties: supportIndex's first). Both read the same set, so
/// the certificate needs no faces' thickness, and the answer is exact to the
/// solver's tolerance on that set; a simplex search stopped short by rounding
/// still projects onto a point of the set (the distance stays an upper bound),
/// and only the speed depends on its Hessian. It answers the meetings of the
/// face planes that lie off the vertices' hull where the closed form on the
/// vertices does not settle (ConvexTraits::answerOffVertices): its projection
/// costs support scans, which only such rare pairs pay.
template <typename S>
struct VertexHullTarget {
  const ConvexTarget<S>& hull;

  /// The point of the vertices' hull nearest y, with psi's Hessian I - D proj:
  /// I at a vertex, I - e e^T on an edge of direction e, m m^T on a triangle
  /// of normal m, 0 inside (a degenerate simplex, of zero length or area,
  /// takes I).
  Projection project(const Vec3& y) const {
    const HullSimplex nearest = hull.nearestVertexSimplex(y, hull.simplexTowards(y));
    if (nearest.inside()) return Projection{y, FactoredHessian()};
    const Vec3 q = y + nearest.v;
    if (nearest.count == 2) {
      const Vec3 edge = nearest.relative[1] - nearest.relative[0];
      const double length = edge.norm();
      if (length > 0.0) return Projection{q, FactoredHessian::identity().add(-1.0, edge / length)};
    } else if (nearest.count == 3) {
      const Vec3 normal = (nearest.relative[1] - nearest.relative[0])
                              .cross(nearest.relative[2] - nearest.relative[0]);
      const double area = normal.norm();
      if (area > 0.0) return Projection{q, FactoredHessian().add(1.0, normal / area)};
    }
    return Projection{q, FactoredHessian::identity()};
  }
  Vec3 support(const Vec3& w) const { return hull.support(w); }
  double leastAlong(const Vec3& w) const { return -hull.mostAlong(-w); }
  Vec3 centre() const { return hull.centre(); }
};

template <typename S>
struct ConvexTraits {
  /// Vertices finite and in range; faces well encoded (ConvexTarget::listsAreValid),
  /// decided once per hull and thread with its geometry.
  static bool valid(const fcl::Convex<S>& convex) {
    return ConvexTarget<S>::geometryOf(convex).valid;
  }
  static double boundingRadius(const fcl::Convex<S>& convex) {
    return ConvexTarget<S>::verifiedGeometryOf(convex).bounding_radius;
  }
  static double inflation(const fcl::Convex<S>&) { return 0.0; }
  /// Where the closed form reads the vertices only (kSupportSearchVertexCount),
  /// intersect() asked for no contact tries it before the generic early exit,
  /// which reads the faces' thickness, which a hull not kept would compute its
  /// faces for. The same verdicts: a pair the early exit calls apart is
  /// further apart than the touching tolerance, and the closed form decides
  /// as the generic path's.
  static bool closedFormDecidesFirst(const fcl::Convex<S>& convex) {
    return std::size_t(ConvexTarget<S>::verifiedGeometryOf(convex).points.rows()) >=
           kSupportSearchVertexCount;
  }
  static ConvexTarget<S> target(const fcl::Convex<S>& convex) {
    const ConvexGeometry& geometry = ConvexTarget<S>::verifiedGeometryOf(convex);
    ConvexTarget<S>::ensureFaces(convex, geometry);
    return ConvexTarget<S>(convex, geometry);
  }
  /// The pair of a hull vertex `a` (no `b`) or edge from `a` to `b` with the
  /// disk, certified along itself with the hull's least values (`mismatch` as
  /// certifiedOrBound's), and its disk point in `next`, the next pass's start;
  /// a common point where the edge crosses the disk within the rim.
  template <typename LeastAlong>
  static LeafToDisk pairWithBoundary(const DiskInShape& disk, LeastAlong&& least_along,
                                     double scale, double mismatch, const Vec3& a, const Vec3* b,
                                     Vec3* next) {
    if (b == nullptr) {
      *next = disk.point(disk.nearest(a));
      return certifiedAlongItself(disk, least_along, (a - *next).norm(), *next, a, scale, mismatch);
    }
    const SegmentToDisk edge = segmentToDisk(disk, a, *b);
    *next = edge.p_disk;
    const LeafToDisk by_edge = certifiedSegmentPair(disk, least_along, edge, scale, mismatch);
    if (by_edge.exact) return by_edge;
    if (const auto common = segmentCrossingWithinRim(disk, a, *b)) return meetingAt(disk, *common);
    return LeafToDisk{};
  }

  /// The polytope by its nearest feature (docs/disk_shape_distance.md,
  /// section 4): found through the face planes (closedFormByFaces) below
  /// kSupportSearchVertexCount vertices, through the vertices' support
  /// alone (closedFormBySupport) from there on. Not exact means only "not
  /// settled here": the generic solver answers.
  static LeafToDisk closedForm(const DiskInShape& disk, const fcl::Convex<S>& convex,
                               double scale) {
    const ConvexGeometry& geometry = ConvexTarget<S>::verifiedGeometryOf(convex);
    if (std::size_t(geometry.points.rows()) >= kSupportSearchVertexCount) {
      return closedFormBySupport(disk, ConvexTarget<S>(convex, geometry), scale);
    }
    return closedFormByFaces(disk, convex, scale);
  }

  /// The answer for a meeting found at the disk point `common` inside the
  /// face planes (closedFormByFaces, the generic solver's projection) when
  /// `common` may lie farther than the faces' thickness plus
  /// kShapeGapTolerance of the scene from the vertices' hull: the planes of
  /// faces planar only to rounding reach that far beyond it near some corners
  /// (docs/disk_shape_distance.md, section 4, "Convex"). Then the closed form
  /// on the vertices alone (closedFormBySupport), else the generic solver on
  /// the vertices' hull (VertexHullTarget). With the planes reaching at most
  /// kPlanesReach thicknesses beyond the vertices' hull, no search is needed
  /// for hulls whose faces are thinner than kShapeGapTolerance / kPlanesReach
  /// of the scene (every hull of planar faces, and data in double planar to
  /// its rounding: the reach stays within the gap tolerance), nor for a point
  /// at least that reach deep inside every plane (the ball of that radius
  /// about a point outside the vertices' hull would reach farther from it).
  static std::optional<LeafToDisk> answerOffSupportSet(const DiskInShape& disk,
                                                       const fcl::Convex<S>& convex,
                                                       const Vec3& common, double scale) {
    return answerOffVertices(
        disk, ConvexTarget<S>(convex, ConvexTarget<S>::verifiedGeometryOf(convex)), common,
        scale);
  }
  /// answerOffSupportSet on the hull's target, for callers holding it (not an
  /// overload: kHasSupportSetCheck takes answerOffSupportSet's address).
  static std::optional<LeafToDisk> answerOffVertices(const DiskInShape& disk,
                                                     const ConvexTarget<S>& hull,
                                                     const Vec3& common, double scale) {
    const double reach = kPlanesReach * hull.face_thickness;
    if (!(reach > kShapeGapTolerance * scale)) return std::nullopt;
    if (hull.depthInsidePlanes(common) >= reach) return std::nullopt;
    if (hull.supportSetDistanceAbove(common) <= hull.face_thickness + kShapeGapTolerance * scale) {
      return std::nullopt;
    }
    const LeafToDisk by_vertices = closedFormBySupport(disk, hull, scale, kOffSupportSetPasses);
    if (by_vertices.exact) return by_vertices;
    return exactLeafOf(solveDiskShape(VertexHullTarget<S>{hull}, disk, 0.0, scale,
                                      SolverGoal::distance));
  }

  /// The closed form's passes (at most `passes`) with the hull's feature nearest p found by the
  /// support search (nearestHullSimplex, from the last pass's simplex; the
  /// first pass's from the vertex most towards p from the centre), which
  /// reads `hull`'s vertices only (its faces need not be computed): from p,
  /// the disk's point nearest the hull's centre,
  ///  * p inside a tetrahedron of vertices, or within kShapeGapTolerance of
  ///    the scene of the hull: p is a common point (at that distance);
  ///  * a vertex or an edge: paired as in closedFormByFaces;
  ///  * a triangle of vertices holding p's nearest point inside it (its plane
  ///    is then a face plane of the hull, p beyond it): the disk's point
  ///    deepest towards it, with its foot when that lies inside the triangle
  ///    (the plane separates the sets), else the triangle's vertex or edge
  ///    nearest it; where the deepest point reaches the plane, the disk's
  ///    point x on the plane between p and it is common when the triangle
  ///    holds it, else the triangle's vertex or edge nearest x is paired.
  /// Certified as closedFormByFaces, with no faces' thickness: every pair is
  /// of points of the disk and of the hull of the vertices, whose support the
  /// certificate reads.
  static LeafToDisk closedFormBySupport(const DiskInShape& disk, const ConvexTarget<S>& hull,
                                        double scale, int passes = kFeaturePasses) {
    const LeafToDisk not_settled;
    const auto least_along = [&](const Vec3& w) { return -hull.mostAlong(-w); };
    const auto certified = [&](double upper, const Vec3& p_disk, const Vec3& p_hull) {
      return certifiedAlongItself(disk, least_along, upper, p_disk, p_hull, scale);
    };
    const auto point = [&](int index) -> Vec3 { return hull.points.row(index).transpose(); };
    Vec3 p = disk.point(disk.nearest(hull.geometry.centre));
    HullSimplex simplex = hull.simplexTowards(p);
    for (int pass = 0; pass < passes; ++pass) {
      simplex = hull.nearestVertexSimplex(p, simplex);
      if (simplex.inside()) return meetingAt(p);
      const double gap = simplex.v.norm();
      if (gap <= kShapeGapTolerance * scale) {
        return certifiedOrBound(0.0, gap, p, p + simplex.v, scale);
      }
      Vec3 next;
      // A vertex or an edge of the hull paired with the disk (pairWithBoundary).
      const auto against_boundary = [&](const HullSimplex& feature) {
        const Vec3 a = point(feature.index[0]);
        const Vec3 b = point(feature.index[feature.count - 1]);
        return pairWithBoundary(disk, least_along, scale, 0.0, a, feature.count == 1 ? nullptr : &b,
                                &next);
      };
      LeafToDisk answer;
      if (simplex.count < 3) {
        answer = against_boundary(simplex);
      } else {
        // The triangle's feature nearest y: its Voronoi region's points.
        const auto triangle_region = [&](const Vec3& y) {
          HullSimplex region = simplex;
          for (int k = 0; k < 3; ++k) region.relative[k] = point(simplex.index[k]) - y;
          hull_simplex::nearestOnTriangle(&region, 0, 1, 2);
          return region;
        };
        const Vec3 a = point(simplex.index[0]), b = point(simplex.index[1]),
                   c = point(simplex.index[2]);
        const Vec3 normal = (b - a).cross(c - a);
        const double normal_length = normal.norm();
        if (!(normal_length > 0.0)) return not_settled;
        const Vec3 m = ((normal.dot(p - a) < 0.0 ? -1.0 : 1.0) / normal_length) * normal;
        const Vec3 deepest = disk.lowestAlong(m);
        const double height = m.dot(deepest - a);
        if (height > 0.0) {
          next = deepest;
          const HullSimplex below = triangle_region(deepest);
          answer = below.count == 3 ? certified(below.v.norm(), deepest, deepest + below.v)
                                    : against_boundary(below);
        } else {
          const double p_height = m.dot(p - a);
          const Vec3 x = p + (p_height / (p_height - height)) * (deepest - p);
          const HullSimplex beside = triangle_region(x);
          if (beside.count == 3) {
            return certifiedOrBound(0.0, beside.v.norm(), x, x + beside.v, scale);
          }
          answer = against_boundary(beside);
        }
      }
      if (answer.exact) return answer;
      if (next == p) break;  // a pair whose certificate stays open: no progress
      p = next;
    }
    return not_settled;
  }

  /// The polytope by its nearest feature through its face planes
  /// (docs/disk_shape_distance.md, section 4), passes of an alternating
  /// projection whose hull side is a feature solved exactly against the
  /// disk: from p, the disk's point nearest
  /// the hull's centre (the vertices' mean), the hull's feature nearest p
  /// (nearestFeature) and its pair with the disk:
  ///  * none, p inside every face plane: p is a common point;
  ///  * a vertex: it and its nearest disk point;
  ///  * an edge: segmentToDisk; where the disk meets the edge, its crossing of
  ///    the disk's plane within the rim is a common point
  ///    (segmentCrossingWithinRim);
  ///  * a face: the disk's point deepest towards it with its foot on the
  ///    face's plane, a pair when the foot lies inside the face (the plane
  ///    then separates the sets), else the face's vertex or edge nearest that
  ///    point, paired as above; if that point reaches the plane, the disk's
  ///    chord in the plane meets the face at a common point (chordWithinRim),
  ///    or passes beside it, and the face's vertex or edge nearest the chord's
  ///    point m is paired instead.
  /// A pair is the answer when the certificate along it, with the vertices'
  /// least value, closes within kShapeGapTolerance of the scene plus the
  /// faces' thickness, as the generic solver's (supportMismatch;
  /// certifiedOrBound); else its disk point is the next pass's p, up to
  /// kFeaturePasses. Not exact means only "not settled here": the generic
  /// solver answers. A flat polytope, whose plane tests cannot tell its
  /// inside, is left to it.
  static LeafToDisk closedFormByFaces(const DiskInShape& disk, const fcl::Convex<S>& convex,
                                      double scale) {
    using Feature = typename ConvexTarget<S>::Feature;
    const ConvexTarget<S> hull = target(convex);
    const LeafToDisk not_settled;
    if (hull.flat) return not_settled;
    const auto least_along = [&](const Vec3& w) { return -hull.mostAlong(-w); };
    const auto certified = [&](double upper, const Vec3& p_disk, const Vec3& p_hull) {
      return certifiedAlongItself(disk, least_along, upper, p_disk, p_hull, scale,
                                  hull.supportMismatch());
    };
    Vec3 p = disk.point(disk.nearest(hull.geometry.centre));
    int last_face = -1;  // where the next pass's climb starts
    for (int pass = 0; pass < kFeaturePasses; ++pass) {
      const auto at = hull.nearestFeature(p, last_face);
      if (!at) return answerOffVertices(disk, hull, p, scale).value_or(meetingAt(p));
      const auto& [nearest, face_index] = *at;
      last_face = face_index;
      const ConvexFace& face = hull.faces[face_index];
      // A vertex or an edge of `face` paired with the disk (pairWithBoundary).
      Vec3 next;
      const auto against_boundary = [&](const typename ConvexTarget<S>::NearestOnFace& at_boundary) {
        if (at_boundary.feature == Feature::vertex) {
          return pairWithBoundary(disk, least_along, scale, hull.supportMismatch(), at_boundary.q,
                                  nullptr, &next);
        }
        const ConvexEdge& on =
            hull.geometry.edges[std::size_t(hull.detailOf(face).first_edge + at_boundary.index)];
        return pairWithBoundary(disk, least_along, scale, hull.supportMismatch(), on.from, &on.to,
                                &next);
      };
      if (nearest.feature != Feature::face) {
        if (LeafToDisk answer = against_boundary(nearest); answer.exact) return answer;
      } else {
        next = disk.lowestAlong(face.unit_normal);
        const auto below = hull.nearestOnFace(next, face);
        const double next_height = face.unit_normal.dot(next - below.q);
        if (!(next_height > 0.0)) {
          // p lies beyond the face's plane, the deepest point on or inside it:
          // the segment between them crosses the plane at m.
          const double p_height = face.unit_normal.dot(p) - face.offset;
          const Vec3 m = p + (p_height / (p_height - next_height)) * (next - p);
          if (const auto common = hull.chordWithinRim(disk, face, m)) return meetingAt(disk, *common);
          // The chord passes beside the face: the face's vertex or edge
          // nearest m.
          next = m;
          if (const auto beside = hull.nearestOnFace(m, face); beside.feature != Feature::face) {
            if (LeafToDisk answer = against_boundary(beside); answer.exact) return answer;
          }
        } else if (below.feature == Feature::face) {
          if (LeafToDisk by_face = certified((next - below.q).norm(), next, below.q);
              by_face.exact) {
            return by_face;
          }
        } else if (LeafToDisk answer = against_boundary(below); answer.exact) {
          // The deepest point lies beyond the face's boundary: the face's
          // feature nearest it.
          return answer;
        }
      }
      if (next == p) break;  // a pair whose certificate stays open: no progress
      p = next;
    }
    return not_settled;
  }
  /// The directions among which the shortest separating translation lies
  /// (shortestSeparation adds the disk's normals and both signs), so the contact's
  /// depth is the exact penetration depth of a Convex whose faces bound the
  /// hull of its vertices: the face normals, and the vertices' and edges'
  /// candidates (feature_candidates.h; docs/penetration_depth.md, section 7).
  /// For a pair that shares a point, candidates that cannot beat the best depth
  /// found are skipped: an edge whose arc of directions cannot
  /// (edgeArcCannotBeat), and a direction whose depth along either sign is
  /// bounded by a point of the hull above the bound (FeaturePointBound), so the
  /// hull's support is evaluated only for the others.
  template <typename Search>
  static void contactDirections(const ConvexTarget<S>& target, const DiskInShape& disk,
                                Search* directions) {
    const ConvexGeometry& geometry = target.geometry;
    const std::vector<ConvexHullEdge>& hull_edges =
        ConvexTarget<S>::hullEdgesOf(*target.convex, geometry);
    const auto vertex = [&](int index) { return target.points.row(index).transpose().eval(); };
    const double rho = directions->inflation();
    // A face is the hull's support along its outward normal -w: w = -normal,
    // where F >= h_disk(-normal) + offset + rho (its plane through its first
    // vertex), computed for every face at once, before any face's bound.
    const auto normals = target.planes.template leftCols<3>();
    const Eigen::ArrayXd along_u = (normals * disk.u).array(), along_v = (normals * disk.v).array();
    const Eigen::ArrayXd face_bounds = target.planes.col(3).array() - (normals * disk.c).array() +
                                       disk.r * (along_u.square() + along_v.square()).sqrt() + rho;
    for (std::size_t f = 0; f < target.faces.size(); ++f) {
      if (face_bounds[Eigen::Index(f)] > directions->pruningBound()) continue;
      const ConvexFace& face = target.faces[f];
      FeaturePointBound<Search>{disk, vertex(target.list[face.start]), *directions, geometry.probes}
          .push_one(-face.unit_normal);
    }
    // A vertex's one candidate (addVertexCandidates), bounded by the probes.
    for (Eigen::Index i = 0; i < target.points.rows(); ++i) {
      FeaturePointBound<Search> bounded{disk, vertex(int(i)), *directions, geometry.probes};
      addVertexCandidates(disk, bounded.point, &bounded);
    }
    const bool orthonormal_disk = isOrthonormal(disk);
    for (const ConvexHullEdge& edge : hull_edges) {
      const Vec3 from = vertex(edge.from);
      if (edgeArcCannotBeat(edge, disk, orthonormal_disk, from, directions->pruningBound())) {
        continue;
      }
      const Vec3 along = vertex(edge.to) - from;
      const double length = ConvexTarget<S>::safeNorm(along);
      if (!(length > 0.0)) continue;
      FeaturePointBound<Search> bounded{disk, from, *directions, geometry.probes};
      addEdgeLineCandidates(disk, from, along / length, &bounded);
    }
  }

  /// A search's candidates, each evaluated only where it can beat the
  /// search's pruning bound: F(w) = h_disk(w) + h_core(-w) + rho, and the
  /// core's support is at least the greatest value along -w of any of its
  /// points, here the feature's `point` and the hull's probes
  /// (ConvexGeometry::probes). A direction whose bound exceeds the pruning
  /// bound along both signs cannot win, and its support is not scanned.
  template <typename Search>
  struct FeaturePointBound {
    const DiskInShape& disk;
    Vec3 point;
    Search& search;
    const std::array<Vec3, 14>& probes;

    /// The least and greatest of unit.p over the points.
    std::pair<double, double> extentAlong(const Vec3& unit) const {
      double least = unit.dot(point), most = least;
      for (const Vec3& probe : probes) {
        const double along = unit.dot(probe);
        least = std::min(least, along), most = std::max(most, along);
      }
      return {least, most};
    }
    /// w alone (the feature can be the support along -w only).
    void push_one(const Vec3& w) {
      const double length = w.norm();
      const double bound = search.pruningBound();
      if (length > 0.0 && bound < std::numeric_limits<double>::infinity()) {
        const Vec3 unit = w / length;
        if (disk.support(unit) - extentAlong(unit).first + search.inflation() > bound) return;
      }
      search.push_one(w);
    }
    /// w and -w, each skipped on its own bound.
    void push_back(const Vec3& w) {
      const double length = w.norm();
      const double bound = search.pruningBound();
      if (length > 0.0 && bound < std::numeric_limits<double>::infinity()) {
        const Vec3 unit = w / length;
        const auto [least, most] = extentAlong(unit);
        const double rho = search.inflation();
        if (!(disk.support(unit) - least + rho > bound)) search.push_one(w);
        if (!(disk.support(-unit) + most + rho > bound)) search.push_one(-w);
        return;
      }
      search.push_back(w);
    }
    bool prunes() const { return search.prunes(); }
    double pruneSlack() const { return search.pruneSlack(); }
    double pruningBound() const { return search.pruningBound(); }
    double inflation() const { return search.inflation(); }
  };

  /// Whether the disk's axes are orthonormal to rounding, so that |P w|^2 =
  /// 1 - (n.w)^2 (the axes solvedDiskInShape gives a Convex pair).
  static bool isOrthonormal(const DiskInShape& disk) {
    constexpr double kAxesRounding = 1e-12;
    return std::abs(disk.u.squaredNorm() - 1.0) <= kAxesRounding &&
           std::abs(disk.v.squaredNorm() - 1.0) <= kAxesRounding &&
           std::abs(disk.u.dot(disk.v)) <= kAxesRounding &&
           (disk.u.cross(disk.v) - disk.n).cwiseAbs().maxCoeff() <= kAxesRounding;
  }

  /// Whether F exceeds `bound` on the whole arc of directions where `edge` is
  /// the hull's support: w normal to the edge with -w between its two faces'
  /// outward normals n1, n2 (docs/penetration_depth.md, section 7). There
  /// F(w) = w.(c - a) + r |P w| (a on the edge), bounded below on the arc
  /// -w(t) = cos t n1 + sin t m (m the unit part of n2 normal to n1, t in
  /// [0, alpha]) by the least of the linear term (a sinusoid in t: its ends,
  /// or its minimum where its slope turns from - to + inside) plus r times the
  /// least |P w| = sqrt(1 - max (n.w)^2) (the same for the sinusoid n.w), less
  /// what widening the arc by kEdgeArcMargin plus the faces' thickness over
  /// their size could lower it (F moves at most |c - a| + r per radian).
  /// False (the edge is searched) where that does not hold: an edge of one or
  /// three faces, faces too thin for their normals, faces back to back, or no
  /// finite bound yet.
  static bool edgeArcCannotBeat(const ConvexHullEdge& edge, const DiskInShape& disk,
                                bool orthonormal_disk, const Vec3& a, double bound) {
    if (!edge.prunable || !(bound < std::numeric_limits<double>::infinity())) return false;
    // The sinusoid A cos t + B sin t on [0, alpha]: its least value and its
    // largest magnitude come from its ends and its slopes' signs there.
    const auto slope_at_end = [&](double A, double B) {
      return B * edge.cos_alpha - A * edge.sin_alpha;
    };
    const Vec3 d = disk.c - a;
    const double A = -edge.n1.dot(d), B = -edge.m.dot(d);
    double least_linear = std::min(A, -edge.n2.dot(d));
    if (B <= 0.0 && slope_at_end(A, B) >= 0.0) least_linear = -std::sqrt(A * A + B * B);
    double in_plane = 0.0;  // a lower bound of |P w| on the arc
    if (orthonormal_disk) {
      const double A_n = -edge.n1.dot(disk.n), B_n = -edge.m.dot(disk.n);
      double most_normal = std::max(std::abs(A_n), std::abs(edge.n2.dot(disk.n)));
      if ((B_n >= 0.0) != (slope_at_end(A_n, B_n) > 0.0)) {
        most_normal = std::sqrt(A_n * A_n + B_n * B_n);
      }
      in_plane = std::sqrt(std::max(0.0, 1.0 - most_normal * most_normal));
    }
    const double lower = least_linear + disk.r * in_plane - edge.widening * (d.norm() + disk.r);
    return lower > bound;
  }
};

// The generic driver finds the meeting check by its address: one function.
static_assert(kHasSupportSetCheck<ConvexTraits<double>> && kHasSupportSetCheck<ConvexTraits<float>>);

}  // namespace

template <typename S>
struct DiskShapePair<fcl::Convex<S>>
    : GenericDiskShapePair<S, fcl::Convex<S>, ConvexTraits<S>> {};

}  // namespace internal
}  // namespace fcl_disk

FCL_DISK_INSTANTIATE_DISK_SHAPE_PAIR(fcl::Convex)

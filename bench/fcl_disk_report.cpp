// fcl_disk_report: speed against error for every disk-disk solver, on the same
// pairs, in one run.
//
// Solvers (all through plain fcl::distance on CollisionObjects, so FCL's dispatch
// is included in every time):
//   exact, almohamad_selim     Disk objects; the method is switched with
//                              registerDiskFunctions().
//   gjk_libccd_h<h>,           FCL 0.7's own GJK on Cylinder(r, h) for
//   gjk_indep_h<h>             h in {1e-2, 1e-4, 1e-6}, default DistanceRequest
//                              (distance_tolerance 1e-6) but the solver type.
//   exact_float                Disk<float> objects at the pair's poses rounded to
//                              float (path "fcl::distance, float"; its error
//                              includes that rounding, ~1e-7 of the scene).
// plus, for the hook's overhead in the same run, the two disk solvers called
// directly (exact_direct, almohamad_selim_direct; path "direct"), and
// fcl_entry_only: the disk pair through fcl::distance with a result already at
// distance 0, which FCL's shape-pair entries (and fcl_disk's) leave alone, so
// the entry path and its Disk test without a solver (fcl_disk's object-level
// entry, docs/fcl_hook.md): the floor under any disk query through
// fcl::distance (timed only; no error, not in the CSV).
//
// Pairs: every family of test/disk_families.h (double), fixed seed. Error:
// |d - d_ref| / (r1 + r2 + |c1 - c2|), d_ref from the independent
// long-double reference of test/reference_distance.h. FCL reports overlap of
// the cylinders as -1 (unsigned distance); that is read as distance 0.
//
// Timing: for each pair and solver, the same query is repeated k times in a
// batch timed with std::chrono::steady_clock (k chosen so a batch lasts about
// --batch-ns, to get far above the clock's ~20 ns cost, which is measured at
// start-up and subtracted); the pair's time is the median of --reps batches.
// Solvers are interleaved pair by pair (rotating the order), so drifts of a
// shared machine hit every solver alike. Repeating one query lets the branch
// predictor learn it; bench_disk_distance cycles through a pool instead.
//
// Output: a markdown table on stdout (per solver and family: median and p99
// ns/query, median and max error), the headline ratios, and in --out:
//   report.csv        one row per (solver, family) with those figures and the
//                     pair of largest error;
//   report.png        time against error, log-log (bench/plot_report.py);
//   report_pairs.csv  with --pairs-csv: one row per (pair, solver).
//
// Then a section on a disk against every other FCL primitive (--shape-pairs N
// random cases per shape, bench/disk_shape_cases.h: disk radius 0.5, shapes of
// size ~0.5, centres in the unit ball, random rotations). Queries, all plain
// fcl::distance on CollisionObjects, timed like the disk pairs above:
//   disk                    Disk(r) against X, default request: whatever answers a
//                           Disk in this build;
//   disk_float              the same in float (Disk<float>, the shape and the
//                           poses rounded to float);
//   sphere_<libccd|indep>   FCL's Sphere(r) at the disk's pose against X: the
//                           baseline (time only: no reference for it here);
//   gjk_<libccd|indep>      FCL on a real Cylinder(r, 0) at the disk's pose: GJK on
//                           the flat cylinder, which is exactly the disk.
// Every query kind first runs once over all cases of a shape in a forked child;
// one that crashes, hangs, leaves the distance unset or makes FCL print "not
// supported" is skipped and named (FCL 0.7: Sphere and Cylinder against
// Halfspace or Plane segfault under libccd; no TriangleP pair at all). Error:
// |d - d_ref| / (r + R_S + |c_D - c_S|), d_ref from the independent long-double
// reference of test/disk_shape_oracle.h. Writes shapes.csv (one row per
// shape) and shapes.png (bench/plot_shapes.py) in --out. --no-shapes skips the
// section, --shapes-only runs nothing else.
//
// Then a section on the penetration depth PD of intersecting disk pairs
// (--penetration-pairs N per family, bench/disk_penetration_cases.h: chain
// links, a disk through another's interior, a rim cap through a face, coplanar
// overlap, coaxial-centred crossing, nearly touching from inside (PD 1e-9..1e-3
// of the scene), far from the origin (translated by 1e5), random intersecting;
// fixed seed, kept when fcl_disk::intersectDisks says they intersect). Queries,
// plain fcl::distance on CollisionObjects with enable_signed_distance (so
// min_distance = -PD), timed like the disk pairs above:
//   disk                    the Disk pair, GST_LIBCCD (fcl_disk's hook);
//   disk_direct             fcl_disk::diskPenetration called directly;
//   epa_libccd_h<h>         FCL on Cylinder(r, h) pairs, GST_LIBCCD: libccd's EPA;
//   indep_h<h>              the same, GST_INDEP: FCL's entry calls collide() and
//                           reports minus the contact depth (FCL's own EPA),
// for h in {1e-2, 1e-4, 1e-6}. FCL query kinds are probed per family in a forked
// child first, as in the shape section (Debian's libfcl 0.7 keeps its asserts:
// indep's collide() reports negative contact depths on these cylinder pairs, so
// its signed-distance entry aborts on `index != -1`; libccd's EPA trips an
// assert on some families). A query that throws (libccd's EPA: std::logic_error
// "origin outside of the polytope") is counted and named, not timed. Error:
// |(-min_distance) - PD_ref| / (r1 + r2 + |c1 - c2|), PD_ref from the
// independent long-double reference of test/reference_penetration.h on the
// first 200 pairs of each family (it costs ~1 ms a pair), and against
// diskPenetration on every pair; without that header the errors are against
// diskPenetration only, and labelled so.
// A second table there: the PD of a Disk against each shape with an exact PD in
// fcl_disk (Sphere, Box, Capsule, Cylinder, Cone, Convex, Halfspace, Plane,
// TriangleP; --penetration-pairs N per shape, bench/disk_shape_penetration_cases.h:
// test_disk_shape_penetration's draws, disk radius 0.2..1, centres in the unit
// ball, random rotations; fixed seed, kept when fcl_disk::diskShapeIntersect
// says they intersect). Queries, plain fcl::distance with enable_signed_distance
// and enable_nearest_points, GST_LIBCCD, timed and probed like the disk pairs:
//   disk                    Disk(r) against the shape (fcl_disk's hook);
//   epa_libccd_h1e-6r       FCL's Cylinder(r, 1e-6 r) in the disk's place:
//                           libccd's EPA on the flat cylinder
// (FCL 0.7 segfaults on the cylinder against Halfspace and Plane under libccd
// and has no TriangleP pair: those cells are skipped and named). Error:
// |(-min_distance) - PD_ref| / (r + 1 + 2) (the test's scale), PD_ref from the
// independent long-double reference of test/reference_shape_penetration.h on
// the first 200 pairs of each shape. Writes penetration.csv (one row per query
// and family, then per query and shape as family "shape:<name>") in --out.
// --no-penetration skips the section, --penetration-only runs nothing else
// (with --shapes-only: those two sections).
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>
#include <fcl_disk/fcl_disk.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <unistd.h>
#include <vector>

#include "disk_families.h"
#include "reference_distance.h"

#include <fcl/geometry/shape/sphere.h>

#include <array>
#include <limits>

#include "disk_shape_cases.h"
#include "disk_shape_oracle.h"

#include "disk_penetration_cases.h"
#include "reference_penetration.h"

#include "disk_shape_penetration_cases.h"
#include "reference_shape_penetration.h"

#ifndef FCL_DISK_PLOT_SCRIPT
#define FCL_DISK_PLOT_SCRIPT "bench/plot_report.py"
#endif
#ifndef FCL_DISK_PLOT_SHAPES_SCRIPT
#define FCL_DISK_PLOT_SHAPES_SCRIPT "bench/plot_shapes.py"
#endif
#ifndef FCL_DISK_DEFAULT_OUT
#define FCL_DISK_DEFAULT_OUT "build/report"
#endif

namespace {

namespace fam = fcl_disk_families;
namespace ref = fcl_disk_reference;
using Clock = std::chrono::steady_clock;
using Case = fam::DiskPairCase<double>;

// ---------------------------------------------------------------------------
// Options.

struct Options {
  int pairs_per_family = 10000;
  int reps = 5;               ///< batches per (pair, solver); the median is kept
  double batch_ns = 2000;     ///< target duration of one batch
  std::uint64_t seed = 20240601;
  std::string out_dir = FCL_DISK_DEFAULT_OUT;
  bool plot = true;
  bool quick = false;
  bool pairs_csv = false;     ///< also write one row per (pair, solver)
  int shape_pairs = 2000;     ///< disk-vs-shape section: cases per shape
  bool shapes = true;         ///< run the disk-vs-shape section
  bool shapes_only = false;   ///< run only the disk-vs-shape section
  /// Penetration section: intersecting pairs per family (and per shape). FCL's
  /// thin-cylinder EPA costs ~5-300 us a query and runs ~7 times per pair (first
  /// answer, calibration, 5 batches of one) for each of 3 heights: ~0.7 ms per
  /// pair on the reference machine (2-core EPYC), so 8 families of 2000 pairs
  /// (plus the reference on 200 of each) take ~15 s.
  int penetration_pairs = 2000;
  bool penetration = true;        ///< run the penetration section
  bool penetration_only = false;  ///< run only the penetration section
};

void printUsage(const char* argv0) {
  std::printf(
      "Usage: %s [--quick] [--out DIR] [--pairs N] [--reps R] [--batch-ns T] [--seed S] "
      "[--pairs-csv] [--no-plot] [--shape-pairs N] [--no-shapes] [--shapes-only]\n"
      "       [--penetration-pairs N] [--no-penetration] [--penetration-only]\n"
      "Runs every disk-disk solver (exact, almohamad_selim, FCL GJK libccd/indep on\n"
      "Cylinder(r, h), h = 1e-2, 1e-4, 1e-6) through fcl::distance on every configuration\n"
      "family, and reports time per query against error vs a long-double reference.\n"
      "  --quick       20 pairs per family, 3 batches: a smoke test of a few seconds\n"
      "  --out DIR     where report.csv and report.png (and report_pairs.csv) go\n"
      "                (default %s)\n"
      "  --pairs N     pairs per family (default 10000; quick 20)\n"
      "  --reps R      timed batches per pair and solver, median kept (default 5; quick 3)\n"
      "  --batch-ns T  target length of one batch in ns (default 2000; quick 500)\n"
      "  --seed S      family seed (default 20240601)\n"
      "  --pairs-csv   also write report_pairs.csv (one row per pair and solver)\n"
      "  --no-plot     do not run bench/plot_report.py\n"
      "Then Disk(r) against every other FCL primitive through fcl::distance, next to FCL's\n"
      "Sphere(r) and GJK on Cylinder(r, 0) on the same poses (shapes.csv, shapes.png):\n"
      "  --shape-pairs N  random cases per shape (default 2000; quick 20)\n"
      "  --no-shapes      skip that section\n"
      "  --shapes-only    run only that section\n"
      "Then the penetration depth of intersecting disk pairs (fcl::distance with\n"
      "enable_signed_distance: Disk pairs, fcl_disk::diskPenetration, FCL's EPA on\n"
      "Cylinder(r, h) pairs), and of a Disk against each shape with an exact PD next to\n"
      "FCL's EPA on Cylinder(r, 1e-6 r) in its place (penetration.csv):\n"
      "  --penetration-pairs N  intersecting pairs per family and per shape (default 2000;\n"
      "                         quick 20)\n"
      "  --no-penetration       skip that section\n"
      "  --penetration-only     run only that section (with --shapes-only: those two)\n",
      argv0, FCL_DISK_DEFAULT_OUT);
}

bool parseOptions(int argc, char** argv, Options* options) {
  bool pairs_set = false, reps_set = false, batch_set = false;
  bool shape_pairs_set = false, penetration_pairs_set = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&](const char* name) -> const char* {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "fcl_disk_report: %s needs a value\n", name);
        std::exit(2);
      }
      return argv[++i];
    };
    if (arg == "--quick") {
      options->quick = true;
    } else if (arg == "--out") {
      options->out_dir = value("--out");
    } else if (arg == "--pairs") {
      options->pairs_per_family = std::atoi(value("--pairs"));
      pairs_set = true;
    } else if (arg == "--reps") {
      options->reps = std::atoi(value("--reps"));
      reps_set = true;
    } else if (arg == "--batch-ns") {
      options->batch_ns = std::atof(value("--batch-ns"));
      batch_set = true;
    } else if (arg == "--seed") {
      options->seed = std::strtoull(value("--seed"), nullptr, 10);
    } else if (arg == "--pairs-csv") {
      options->pairs_csv = true;
    } else if (arg == "--no-plot") {
      options->plot = false;
    } else if (arg == "--shape-pairs") {
      options->shape_pairs = std::atoi(value("--shape-pairs"));
      shape_pairs_set = true;
    } else if (arg == "--no-shapes") {
      options->shapes = false;
    } else if (arg == "--shapes-only") {
      options->shapes_only = true;
    } else if (arg == "--penetration-pairs") {
      options->penetration_pairs = std::atoi(value("--penetration-pairs"));
      penetration_pairs_set = true;
    } else if (arg == "--no-penetration") {
      options->penetration = false;
    } else if (arg == "--penetration-only") {
      options->penetration_only = true;
    } else if (arg == "--help" || arg == "-h") {
      printUsage(argv[0]);
      std::exit(0);
    } else {
      std::fprintf(stderr, "fcl_disk_report: unknown argument '%s'\n", arg.c_str());
      printUsage(argv[0]);
      return false;
    }
  }
  if (options->quick) {
    if (!pairs_set) options->pairs_per_family = 20;
    if (!reps_set) options->reps = 3;
    if (!batch_set) options->batch_ns = 500;
    if (!shape_pairs_set) options->shape_pairs = 20;
    if (!penetration_pairs_set) options->penetration_pairs = 20;
  }
  if (options->shape_pairs < 1 || options->penetration_pairs < 1) {
    std::fprintf(stderr,
                 "fcl_disk_report: --shape-pairs and --penetration-pairs must be positive\n");
    return false;
  }
  if (options->pairs_per_family < 1 || options->reps < 1 || !(options->batch_ns > 0)) {
    std::fprintf(stderr, "fcl_disk_report: --pairs, --reps and --batch-ns must be positive\n");
    return false;
  }
  return true;
}

// ---------------------------------------------------------------------------
// Solvers.

const double kHeights[] = {1e-2, 1e-4, 1e-6};

/// The objects a disk pair is queried through: the two Disks, and FCL's
/// Cylinder(r, h) at the same poses for every height (FCL's Cylinder is centred
/// on its frame, axis +z: the disk thickened by h/2 on each side).
struct PairObjects {
  std::unique_ptr<fcl::CollisionObjectd> disk1, disk2;
  std::unique_ptr<fcl::CollisionObjectf> disk1f, disk2f;  ///< the same in float
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> cyl1, cyl2;  ///< one per height

  void build(double r1, const fcl::Transform3d& X_W1, double r2, const fcl::Transform3d& X_W2) {
    disk1 = std::make_unique<fcl::CollisionObjectd>(std::make_shared<fcl_disk::Diskd>(r1), X_W1);
    disk2 = std::make_unique<fcl::CollisionObjectd>(std::make_shared<fcl_disk::Diskd>(r2), X_W2);
    disk1f = std::make_unique<fcl::CollisionObjectf>(
        std::make_shared<fcl_disk::Diskf>(float(r1)), X_W1.cast<float>());
    disk2f = std::make_unique<fcl::CollisionObjectf>(
        std::make_shared<fcl_disk::Diskf>(float(r2)), X_W2.cast<float>());
    for (double h : kHeights) {
      cyl1.push_back(std::make_unique<fcl::CollisionObjectd>(
          std::make_shared<fcl::Cylinderd>(r1, h), X_W1));
      cyl2.push_back(std::make_unique<fcl::CollisionObjectd>(
          std::make_shared<fcl::Cylinderd>(r2, h), X_W2));
    }
  }
};

/// One prepared pair: the case, its reference, and the objects every solver needs.
struct PreparedPair : PairObjects {
  Case c;
  fam::Family family;
  double reference = 0;  ///< reference distance (rounded to double)
  double scale = 1;      ///< r1 + r2 + |c1 - c2|
};
constexpr int kNumHeights = 3;

enum class Kind { disk_fcl, disk_fcl_float, disk_direct, gjk, fcl_entry };

struct Solver {
  std::string name;
  std::string path;  ///< "fcl::distance" or "direct"
  Kind kind;
  fcl_disk::DiskDistanceMethod method = fcl_disk::DiskDistanceMethod::exact;
  fcl::GJKSolverType gjk = fcl::GST_LIBCCD;
  int height_index = 0;
};

std::vector<Solver> makeSolvers() {
  using M = fcl_disk::DiskDistanceMethod;
  std::vector<Solver> solvers;
  solvers.push_back({"exact", "fcl::distance", Kind::disk_fcl, M::exact});
  solvers.push_back({"almohamad_selim", "fcl::distance", Kind::disk_fcl, M::almohamad_selim});
  solvers.push_back({"exact_float", "fcl::distance, float", Kind::disk_fcl_float, M::exact});
  const char* heights[] = {"1e-2", "1e-4", "1e-6"};
  for (auto gjk : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
    for (int h = 0; h < kNumHeights; ++h) {
      Solver s{std::string(gjk == fcl::GST_LIBCCD ? "gjk_libccd_h" : "gjk_indep_h") + heights[h],
               "fcl::distance", Kind::gjk};
      s.gjk = gjk;
      s.height_index = h;
      solvers.push_back(s);
    }
  }
  solvers.push_back({"exact_direct", "direct", Kind::disk_direct, M::exact});
  solvers.push_back(
      {"almohamad_selim_direct", "direct", Kind::disk_direct, M::almohamad_selim});
  solvers.push_back({"fcl_entry_only", "fcl::distance, result at 0", Kind::fcl_entry});
  return solvers;
}

/// One query of `solver` on `pair`; returns the distance (overlap -> 0).
/// Selecting the disk method (registerDiskFunctions) is done by the caller,
/// outside the timed region.
inline double query(const Solver& solver, const PreparedPair& pair) {
  switch (solver.kind) {
    case Kind::disk_fcl: {
      fcl::DistanceRequestd request;
      fcl::DistanceResultd result;
      fcl::distance(pair.disk1.get(), pair.disk2.get(), request, result);
      return result.min_distance;
    }
    case Kind::disk_fcl_float: {
      fcl::DistanceRequestf request;
      fcl::DistanceResultf result;
      fcl::distance(pair.disk1f.get(), pair.disk2f.get(), request, result);
      return result.min_distance;
    }
    case Kind::disk_direct: {
      const Case& c = pair.c;
      return solver.method == fcl_disk::DiskDistanceMethod::exact
                 ? fcl_disk::exactDiskDistance(c.r1, c.X_W1, c.r2, c.X_W2).distance
                 : fcl_disk::almohamadSelimDiskDistance(c.r1, c.X_W1, c.r2, c.X_W2).distance;
    }
    case Kind::fcl_entry: {
      fcl::DistanceRequestd request;
      fcl::DistanceResultd result;
      result.min_distance = 0;
      fcl::distance(pair.disk1.get(), pair.disk2.get(), request, result);
      return result.min_distance;
    }
    case Kind::gjk: {
      fcl::DistanceRequestd request;
      request.gjk_solver_type = solver.gjk;
      fcl::DistanceResultd result;
      fcl::distance(pair.cyl1[solver.height_index].get(), pair.cyl2[solver.height_index].get(),
                    request, result);
      return result.min_distance;
    }
  }
  return std::nan("");
}

/// Keeps a value alive without a store the compiler could drop.
template <typename T>
inline void keep(const T& value) {
  asm volatile("" : : "g"(&value) : "memory");
}

double nsBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::nano>(b - a).count();
}

/// Median cost of an empty steady_clock interval (subtracted from each batch).
double measureClockOverhead() {
  std::vector<double> samples(20001);
  for (auto& s : samples) {
    const auto a = Clock::now();
    const auto b = Clock::now();
    s = nsBetween(a, b);
  }
  std::nth_element(samples.begin(), samples.begin() + samples.size() / 2, samples.end());
  return samples[samples.size() / 2];
}

struct Measurement {
  double ns = 0;        ///< median ns per query over the batches
  double distance = 0;  ///< the solver's answer (overlap -> 0)
  double error = 0;     ///< |distance - reference| / scale
};

Measurement measure(const Solver& solver, const PreparedPair& pair, const Options& options,
                    double clock_ns) {
  if (solver.kind == Kind::disk_fcl || solver.kind == Kind::disk_fcl_float) {
    fcl_disk::registerDiskFunctions(solver.method);
  }
  Measurement m;
  // First call: the answer (and warms the caches).
  double d = query(solver, pair);
  if (d < 0) d = 0;  // FCL's unsigned distance reports overlap as -1
  m.distance = d;
  m.error = solver.kind == Kind::fcl_entry ? std::nan("")  // answers nothing
                                           : std::fabs(d - pair.reference) / pair.scale;
  // Calibrate the batch length on a second call.
  const auto t0 = Clock::now();
  double sink = query(solver, pair);
  const auto t1 = Clock::now();
  const double single = std::max(1.0, nsBetween(t0, t1) - clock_ns);
  const int k = static_cast<int>(std::clamp(options.batch_ns / single, 1.0, 4096.0));
  std::vector<double> batches(options.reps);
  for (int r = 0; r < options.reps; ++r) {
    const auto b0 = Clock::now();
    for (int i = 0; i < k; ++i) {
      sink += query(solver, pair);
      keep(sink);
    }
    const auto b1 = Clock::now();
    batches[r] = std::max(0.0, nsBetween(b0, b1) - clock_ns) / k;
  }
  keep(sink);
  std::sort(batches.begin(), batches.end());
  const int n = options.reps;
  m.ns = n % 2 ? batches[n / 2] : (batches[n / 2 - 1] + batches[n / 2]) / 2;
  return m;
}

/// What is kept of a pair once its objects are freed.
struct PairRecord {
  fam::Family family;
  std::string name;
  double reference = 0;
  double scale = 1;
  std::vector<Measurement> results;  ///< one per solver
};

PreparedPair preparePair(Case c, fam::Family family) {
  PreparedPair p;
  const ref::ReferenceResult r = ref::referenceDiskDistance(c.r1, c.X_W1, c.r2, c.X_W2);
  p.reference = static_cast<double>(r.distance);
  p.scale = fam::sceneScale(c);
  p.family = family;
  p.build(c.r1, c.X_W1, c.r2, c.X_W2);
  p.c = std::move(c);
  return p;
}

// ---------------------------------------------------------------------------
// Statistics and output.

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

/// Nearest-rank percentile (q in (0, 1]).
double percentile(std::vector<double> v, double q) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  std::size_t rank = static_cast<std::size_t>(std::ceil(q * v.size()));
  rank = std::clamp<std::size_t>(rank, 1, v.size());
  return v[rank - 1];
}

struct Summary {
  std::string solver, path, family;
  std::size_t pairs = 0;
  double median_ns = 0, p99_ns = 0, median_err = 0, max_err = 0;
  std::string worst_case;  ///< name of the pair with the max error
};

Summary summarise(const std::string& solver, const std::string& path, const std::string& family,
                  const std::vector<double>& ns, const std::vector<double>& err,
                  const std::string& worst_case) {
  Summary s;
  s.solver = solver;
  s.path = path;
  s.family = family;
  s.pairs = ns.size();
  s.worst_case = worst_case;
  s.median_ns = median(ns);
  s.p99_ns = percentile(ns, 0.99);
  s.median_err = median(err);
  s.max_err = err.empty() ? std::nan("") : *std::max_element(err.begin(), err.end());
  return s;
}

std::string formatNs(double ns) {
  char buffer[32];
  if (ns >= 1e4) {
    std::snprintf(buffer, sizeof buffer, "%.0f", ns);
  } else if (ns >= 100) {
    std::snprintf(buffer, sizeof buffer, "%.0f", ns);
  } else {
    std::snprintf(buffer, sizeof buffer, "%.1f", ns);
  }
  return buffer;
}

std::string formatErr(double e) {
  char buffer[32];
  if (e == 0) return "0";
  if (std::isnan(e)) return "-";  // fcl_entry_only: times, answers nothing
  std::snprintf(buffer, sizeof buffer, "%.1e", e);
  return buffer;
}

/// Progress on stderr: a rewritten line on a terminal, a line per family otherwise.
class Progress {
 public:
  explicit Progress(std::size_t total)
      : total_(total), start_(Clock::now()), tty_(isatty(2)) {}

  void update(std::size_t done, const std::string& detail, bool force = false) {
    const auto now = Clock::now();
    if (!force && nsBetween(last_, now) < 2e8) return;  // 5 updates a second
    last_ = now;
    const double elapsed = nsBetween(start_, now) * 1e-9;
    const double fraction = total_ ? double(done) / double(total_) : 1.0;
    const double eta = fraction > 0 ? elapsed * (1 - fraction) / fraction : 0;
    char line[256];
    std::snprintf(line, sizeof line, "fcl_disk_report: %5.1f%%  %-42s elapsed %4.0f s, eta %4.0f s",
                  100 * fraction, detail.c_str(), elapsed, eta);
    if (tty_) {
      std::fprintf(stderr, "\r%s\033[K", line);
    } else if (detail != last_detail_ || force) {
      std::fprintf(stderr, "%s\n", line);
    }
    last_detail_ = detail;
    std::fflush(stderr);
  }

  void finish() {
    update(total_, "done", true);
    if (tty_) std::fprintf(stderr, "\n");
  }

 private:
  std::size_t total_;
  Clock::time_point start_, last_{};
  bool tty_;
  std::string last_detail_;
};

std::string machineName() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(colon + 2);
    }
  }
  return "unknown CPU";
}

/// A Python with matplotlib: $FCL_DISK_PYTHON, python3 on PATH, /usr/bin/python3
/// (Debian's python3-matplotlib lives there; a pyenv python3 may not have it).
std::string findPython() {
  std::vector<std::string> candidates;
  if (const char* env = std::getenv("FCL_DISK_PYTHON")) candidates.push_back(env);
  candidates.push_back("python3");
  candidates.push_back("/usr/bin/python3");
  for (const auto& python : candidates) {
    const std::string probe = "'" + python + "' -c 'import matplotlib' >/dev/null 2>&1";
    if (std::system(probe.c_str()) == 0) return python;
  }
  return "";
}


/// Draws `png_path` from `csv_path` with the plotting `script`; false if
/// plotting failed (a missing matplotlib only skips the plot, saying how).
bool runPlot(const char* script, const std::string& csv_path, const std::string& png_path) {
  const std::string python = findPython();
  const std::string command = "'" + (python.empty() ? std::string("python3") : python) + "' '" +
                              script + "' '" + csv_path + "' '" + png_path + "'";
  if (python.empty()) {
    std::fprintf(stderr,
                 "fcl_disk_report: no python3 with matplotlib found (apt-get install "
                 "python3-matplotlib, or set FCL_DISK_PYTHON); plot skipped. Run:\n  %s\n",
                 command.c_str());
  } else if (std::system(command.c_str()) != 0) {
    std::fprintf(stderr, "fcl_disk_report: plotting failed: %s\n", command.c_str());
    return false;
  } else {
    std::printf("wrote %s\n", png_path.c_str());
  }
  return true;
}

// ---------------------------------------------------------------------------
// Disk against other shapes.

namespace dsc = fcl_disk_shape_cases;

// The independent long-double disk-vs-shape reference of the tests
// (test/disk_shape_oracle.h: nested golden-section search over the disk of a
// point-to-shape distance written there, sharing no code with the solver).
constexpr bool kHaveShapeReference = true;
constexpr std::size_t kReferencedPairs = 200;
double shapeReference(const dsc::CaseSpec& spec) {
  namespace oracle = fcl_disk_test::oracle;
  using Real = oracle::Real;
  oracle::Shape shape;
  const auto& in = spec.shape;
  const oracle::V3 dims = in.dims.cast<Real>();
  switch (in.kind) {
    case dsc::ShapeKind::sphere: shape.kind = oracle::Kind::sphere; shape.dims = dims; break;
    case dsc::ShapeKind::box: shape.kind = oracle::Kind::box; shape.dims = dims / 2; break;
    case dsc::ShapeKind::capsule:
      shape.kind = oracle::Kind::capsule;
      shape.dims = oracle::V3(dims.x(), dims.y() / 2, 0);
      break;
    case dsc::ShapeKind::cylinder:
      shape.kind = oracle::Kind::cylinder;
      shape.dims = oracle::V3(dims.x(), dims.y() / 2, 0);
      break;
    case dsc::ShapeKind::cone:
      shape.kind = oracle::Kind::cone;
      shape.dims = oracle::V3(dims.x(), dims.y() / 2, 0);
      break;
    case dsc::ShapeKind::ellipsoid: shape.kind = oracle::Kind::ellipsoid; shape.dims = dims; break;
    case dsc::ShapeKind::convex8:
    case dsc::ShapeKind::convex40: {
      shape.kind = oracle::Kind::convex;
      for (const auto& v : in.vertices) shape.vertices.push_back(v.cast<Real>());
      std::size_t at = 0;
      for (int f = 0; f < in.num_faces; ++f) {
        const int count = in.faces[at];
        shape.faces.emplace_back(in.faces.begin() + at + 1, in.faces.begin() + at + 1 + count);
        at += count + 1;
      }
      break;
    }
    case dsc::ShapeKind::halfspace:
    case dsc::ShapeKind::plane:
      shape.kind = in.kind == dsc::ShapeKind::halfspace ? oracle::Kind::halfspace : oracle::Kind::plane;
      shape.n = in.normal.normalized().cast<Real>();
      shape.d = Real(in.offset) / Real(in.normal.norm());
      break;
    case dsc::ShapeKind::triangle:
      shape.kind = oracle::Kind::triangle;
      for (const auto& v : in.vertices) shape.vertices.push_back(v.cast<Real>());
      break;
  }
  const oracle::Disk disk{spec.X_WD.translation().cast<Real>(),
                          spec.X_WD.linear().col(0).cast<Real>(),
                          spec.X_WD.linear().col(1).cast<Real>(), Real(spec.disk_radius)};
  oracle::Pose X;
  X.R = spec.X_WS.linear().cast<Real>();
  X.t = spec.X_WS.translation().cast<Real>();
  return double(oracle::referenceDistance(disk, shape, X));
}

/// kDiskFloat: Disk<float> against the shape in float, the case's dimensions
/// and poses rounded to float.
enum ShapeSolver {
  kDisk,
  kDiskFloat,
  kSphereLibccd,
  kSphereIndep,
  kGjkLibccd,
  kGjkIndep,
  kNumShapeSolvers
};

const char* shapeSolverName(int s) {
  static const char* const names[] = {"disk", "disk_float", "sphere_libccd", "sphere_indep",
                                      "gjk_libccd", "gjk_indep"};
  return names[s];
}

/// Whether the solver answers the disk's question (and so has an error).
bool answersDisk(int s) {
  return s == kDisk || s == kDiskFloat || s == kGjkLibccd || s == kGjkIndep;
}

struct ShapePair {
  dsc::CaseSpec spec;
  double reference = std::nan("");  ///< d_ref (rounded to double); NaN without reference
  std::unique_ptr<fcl::CollisionObjectd> disk, sphere, flat_cylinder, shape;
  std::unique_ptr<fcl::CollisionObjectf> disk_float, shape_float;
};

ShapePair prepareShapePair(dsc::CaseSpec spec) {
  ShapePair p;
  const fcl::Transform3d X_WD = dsc::toS<double>(spec.X_WD);
  const double r = spec.disk_radius;
  p.disk = std::make_unique<fcl::CollisionObjectd>(std::make_shared<fcl_disk::Diskd>(r), X_WD);
  p.sphere = std::make_unique<fcl::CollisionObjectd>(std::make_shared<fcl::Sphered>(r), X_WD);
  p.flat_cylinder =
      std::make_unique<fcl::CollisionObjectd>(std::make_shared<fcl::Cylinderd>(r, 0.0), X_WD);
  p.shape = std::make_unique<fcl::CollisionObjectd>(dsc::makeShape<double>(spec.shape),
                                                    dsc::toS<double>(spec.X_WS));
  p.disk_float = std::make_unique<fcl::CollisionObjectf>(
      std::make_shared<fcl_disk::Diskf>(float(r)), dsc::toS<float>(spec.X_WD));
  p.shape_float = std::make_unique<fcl::CollisionObjectf>(dsc::makeShape<float>(spec.shape),
                                                          dsc::toS<float>(spec.X_WS));
  p.spec = std::move(spec);
  return p;
}

/// One fcl::distance of `solver` on `pair`, a fresh request and result; FCL's raw value.
inline double shapeQuery(int solver, const ShapePair& pair) {
  if (solver == kDiskFloat) {
    fcl::DistanceRequestf request;
    fcl::DistanceResultf result;
    fcl::distance(pair.disk_float.get(), pair.shape_float.get(), request, result);
    return double(result.min_distance);
  }
  fcl::DistanceRequestd request;
  request.gjk_solver_type =
      solver == kSphereIndep || solver == kGjkIndep ? fcl::GST_INDEP : fcl::GST_LIBCCD;
  fcl::DistanceResultd result;
  const fcl::CollisionObjectd* first = solver == kDisk ? pair.disk.get()
                                       : solver == kSphereLibccd || solver == kSphereIndep
                                           ? pair.sphere.get()
                                           : pair.flat_cylinder.get();
  fcl::distance(first, pair.shape.get(), request, result);
  return result.min_distance;
}

/// The timing of measure() above for any query: the first call gives the answer,
/// the second sizes the batch, then `reps` batches; median ns per query.
template <typename Query>
std::pair<double, double> timeRepeated(const Query& query, const Options& options,
                                       double clock_ns) {
  const double answer = query();
  const auto t0 = Clock::now();
  double sink = query();
  const auto t1 = Clock::now();
  const double single = std::max(1.0, nsBetween(t0, t1) - clock_ns);
  const int k = static_cast<int>(std::clamp(options.batch_ns / single, 1.0, 4096.0));
  std::vector<double> batches(options.reps);
  for (int r = 0; r < options.reps; ++r) {
    const auto b0 = Clock::now();
    for (int i = 0; i < k; ++i) {
      sink += query();
      keep(sink);
    }
    const auto b1 = Clock::now();
    batches[r] = std::max(0.0, nsBetween(b0, b1) - clock_ns) / k;
  }
  keep(sink);
  return {answer, median(batches)};
}

struct ShapeSolverSummary {
  bool measured = false;
  std::string skip_reason;  ///< why not measured
  double median_ns = std::nan(""), p99_ns = std::nan("");
  double median_err = std::nan(""), max_err = std::nan("");  ///< NaN: no error computed
  std::string worst_case;
};

struct ShapeSummary {
  std::string shape;
  std::size_t pairs = 0;
  double overlap_fraction = std::nan("");  ///< d_ref == 0; NaN without reference
  std::array<ShapeSolverSummary, kNumShapeSolvers> solvers;
};

/// The faster of two measured summaries (index), or -1 if neither was measured.
int faster(const ShapeSummary& s, int a, int b) {
  const bool ma = s.solvers[a].measured, mb = s.solvers[b].measured;
  if (ma && mb) return s.solvers[a].median_ns <= s.solvers[b].median_ns ? a : b;
  return ma ? a : mb ? b : -1;
}

std::string csvNumber(double v) {
  if (std::isnan(v)) return "";
  std::ostringstream out;
  out.precision(6);
  out << v;
  return out.str();
}

std::string csvQuoted(const std::string& text) {
  std::string quoted = "\"";
  for (char ch : text) quoted += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return quoted + "\"";
}

int runShapeSection(const Options& options, double clock_ns) {
  const auto& kinds = dsc::allShapeKinds();
  const std::size_t n = static_cast<std::size_t>(options.shape_pairs);
  std::vector<ShapeSummary> summaries;
  const auto run_start = Clock::now();
  {
    Progress progress(kinds.size() * n);
    std::size_t done = 0;
    for (std::size_t t = 0; t < kinds.size(); ++t) {
      const dsc::ShapeKind kind = kinds[t];
      char label[64];
      std::snprintf(label, sizeof label, "shape %zu/%zu %s", t + 1, kinds.size(),
                    dsc::shapeName(kind));
      progress.update(done, std::string(label) + ": cases", true);
      std::vector<ShapePair> pairs;
      pairs.reserve(n);
      for (dsc::CaseSpec& spec : dsc::makeCases(kind, n, options.seed))
        pairs.push_back(prepareShapePair(std::move(spec)));
      // The reference costs ~1e4 point-to-shape distances in long double: the
      // errors come from the first kReferencedPairs cases of each shape.
      if (kHaveShapeReference) {
        progress.update(done, std::string(label) + ": reference", true);
        for (std::size_t i = 0; i < pairs.size() && i < kReferencedPairs; ++i)
          pairs[i].reference = shapeReference(pairs[i].spec);
      }

      ShapeSummary summary;
      summary.shape = dsc::shapeName(kind);
      summary.pairs = pairs.size();
      // Each query kind once over all cases, in a child: skip what does not finish.
      progress.update(done, std::string(label) + ": probe", true);
      for (int s = 0; s < kNumShapeSolvers; ++s) {
        const auto outcome = dsc::probeInChild(
            [&]() -> int {
              for (const ShapePair& p : pairs)
                if (shapeQuery(s, p) == std::numeric_limits<double>::max()) return 10;
              return 0;
            },
            [](int code) {
              return code == 10 ? std::string("no answer (distance left at max)")
                                : "exit code " + std::to_string(code);
            });
        summary.solvers[s].measured = outcome.ok;
        summary.solvers[s].skip_reason = outcome.reason;
      }

      std::array<std::vector<double>, kNumShapeSolvers> ns, err;
      std::array<double, kNumShapeSolvers> worst_err;
      worst_err.fill(-1);
      std::size_t overlaps = 0;
      for (std::size_t i = 0; i < pairs.size(); ++i) {
        const ShapePair& p = pairs[i];
        if (p.reference == 0) ++overlaps;
        for (int j = 0; j < kNumShapeSolvers; ++j) {
          const int s = static_cast<int>((i + j) % kNumShapeSolvers);  // rotate the order
          if (!summary.solvers[s].measured) continue;
          const auto [answer, time_ns] =
              timeRepeated([&]() { return shapeQuery(s, p); }, options, clock_ns);
          ns[s].push_back(time_ns);
          if (!answersDisk(s) || std::isnan(p.reference)) continue;
          const double d = answer < 0 ? 0.0 : answer;  // FCL's overlap value -1 read as 0
          const double e = std::isnan(d) ? std::numeric_limits<double>::infinity()
                                         : std::fabs(d - p.reference) / p.spec.scale;
          err[s].push_back(e);
          if (e > worst_err[s]) {
            worst_err[s] = e;
            summary.solvers[s].worst_case = p.spec.name;
          }
        }
        progress.update(done + i + 1, std::string(label) + ": timing");
      }
      if (kHaveShapeReference) {
        summary.overlap_fraction =
            double(overlaps) / double(std::min<std::size_t>(pairs.size(), kReferencedPairs));
      }
      for (int s = 0; s < kNumShapeSolvers; ++s) {
        ShapeSolverSummary& out = summary.solvers[s];
        if (!out.measured) continue;
        out.median_ns = median(ns[s]);
        out.p99_ns = percentile(ns[s], 0.99);
        if (!err[s].empty()) {
          out.median_err = median(err[s]);
          out.max_err = *std::max_element(err[s].begin(), err[s].end());
        }
      }
      summaries.push_back(std::move(summary));
      done += pairs.size();
    }
    progress.finish();
  }
  const double run_seconds = nsBetween(run_start, Clock::now()) * 1e-9;

  // Table.
  auto ns = [](const ShapeSolverSummary& s) { return s.measured ? formatNs(s.median_ns) : "-"; };
  auto err = [](const ShapeSolverSummary& s) { return formatErr(s.max_err); };
  std::printf("\n## Disk against other shapes (fcl::distance; %d cases per shape, seed %llu)\n\n",
              options.shape_pairs, static_cast<unsigned long long>(options.seed));
  std::printf("machine: %s, %ld logical CPUs; time = median of %d batches of the same query "
              "(batch ~%.0f ns, clock cost %.1f ns subtracted), then median and p99 over the "
              "cases; the section took %.0f s.\n",
              machineName().c_str(), sysconf(_SC_NPROCESSORS_ONLN), options.reps,
              options.batch_ns, clock_ns, run_seconds);
  std::printf("Cases: disk r = 0.5 and a shape of size ~0.5 (bench/disk_shape_cases.h), centres "
              "uniform in the unit ball, uniform rotations. disk = Disk(r) against X (float "
              "disk: the same on Disk<float>, shape and poses rounded to float); sphere = "
              "FCL's Sphere(r) against X at the disk's pose; GJK = FCL on Cylinder(r, 0) at the "
              "disk's pose. Sphere and GJK columns: the faster of libccd / indep (named).\n");
  if (kHaveShapeReference) {
    std::printf("error (over the first %zu cases of each shape; overlap: their share at distance "
              "0) = |d - d_ref| / (r + R_S + |c_D - c_S|), d_ref: long-double reference "
                "(test/disk_shape_oracle.h); FCL's overlap value -1 read as 0.\n\n",
                kReferencedPairs);
  } else {
    std::printf("error: not computed (no disk-vs-shape reference in this build: "
                "test/disk_shape_oracle.h).\n\n");
  }
  std::printf("| shape | cases | overlap | disk median ns | disk p99 ns | sphere median ns | GJK "
              "flat cylinder median ns | disk / sphere | GJK / disk | disk max err | GJK max "
              "err | float disk median / p99 ns | float / double, median / p99 | float disk "
              "max err |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const ShapeSummary& s : summaries) {
    const ShapeSolverSummary& disk = s.solvers[kDisk];
    const ShapeSolverSummary& disk_float = s.solvers[kDiskFloat];
    const int sphere = faster(s, kSphereLibccd, kSphereIndep);
    const int gjk = faster(s, kGjkLibccd, kGjkIndep);
    auto named = [&](int index) {
      if (index < 0) return std::string("-");
      return ns(s.solvers[index]) +
             (index == kSphereLibccd || index == kGjkLibccd ? " (libccd)" : " (indep)");
    };
    char overlap[32] = "-";
    if (!std::isnan(s.overlap_fraction))
      std::snprintf(overlap, sizeof overlap, "%.0f%%", 100 * s.overlap_fraction);
    char disk_over_sphere[32] = "-", gjk_over_disk[32] = "-";
    if (disk.measured && sphere >= 0)
      std::snprintf(disk_over_sphere, sizeof disk_over_sphere, "%.2fx",
                    disk.median_ns / s.solvers[sphere].median_ns);
    if (disk.measured && gjk >= 0)
      std::snprintf(gjk_over_disk, sizeof gjk_over_disk, "%.1fx",
                    s.solvers[gjk].median_ns / disk.median_ns);
    std::string float_times = "-";
    char float_over_double[48] = "-";
    if (disk_float.measured) {
      float_times = formatNs(disk_float.median_ns) + " / " + formatNs(disk_float.p99_ns);
      if (disk.measured)
        std::snprintf(float_over_double, sizeof float_over_double, "%.2fx / %.2fx",
                      disk_float.median_ns / disk.median_ns, disk_float.p99_ns / disk.p99_ns);
    }
    std::printf("| %s | %zu | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n",
                s.shape.c_str(), s.pairs, overlap, ns(disk).c_str(),
                disk.measured ? formatNs(disk.p99_ns).c_str() : "-",
                named(sphere).c_str(), named(gjk).c_str(), disk_over_sphere,
                gjk_over_disk, err(disk).c_str(),
                gjk >= 0 ? err(s.solvers[gjk]).c_str() : "-", float_times.c_str(),
                float_over_double, err(disk_float).c_str());
  }
  bool any_skipped = false;
  for (const ShapeSummary& s : summaries)
    for (int k = 0; k < kNumShapeSolvers; ++k)
      if (!s.solvers[k].measured) {
        if (!any_skipped) std::printf("\nNot measured (probed in a child process first):\n");
        any_skipped = true;
        std::printf("- %s / %s: %s\n", s.shape.c_str(), shapeSolverName(k),
                    s.solvers[k].skip_reason.c_str());
      }

  // CSV: one row per shape, every query kind's figures.
  std::error_code ec;
  std::filesystem::create_directories(options.out_dir, ec);
  const std::string csv_path = options.out_dir + "/shapes.csv";
  const std::string png_path = options.out_dir + "/shapes.png";
  {
    std::ofstream csv(csv_path);
    if (!csv) {
      std::fprintf(stderr, "fcl_disk_report: cannot write %s\n", csv_path.c_str());
      return 1;
    }
    csv << "shape,cases,overlap_fraction";
    for (int k = 0; k < kNumShapeSolvers; ++k) {
      const std::string p = shapeSolverName(k);
      csv << ',' << p << "_median_ns," << p << "_p99_ns";
      if (answersDisk(k))
        csv << ',' << p << "_median_rel_err," << p << "_max_rel_err," << p << "_worst_case";
    }
    csv << ",sphere_solver,gjk_solver,disk_over_sphere,gjk_over_disk,not_measured\n";
    for (const ShapeSummary& s : summaries) {
      csv << s.shape << ',' << s.pairs << ',' << csvNumber(s.overlap_fraction);
      std::string not_measured;
      for (int k = 0; k < kNumShapeSolvers; ++k) {
        const ShapeSolverSummary& m = s.solvers[k];
        csv << ',' << csvNumber(m.median_ns) << ',' << csvNumber(m.p99_ns);
        if (answersDisk(k))
          csv << ',' << csvNumber(m.median_err) << ',' << csvNumber(m.max_err) << ','
              << m.worst_case;
        if (!m.measured)
          not_measured += std::string(not_measured.empty() ? "" : "; ") + shapeSolverName(k) +
                          ": " + m.skip_reason;
      }
      const ShapeSolverSummary& disk = s.solvers[kDisk];
      const int sphere = faster(s, kSphereLibccd, kSphereIndep);
      const int gjk = faster(s, kGjkLibccd, kGjkIndep);
      csv << ',' << (sphere >= 0 ? shapeSolverName(sphere) : "") << ','
          << (gjk >= 0 ? shapeSolverName(gjk) : "") << ','
          << csvNumber(disk.measured && sphere >= 0
                           ? disk.median_ns / s.solvers[sphere].median_ns
                           : std::nan(""))
          << ','
          << csvNumber(disk.measured && gjk >= 0 ? s.solvers[gjk].median_ns / disk.median_ns
                                                 : std::nan(""))
          << ',' << csvQuoted(not_measured) << '\n';
    }
  }
  std::printf("\nwrote %s\n", csv_path.c_str());

  if (options.plot && !runPlot(FCL_DISK_PLOT_SHAPES_SCRIPT, csv_path, png_path)) return 1;
  return 0;
}

// ---------------------------------------------------------------------------
// Penetration depth of intersecting disk pairs.

namespace pen = fcl_disk_penetration_cases;

// The independent long-double penetration reference of the tests
// (test/reference_penetration.h: a dense Fibonacci-sphere scan of F(w) plus
// local refinement and the four kinks, no fcl_disk code).
double penReference(const pen::PenCase& c) {
  return static_cast<double>(
      fcl_disk_penetration_reference::referencePenetration(c.r1, c.X_W1, c.r2, c.X_W2).pd);
}
/// The reference costs ~1 ms per pair (20000 directions, then refinement in long
/// double): errors against it come from the first kPenReferencedPairs pairs of
/// each family (~1.6 s for 8 families); every pair is also compared with
/// fcl_disk's own answer.
constexpr std::size_t kPenReferencedPairs = 200;
/// diskPenetration's documented bound (include/fcl_disk/disk_penetration.h),
/// relative to the scene r1 + r2 + |c1 - c2|.
constexpr double kPenBound = 1e-12;
/// An answer above this (relative to the scene) on an intersecting pair counts
/// as "reported apart": the disks' own rounding (coplanar pairs: PD = 0 to
/// ~1e-17) stays far below it, a solver that misses the overlap does not.
constexpr double kReportedApart = kPenBound;

enum class PenKind { disk_fcl, disk_direct, epa_libccd, indep };

struct PenQuery {
  std::string name;
  std::string path;
  PenKind kind;
  int height_index = 0;  ///< into kHeights, for the thin-cylinder kinds
  bool isFcl() const { return kind != PenKind::disk_direct; }
  bool isCylinder() const { return kind == PenKind::epa_libccd || kind == PenKind::indep; }
};

std::vector<PenQuery> makePenQueries() {
  std::vector<PenQuery> queries;
  queries.push_back({"disk", "fcl::distance", PenKind::disk_fcl});
  queries.push_back({"disk_direct", "direct", PenKind::disk_direct});
  const char* heights[] = {"1e-2", "1e-4", "1e-6"};
  for (PenKind kind : {PenKind::epa_libccd, PenKind::indep}) {
    for (int h = 0; h < kNumHeights; ++h) {
      queries.push_back({std::string(kind == PenKind::epa_libccd ? "epa_libccd_h" : "indep_h") +
                             heights[h],
                         "fcl::distance", kind, h});
    }
  }
  return queries;
}

/// One prepared pair: the case, its PD (reference and fcl_disk's), the objects.
struct PenPair : PairObjects {
  pen::PenCase c;
  double reference = std::nan("");  ///< PD_ref (rounded to double); NaN unreferenced
  double fcl_disk_pd = 0;           ///< -diskPenetration().signed_distance
};

PenPair preparePenPair(pen::PenCase c) {
  PenPair p;
  p.fcl_disk_pd = -fcl_disk::diskPenetration(c.r1, c.X_W1, c.r2, c.X_W2).signed_distance;
  // A cylinder's PD exceeds the disk's by up to h.
  p.build(c.r1, c.X_W1, c.r2, c.X_W2);
  p.c = std::move(c);
  return p;
}

/// One signed-distance query; returns the signed distance (-PD on overlap) or,
/// for FCL, whatever min_distance it left (max() when nothing answered).
inline double penQuery(const PenQuery& q, const PenPair& p) {
  if (q.kind == PenKind::disk_direct)
    return fcl_disk::diskPenetration(p.c.r1, p.c.X_W1, p.c.r2, p.c.X_W2).signed_distance;
  fcl::DistanceRequestd request;
  request.enable_signed_distance = true;
  request.gjk_solver_type = q.kind == PenKind::indep ? fcl::GST_INDEP : fcl::GST_LIBCCD;
  fcl::DistanceResultd result;
  if (q.isCylinder()) {
    fcl::distance(p.cyl1[q.height_index].get(), p.cyl2[q.height_index].get(), request, result);
  } else {
    fcl::distance(p.disk1.get(), p.disk2.get(), request, result);
  }
  return result.min_distance;
}

struct PenSummary {
  std::string query, path, family;
  bool measured = true;
  std::string skip_reason;
  std::size_t pairs = 0, referenced = 0;
  double median_ns = std::nan(""), p99_ns = std::nan("");
  double median_err = std::nan(""), max_err = std::nan("");  ///< vs reference (subset)
  std::string worst_case;                                    ///< pair of max_err
  double max_err_vs_disk = std::nan("");  ///< vs diskPenetration, every pair
  std::size_t reported_apart = 0;  ///< answers > kReportedApart * scale
  std::size_t threw = 0;           ///< pairs where the query threw (not timed)
  std::string threw_example;       ///< the first of them and its message
  double slowest_ns = std::nan("");
  std::string slowest_case;
};

/// Per-pair raw figures of one query over one family (or pooled).
struct PenSamples {
  std::vector<double> ns, err, err_vs_disk;
  std::string worst_case;
  double worst_err = -1;
  std::size_t reported_apart = 0, threw = 0;
  std::string threw_example;
  std::string slowest_case;
  double slowest_ns = -1;

  void append(const PenSamples& other) {
    ns.insert(ns.end(), other.ns.begin(), other.ns.end());
    err.insert(err.end(), other.err.begin(), other.err.end());
    err_vs_disk.insert(err_vs_disk.end(), other.err_vs_disk.begin(), other.err_vs_disk.end());
    if (other.worst_err > worst_err) {
      worst_err = other.worst_err;
      worst_case = other.worst_case;
    }
    reported_apart += other.reported_apart;
    threw += other.threw;
    if (threw_example.empty()) threw_example = other.threw_example;
    if (other.slowest_ns > slowest_ns) {
      slowest_ns = other.slowest_ns;
      slowest_case = other.slowest_case;
    }
  }
};

PenSummary summarisePen(const PenQuery& q, const std::string& family, const PenSamples& s) {
  PenSummary out;
  out.query = q.name;
  out.path = q.path;
  out.family = family;
  out.pairs = s.ns.size();
  out.referenced = s.err.size();
  out.median_ns = median(s.ns);
  out.p99_ns = percentile(s.ns, 0.99);
  out.median_err = median(s.err);
  out.max_err = s.err.empty() ? std::nan("") : *std::max_element(s.err.begin(), s.err.end());
  out.worst_case = s.worst_case;
  out.max_err_vs_disk = s.err_vs_disk.empty()
                            ? std::nan("")
                            : *std::max_element(s.err_vs_disk.begin(), s.err_vs_disk.end());
  out.reported_apart = s.reported_apart;
  out.threw = s.threw;
  out.threw_example = s.threw_example;
  out.slowest_ns = s.slowest_ns >= 0 ? s.slowest_ns : std::nan("");
  out.slowest_case = s.slowest_case;
  return out;
}

/// The informative line of an exception FCL threw: for libccd's EPA, the
/// "Original error message" without its source path (the rest of what() is the
/// two shapes and poses, over a dozen lines).
std::string exceptionSummary(const std::exception& e) {
  std::string text = e.what();
  const std::string marker = "Original error message: ";
  const auto at = text.find(marker);
  if (at != std::string::npos) {
    text = text.substr(at + marker.size());
    const auto after_path = text.find("): ");  // "file:(line): function(): message"
    if (after_path != std::string::npos) text = text.substr(after_path + 3);
  }
  text = text.substr(0, text.find('\n'));
  const bool logic_error = dynamic_cast<const std::logic_error*>(&e) != nullptr;
  return std::string(logic_error ? "std::logic_error: " : "exception: ") + text;
}

/// dsc::probeInChild with the child's stderr (file descriptor 2: failed
/// assertions and abort messages of libfcl, which std::cerr capture misses)
/// sent to a temporary file instead of the terminal; a failure's reason gets
/// the failed assertion from it.
dsc::ProbeOutcome probeQuietly(const std::function<int()>& body,
                               const std::function<std::string(int)>& describe) {
  char path[] = "/tmp/fcl_disk_report_probe_XXXXXX";
  const int fd = mkstemp(path);
  dsc::ProbeOutcome outcome = dsc::probeInChild(
      [&]() {
        if (fd >= 0) dup2(fd, 2);
        return body();
      },
      describe);
  if (fd < 0) return outcome;
  std::ifstream file(path);
  std::string line, assertion;
  while (std::getline(file, line)) {
    const auto at = line.find("Assertion `");
    if (at == std::string::npos) continue;
    // "prog: file:line: function: Assertion `x' failed.": keep file:line and the test.
    const auto file_start = line.find(": ");
    const auto file_end = line.find(": ", file_start + 2);
    std::string where = file_start != std::string::npos && file_end != std::string::npos
                            ? line.substr(file_start + 2, file_end - file_start - 2)
                            : std::string();
    const auto slash = where.rfind('/');
    if (slash != std::string::npos) where = where.substr(slash + 1);
    assertion = where + ": " + line.substr(at);
    break;
  }
  close(fd);
  unlink(path);
  if (!outcome.ok && !assertion.empty()) outcome.reason += ": " + assertion;
  return outcome;
}

/// FCL's distance with a fresh result: min_distance starts at max().
constexpr double kUnanswered = std::numeric_limits<double>::max();

/// Runs `query` once on every pair in a child (probeQuietly): "" when each
/// call gave an answer, else why not. Exceptions are left to the timing,
/// which counts them per pair.
template <typename Pair, typename Query>
std::string probePenQuery(const std::vector<Pair>& pairs, const Query& query) {
  const auto outcome = probeQuietly(
      [&]() -> int {
        for (const Pair& p : pairs) {
          double d = 0;
          try {
            d = query(p);
          } catch (const std::exception&) {
            continue;
          }
          if (d == kUnanswered) return 10;
          if (std::isnan(d)) return 11;
        }
        return 0;
      },
      [](int code) {
        return code == 10   ? std::string("no answer (distance left at max)")
               : code == 11 ? std::string("NaN distance")
                            : "exit code " + std::to_string(code);
      });
  return outcome.ok ? std::string() : outcome.reason;
}

/// Times one signed-distance `query` on one intersecting pair (timeRepeated)
/// and adds it to `s`: its time, whether it reported the pair apart, and its
/// error against PD_ref (NaN: the pair is not referenced) and fcl_disk's PD.
/// A template, so that the timed calls stay direct.
template <typename Query>
void samplePenQuery(const Query& query, const std::string& name, double scale,
                    double reference, double fcl_disk_pd, const Options& options,
                    double clock_ns, PenSamples* s) {
  // libccd's EPA throws std::logic_error on some pairs ("the origin is
  // outside of the polytope"): a deterministic failure of that pair,
  // counted and named rather than losing the other pairs.
  double answer = 0, time_ns = 0;
  try {
    std::tie(answer, time_ns) = timeRepeated(query, options, clock_ns);
  } catch (const std::exception& e) {
    if (s->threw++ == 0) s->threw_example = name + ": " + exceptionSummary(e);
    return;
  }
  s->ns.push_back(time_ns);
  if (time_ns > s->slowest_ns) {
    s->slowest_ns = time_ns;
    s->slowest_case = name;
  }
  if (answer > kReportedApart * scale) ++s->reported_apart;
  const double pd = -answer;
  auto relative = [&](double pd_ref) {
    const double e = std::fabs(pd - pd_ref) / scale;
    return std::isnan(e) ? std::numeric_limits<double>::infinity() : e;
  };
  s->err_vs_disk.push_back(relative(fcl_disk_pd));
  if (std::isnan(reference)) return;
  const double e = relative(reference);
  s->err.push_back(e);
  if (e > s->worst_err) {
    s->worst_err = e;
    s->worst_case = name;
  }
}

// ---------------------------------------------------------------------------
// Penetration depth of a Disk against the shapes with an exact PD.

namespace spc = fcl_disk_shape_penetration_cases;

// The independent long-double reference of test_disk_shape_penetration
// (test/reference_shape_penetration.h: closed forms for the sphere, halfspace
// and plane, a search over the sphere of directions for the others; no
// fcl_disk code). The search costs ~1 ms a pair, as the disk pairs' reference
// does: errors against it come from the first kPenReferencedPairs pairs of
// each shape.
template <typename Shape>
double shapePenReference(const spc::ShapePenCase<Shape>& c) {
  return static_cast<double>(
      fcl_disk_shape_penetration_reference::referenceDepth(c.r, c.X_WD, c.shape, c.X_WS));
}

/// FCL's own signed distance of the disk: its Cylinder(r, h) with h this
/// fraction of r in the disk's place.
constexpr double kFlatCylinderRelativeHeight = 1e-6;

/// The shape table's queries, disk first (the denominator of the ratio).
std::vector<PenQuery> makeShapePenQueries() {
  return {{"disk", "fcl::distance", PenKind::disk_fcl},
          {"epa_libccd_h1e-6r", "fcl::distance", PenKind::epa_libccd}};
}
constexpr std::size_t kShapeDiskQuery = 0, kShapeFclQuery = 1;

template <typename Shape>
struct ShapePenPair {
  explicit ShapePenPair(spc::ShapePenCase<Shape> pair) : c(std::move(pair)) {}
  spc::ShapePenCase<Shape> c;
  double reference = std::nan("");  ///< PD_ref (rounded to double); NaN unreferenced
  double fcl_disk_pd = 0;           ///< -signedDiskShapeDistance().signed_distance
  std::unique_ptr<fcl::CollisionObjectd> disk, flat_cylinder, shape;
};

template <typename Shape>
ShapePenPair<Shape> prepareShapePenPair(spc::ShapePenCase<Shape> c) {
  ShapePenPair<Shape> p(std::move(c));
  const double r = p.c.r;
  p.fcl_disk_pd =
      -fcl_disk::signedDiskShapeDistance(r, p.c.X_WD, p.c.shape, p.c.X_WS).signed_distance;
  p.disk = std::make_unique<fcl::CollisionObjectd>(std::make_shared<fcl_disk::Diskd>(r), p.c.X_WD);
  p.flat_cylinder = std::make_unique<fcl::CollisionObjectd>(
      std::make_shared<fcl::Cylinderd>(r, kFlatCylinderRelativeHeight * r), p.c.X_WD);
  p.shape = std::make_unique<fcl::CollisionObjectd>(std::make_shared<Shape>(p.c.shape), p.c.X_WS);
  return p;
}

/// One signed-distance query, the disk (or its flat cylinder) as object 1;
/// FCL's raw min_distance.
template <typename Shape>
inline double shapePenQuery(const PenQuery& q, const ShapePenPair<Shape>& p) {
  fcl::DistanceRequestd request;
  request.enable_signed_distance = true;
  request.enable_nearest_points = true;
  request.gjk_solver_type = fcl::GST_LIBCCD;
  fcl::DistanceResultd result;
  fcl::distance(q.kind == PenKind::disk_fcl ? p.disk.get() : p.flat_cylinder.get(), p.shape.get(),
                request, result);
  return result.min_distance;
}

/// One shape's raw figures: per query, the samples or why it was skipped; and
/// the referenced pairs where the disk misses the 1e-12 bound.
struct ShapePenResult {
  std::string shape;
  std::size_t generated = 0;
  std::vector<PenSamples> samples;
  std::vector<std::string> skipped;
  std::vector<std::string> above_bound;
};

template <typename Shape>
ShapePenResult measureShapePenetration(const std::vector<PenQuery>& queries,
                                       const Options& options, double clock_ns,
                                       const std::string& label, Progress* progress,
                                       std::size_t done) {
  const std::size_t n = static_cast<std::size_t>(options.penetration_pairs);
  ShapePenResult result;
  result.shape = spc::shapePenName(static_cast<const Shape*>(nullptr));
  result.samples.resize(queries.size());
  result.skipped.resize(queries.size());
  progress->update(done, label + ": pairs", true);
  std::vector<ShapePenPair<Shape>> pairs;
  pairs.reserve(n);
  for (spc::ShapePenCase<Shape>& c : spc::makeShapePenCases<Shape>(n, options.seed))
    pairs.push_back(prepareShapePenPair(std::move(c)));
  result.generated = pairs.size();

  progress->update(done, label + ": reference", true);
  for (std::size_t i = 0; i < pairs.size() && i < kPenReferencedPairs; ++i) {
    ShapePenPair<Shape>& p = pairs[i];
    p.reference = shapePenReference(p.c);
    if (!(std::fabs(p.fcl_disk_pd - p.reference) <= kPenBound * p.c.scale)) {
      char line[256];
      std::snprintf(line, sizeof line, "%s: fcl_disk %.17g, reference %.17g, error %.1e",
                    p.c.name.c_str(), p.fcl_disk_pd, p.reference,
                    std::fabs(p.fcl_disk_pd - p.reference) / p.c.scale);
      result.above_bound.push_back(line);
    }
  }

  // Both queries once over the pairs, in a child: FCL 0.7 crashes on the flat
  // cylinder against Halfspace and Plane under libccd, and has no TriangleP pair.
  progress->update(done, label + ": probe", true);
  for (std::size_t q = 0; q < queries.size(); ++q) {
    result.skipped[q] = probePenQuery(
        pairs, [&](const ShapePenPair<Shape>& p) { return shapePenQuery(queries[q], p); });
  }

  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const ShapePenPair<Shape>& p = pairs[i];
    for (std::size_t j = 0; j < queries.size(); ++j) {
      const std::size_t q = (i + j) % queries.size();  // rotate the order
      if (!result.skipped[q].empty()) continue;
      samplePenQuery([&]() { return shapePenQuery(queries[q], p); }, p.c.name, p.c.scale,
                     p.reference, p.fcl_disk_pd, options, clock_ns, &result.samples[q]);
    }
    progress->update(done + i + 1, label + ": timing");
  }
  return result;
}

/// The second table of the penetration section: a Disk against each shape with
/// an exact PD, next to FCL's EPA on the flat cylinder. Prints the table and its
/// notes; returns the CSV rows (per shape: disk, then FCL; family "shape:<name>").
std::vector<PenSummary> runShapePenetration(const Options& options, double clock_ns) {
  const std::vector<PenQuery> queries = makeShapePenQueries();
  const std::size_t n = static_cast<std::size_t>(options.penetration_pairs);
  std::size_t num_shapes = 0;
  spc::forEachExactPenetrationShape([&](auto*) { ++num_shapes; });

  std::vector<ShapePenResult> results;
  const auto run_start = Clock::now();
  {
    Progress progress(num_shapes * n);
    std::size_t done = 0;
    spc::forEachExactPenetrationShape([&](auto* tag) {
      using Shape = std::remove_pointer_t<decltype(tag)>;
      const std::string label = "penetration shape " + std::to_string(results.size() + 1) +
                                "/" + std::to_string(num_shapes) + " " +
                                spc::shapePenName(static_cast<const Shape*>(nullptr));
      results.push_back(
          measureShapePenetration<Shape>(queries, options, clock_ns, label, &progress, done));
      done += n;
    });
    progress.finish();
  }
  const double run_seconds = nsBetween(run_start, Clock::now()) * 1e-9;

  std::vector<PenSummary> rows;
  for (const ShapePenResult& r : results) {
    for (std::size_t q = 0; q < queries.size(); ++q) {
      PenSummary s = summarisePen(queries[q], "shape:" + r.shape, r.samples[q]);
      s.measured = r.skipped[q].empty();
      s.skip_reason = r.skipped[q];
      rows.push_back(s);
    }
  }

  std::printf("\n## Penetration depth of a Disk against the shapes with an exact PD "
              "(fcl::distance, enable_signed_distance; %d intersecting pairs per shape, seed "
              "%llu)\n\n",
              options.penetration_pairs, static_cast<unsigned long long>(options.seed));
  std::printf("Timed as the disk pairs above; the table took %.0f s. Pairs: "
              "bench/disk_shape_penetration_cases.h (test_disk_shape_penetration's draws: disk "
              "r uniform in 0.2..1, shapes of size ~0.5, both centres uniform in the unit ball, "
              "uniform rotations), kept when fcl_disk::diskShapeIntersect says they intersect. "
              "disk = Disk(r) against the shape (fcl_disk's hook); FCL = FCL's "
              "Cylinder(r, 1e-6 r) in the disk's place (libccd's EPA; its PD exceeds the "
              "disk's by up to 1e-6 r, so its error is at least that much from the model "
              "alone); both GST_LIBCCD with enable_nearest_points. FCL / disk = ratio of the "
              "median times.\n",
              run_seconds);
  std::printf("err = |(-min_distance) - PD_ref| / (r + 1 + 2) over the first %zu pairs of "
              "each shape (ref pairs), PD_ref: long-double reference "
              "(test/reference_shape_penetration.h).\n\n",
              kPenReferencedPairs);
  std::printf("| shape | pairs | ref pairs | disk median ns | disk p99 ns | disk max err | FCL "
              "median ns | FCL p99 ns | FCL max err | FCL / disk |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  auto cells = [](const PenSummary& s) {
    if (!s.measured) return std::string("skipped | |");
    return formatNs(s.median_ns) + " | " + formatNs(s.p99_ns) + " | " + formatErr(s.max_err);
  };
  for (std::size_t k = 0; k < results.size(); ++k) {
    const PenSummary& disk = rows[k * queries.size() + kShapeDiskQuery];
    const PenSummary& fcl = rows[k * queries.size() + kShapeFclQuery];
    char ratio[32] = "-";
    if (disk.measured && fcl.measured)
      std::snprintf(ratio, sizeof ratio, "%.1fx", fcl.median_ns / disk.median_ns);
    std::string pairs = std::to_string(results[k].generated);
    if (fcl.threw > 0) pairs += " (FCL threw on " + std::to_string(fcl.threw) + ")";
    const std::size_t referenced = std::min(results[k].generated, kPenReferencedPairs);
    std::printf("| %s | %s | %zu | %s | %s | %s |\n", results[k].shape.c_str(), pairs.c_str(),
                referenced, cells(disk).c_str(), cells(fcl).c_str(), ratio);
  }

  bool any_note = false;
  auto note = [&](const std::string& text) {
    if (!any_note) std::printf("\nNotes:\n");
    any_note = true;
    std::printf("- %s\n", text.c_str());
  };
  for (std::size_t k = 0; k < results.size(); ++k) {
    const ShapePenResult& r = results[k];
    if (r.generated < n)
      note(r.shape + ": only " + std::to_string(r.generated) + " of " + std::to_string(n) +
           " pairs generated");
    for (std::size_t q = 0; q < queries.size(); ++q) {
      const PenSummary& s = rows[k * queries.size() + q];
      if (!s.measured)
        note(r.shape + " / " + s.query + ": not measured (probed in a child first): " +
             s.skip_reason);
      if (s.threw > 0)
        note(r.shape + " / " + s.query + ": threw on " + std::to_string(s.threw) + " of " +
             std::to_string(s.pairs + s.threw) + " pairs (not timed, no error), first " +
             s.threw_example);
      if (s.reported_apart > 0)
        note(r.shape + " / " + s.query + ": " + std::to_string(s.reported_apart) + " of " +
             std::to_string(s.pairs) +
             " intersecting pairs reported apart (min_distance > 1e-12 of the scene)");
    }
    for (std::size_t i = 0; i < r.above_bound.size() && i < 12; ++i)
      note("fcl_disk above the 1e-12 bound: " + r.above_bound[i]);
  }
  return rows;
}

int runPenetrationSection(const Options& options, double clock_ns) {
  const auto& families = pen::allPenFamilies();
  const std::vector<PenQuery> queries = makePenQueries();
  const std::size_t num_queries = queries.size();
  const std::size_t n = static_cast<std::size_t>(options.penetration_pairs);

  std::vector<std::vector<PenSamples>> samples(families.size(),
                                               std::vector<PenSamples>(num_queries));
  std::vector<std::vector<std::string>> skipped(families.size(),
                                                std::vector<std::string>(num_queries));
  std::vector<std::size_t> generated(families.size(), 0);
  // The reference against the constructions with a closed-form PD (coplanar,
  // coaxial, nearly touching/face): a check of the yardstick itself.
  double worst_known_gap = -1;
  std::string worst_known_case;
  // fcl_disk against its bound, on the referenced pairs.
  std::vector<std::string> above_bound;
  std::size_t referenced_total = 0;

  const auto run_start = Clock::now();
  {
    Progress progress(families.size() * n);
    std::size_t done = 0;
    for (std::size_t f = 0; f < families.size(); ++f) {
      const pen::PenFamily family = families[f];
      const std::string label = "penetration " + std::to_string(f + 1) + "/" +
                                std::to_string(families.size()) + " " +
                                pen::penFamilyName(family);
      progress.update(done, std::string(label) + ": pairs", true);
      std::vector<PenPair> pairs;
      pairs.reserve(n);
      for (pen::PenCase& c : pen::makePenFamily(family, n, options.seed))
        pairs.push_back(preparePenPair(std::move(c)));
      generated[f] = pairs.size();

      progress.update(done, std::string(label) + ": reference", true);
      const std::size_t referenced = std::min(pairs.size(), kPenReferencedPairs);
      for (std::size_t i = 0; i < referenced; ++i) {
        PenPair& p = pairs[i];
        p.reference = penReference(p.c);
        ++referenced_total;
        if (!std::isnan(p.c.known_pd)) {
          const double gap = std::fabs(p.reference - p.c.known_pd) / p.c.scale;
          if (gap > worst_known_gap) {
            worst_known_gap = gap;
            worst_known_case = p.c.name;
          }
        }
        if (!(std::fabs(p.fcl_disk_pd - p.reference) <= kPenBound * p.c.scale)) {
          char line[256];
          std::snprintf(line, sizeof line, "%s: fcl_disk %.17g, reference %.17g, error %.1e",
                        p.c.name.c_str(), p.fcl_disk_pd, p.reference,
                        std::fabs(p.fcl_disk_pd - p.reference) / p.c.scale);
          above_bound.push_back(line);
        }
      }

      // Every FCL query kind once over the family, in a child: skip what does
      // not finish (FCL's EPA on degenerate simplices may crash or loop).
      progress.update(done, std::string(label) + ": probe", true);
      for (std::size_t q = 0; q < num_queries; ++q) {
        if (queries[q].isFcl()) {
          skipped[f][q] =
              probePenQuery(pairs, [&](const PenPair& p) { return penQuery(queries[q], p); });
        }
      }

      for (std::size_t i = 0; i < pairs.size(); ++i) {
        const PenPair& p = pairs[i];
        for (std::size_t j = 0; j < num_queries; ++j) {
          const std::size_t q = (i + j) % num_queries;  // rotate the order
          if (!skipped[f][q].empty()) continue;
          samplePenQuery([&]() { return penQuery(queries[q], p); }, p.c.name, p.c.scale,
                         p.reference, p.fcl_disk_pd, options, clock_ns, &samples[f][q]);
        }
        progress.update(done + i + 1, std::string(label) + ": timing");
      }
      done += n;
    }
    progress.finish();
  }
  const double run_seconds = nsBetween(run_start, Clock::now()) * 1e-9;

  // Summaries: per (family, query), and pooled per query over the families
  // where it was measured.
  std::vector<std::string> family_names;
  for (pen::PenFamily family : families) family_names.push_back(pen::penFamilyName(family));
  std::vector<std::vector<PenSummary>> table(families.size() + 1);  // last: "all"
  for (std::size_t q = 0; q < num_queries; ++q) {
    PenSamples pooled;
    std::size_t measured_families = 0;
    for (std::size_t f = 0; f < families.size(); ++f) {
      PenSummary s = summarisePen(queries[q], family_names[f], samples[f][q]);
      if (!skipped[f][q].empty()) {
        s.measured = false;
        s.skip_reason = skipped[f][q];
      } else {
        pooled.append(samples[f][q]);
        ++measured_families;
      }
      table[f].push_back(s);
    }
    PenSummary all = summarisePen(queries[q], "all", pooled);
    all.measured = measured_families > 0;
    if (measured_families < families.size())
      all.skip_reason = "pooled over " + std::to_string(measured_families) + " of " +
                        std::to_string(families.size()) + " families";
    table[families.size()].push_back(all);
  }
  family_names.push_back("all");
  // Indices of the disk queries in each row set (makePenQueries' order); the
  // first is the denominator of the ratios.
  const std::size_t kDiskQuery = 0, kDiskDirectQuery = 1;
  // A query skipped in every family for one and the same reason is named once
  // (row "all", one note) instead of once per family.
  std::vector<std::string> skipped_everywhere(num_queries);
  for (std::size_t q = 0; q < num_queries; ++q) {
    bool same = !skipped[0][q].empty();
    for (std::size_t f = 1; f < families.size() && same; ++f)
      same = skipped[f][q] == skipped[0][q];
    if (same) skipped_everywhere[q] = skipped[0][q];
  }

  // Table.
  std::printf("\n## Penetration depth of intersecting disks (fcl::distance, "
              "enable_signed_distance; %d pairs per family, seed %llu)\n\n",
              options.penetration_pairs, static_cast<unsigned long long>(options.seed));
  std::printf("machine: %s, %ld logical CPUs; time = median of %d batches of the same query "
              "(batch ~%.0f ns, clock cost %.1f ns subtracted), then median and p99 over the "
              "pairs; the section took %.0f s.\n",
              machineName().c_str(), sysconf(_SC_NPROCESSORS_ONLN), options.reps,
              options.batch_ns, clock_ns, run_seconds);
  std::printf("Pairs: bench/disk_penetration_cases.h, kept when fcl_disk::intersectDisks says "
              "they intersect. disk = Disk pair (GST_LIBCCD, fcl_disk's hook); disk_direct = "
              "fcl_disk::diskPenetration; epa_libccd_h<h> = FCL on Cylinder(r, h) pairs, "
              "GST_LIBCCD (libccd's EPA); indep_h<h> = the same, GST_INDEP (FCL's entry calls "
              "collide() and reports minus the contact depth). A cylinder's PD exceeds the "
              "disk's by up to h, so its error is at least that much from the model alone.\n");
  std::printf("err = |(-min_distance) - PD_ref| / (r1 + r2 + |c1 - c2|) over the first %zu "
              "pairs of each family (ref pairs), PD_ref: long-double reference "
              "(test/reference_penetration.h); err vs fcl_disk = the same against "
              "diskPenetration, over every pair.\n\n",
              kPenReferencedPairs);
  const char* err_label = "err";
  std::printf("| family | query | pairs | ref pairs | median ns | p99 ns | median %s | max %s | "
              "max err vs fcl_disk | / disk |\n",
              err_label, err_label);
  std::printf("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  const std::size_t all_row = families.size();
  for (std::size_t f = 0; f < table.size(); ++f) {
    const PenSummary& disk = table[f][kDiskQuery];
    for (std::size_t q = 0; q < num_queries; ++q) {
      const PenSummary& s = table[f][q];
      if (!s.measured) {
        if (f == all_row || skipped_everywhere[q].empty())
          std::printf("| %s | %s | - | - | %s | | | | | |\n", s.family.c_str(),
                      s.query.c_str(), f == all_row ? "skipped in every family" : "skipped");
        continue;
      }
      char ratio[32] = "-";
      if (disk.measured && s.query != disk.query)
        std::snprintf(ratio, sizeof ratio, "%.1fx", s.median_ns / disk.median_ns);
      std::string pairs = std::to_string(s.pairs);
      if (s.threw > 0) pairs += " (" + std::to_string(s.threw) + " threw)";
      std::printf("| %s | %s | %s | %zu | %s | %s | %s | %s | %s | %s |\n", s.family.c_str(),
                  s.query.c_str(), pairs.c_str(), s.referenced, formatNs(s.median_ns).c_str(),
                  formatNs(s.p99_ns).c_str(), formatErr(s.median_err).c_str(),
                  formatErr(s.max_err).c_str(), formatErr(s.max_err_vs_disk).c_str(), ratio);
    }
  }

  // Headline: pooled medians, disk against the fastest EPA.
  const std::vector<PenSummary>& all = table[families.size()];
  auto fastest = [&](PenKind kind) -> const PenSummary* {
    const PenSummary* best = nullptr;
    for (std::size_t q = 0; q < num_queries; ++q)
      if (queries[q].kind == kind && all[q].measured &&
          (!best || all[q].median_ns < best->median_ns))
        best = &all[q];
    return best;
  };
  const PenSummary& disk_all = all[kDiskQuery];
  std::printf("\n## Headline (medians pooled over all pairs, one run)\n\n");
  if (const PenSummary* epa = fastest(PenKind::epa_libccd)) {
    std::printf("- disk %s ns vs fastest libccd EPA (%s) %s ns: EPA / disk = %.0fx; max err "
                "disk %s, %s %s\n",
                formatNs(disk_all.median_ns).c_str(), epa->query.c_str(),
                formatNs(epa->median_ns).c_str(), epa->median_ns / disk_all.median_ns,
                formatErr(disk_all.max_err).c_str(), epa->query.c_str(),
                formatErr(epa->max_err).c_str());
  } else {
    std::printf("- no libccd EPA query finished on any family\n");
  }
  if (const PenSummary* indep = fastest(PenKind::indep)) {
    std::printf("- fastest indep (%s) %s ns: indep / disk = %.0fx; max err %s\n",
                indep->query.c_str(), formatNs(indep->median_ns).c_str(),
                indep->median_ns / disk_all.median_ns, formatErr(indep->max_err).c_str());
  }
  std::printf("- hook overhead: disk %s ns vs disk_direct %s ns (the hook also runs the "
              "distance solver and intersectDisks before diskPenetration)\n",
              formatNs(disk_all.median_ns).c_str(), formatNs(all[kDiskDirectQuery].median_ns).c_str());
  std::printf("- fcl_disk vs reference on %zu pairs: %zu above the %.0e bound\n",
              referenced_total, above_bound.size(), kPenBound);
  for (std::size_t i = 0; i < above_bound.size() && i < 12; ++i)
    std::printf("  - %s\n", above_bound[i].c_str());
  if (worst_known_gap >= 0)
    std::printf("- reference vs closed-form PD of the construction (coplanar, coaxial, "
                "nearly_touching/face): max %s of the scene (%s)\n",
                formatErr(worst_known_gap).c_str(), worst_known_case.c_str());

  // Notes: skipped kinds, short families, exceptions, pairs reported apart.
  bool any_note = false;
  auto note = [&](const std::string& text) {
    if (!any_note) std::printf("\nNotes:\n");
    any_note = true;
    std::printf("- %s\n", text.c_str());
  };
  for (std::size_t q = 0; q < num_queries; ++q)
    if (!skipped_everywhere[q].empty())
      note(queries[q].name + ": not measured in any family (probed in a child first): " +
           skipped_everywhere[q]);
  for (std::size_t f = 0; f < families.size(); ++f) {
    if (generated[f] < n)
      note(family_names[f] + ": only " + std::to_string(generated[f]) + " of " +
           std::to_string(n) + " pairs generated");
    for (std::size_t q = 0; q < num_queries; ++q) {
      if (!skipped[f][q].empty() && skipped_everywhere[q].empty())
        note(family_names[f] + " / " + queries[q].name + ": not measured (probed in a child "
             "first): " + skipped[f][q]);
      const PenSummary& s = table[f][q];
      if (s.threw > 0)
        note(family_names[f] + " / " + queries[q].name + ": threw on " +
             std::to_string(s.threw) + " of " + std::to_string(s.pairs + s.threw) +
             " pairs (not timed, no error), first " + s.threw_example);
      if (s.reported_apart > 0)
        note(family_names[f] + " / " + queries[q].name + ": " +
             std::to_string(s.reported_apart) + " of " + std::to_string(s.pairs) +
             " intersecting pairs reported apart (min_distance > 1e-12 of the scene)");
    }
  }

  const std::vector<PenSummary> shape_rows = runShapePenetration(options, clock_ns);

  // CSV: one row per (query, family), "all" last per query; then per shape
  // (family "shape:<name>") the disk's row and FCL's.
  std::error_code ec;
  std::filesystem::create_directories(options.out_dir, ec);
  const std::string csv_path = options.out_dir + "/penetration.csv";
  {
    std::ofstream csv(csv_path);
    if (!csv) {
      std::fprintf(stderr, "fcl_disk_report: cannot write %s\n", csv_path.c_str());
      return 1;
    }
    csv << "query,path,family,pairs,referenced_pairs,median_ns,p99_ns,median_rel_err,"
           "max_rel_err,worst_case,max_rel_err_vs_fcl_disk,over_disk,reported_apart,threw,"
           "threw_first,slowest_ns,slowest_case,reference,not_measured\n";
    auto row = [&](const PenSummary& s, const PenSummary& disk, const char* reference) {
      csv << s.query << ',' << s.path << ',' << s.family << ',' << s.pairs << ','
          << s.referenced << ',' << csvNumber(s.median_ns) << ',' << csvNumber(s.p99_ns) << ','
          << csvNumber(s.median_err) << ',' << csvNumber(s.max_err) << ',' << s.worst_case
          << ',' << csvNumber(s.max_err_vs_disk) << ','
          << csvNumber(s.measured && disk.measured ? s.median_ns / disk.median_ns
                                                   : std::nan(""))
          << ',' << s.reported_apart << ',' << s.threw << ',' << csvQuoted(s.threw_example)
          << ',' << csvNumber(s.slowest_ns) << ',' << s.slowest_case << ',' << reference << ','
          << csvQuoted(s.skip_reason) << '\n';
    };
    for (std::size_t q = 0; q < num_queries; ++q)
      for (std::size_t f = 0; f < table.size(); ++f)
        row(table[f][q], table[f][kDiskQuery], "reference_penetration");
    const std::size_t per_shape = makeShapePenQueries().size();
    for (std::size_t i = 0; i < shape_rows.size(); ++i)
      row(shape_rows[i], shape_rows[i - i % per_shape + kShapeDiskQuery],
          "reference_shape_penetration");
  }
  std::printf("\nwrote %s\n", csv_path.c_str());
  return 0;
}
}  // namespace

int main(int argc, char** argv) {
  Options options;
  if (!parseOptions(argc, argv, &options)) return 2;

  // Installs the hook (and proves it reaches plain fcl::distance) before timing.
  fcl_disk::registerDiskFunctions(fcl_disk::DiskDistanceMethod::exact);
  const std::vector<Solver> solvers = makeSolvers();
  const std::size_t num_solvers = solvers.size();
  const auto& families = fam::allFamilies();
  const double clock_ns = measureClockOverhead();
  // --shapes-only / --penetration-only: exactly the sections named.
  if (options.shapes_only || options.penetration_only) {
    if (options.shapes_only) {
      const int status = runShapeSection(options, clock_ns);
      if (status != 0) return status;
    }
    return options.penetration_only ? runPenetrationSection(options, clock_ns) : 0;
  }

  // 1. Family by family: pairs, references, then every solver on every pair,
  //    interleaved; the FCL objects are freed before the next family.
  std::vector<PairRecord> records;
  records.reserve(families.size() * options.pairs_per_family);
  const auto run_start = Clock::now();
  {
    Progress progress(families.size() * options.pairs_per_family);
    std::size_t done = 0;
    for (std::size_t f = 0; f < families.size(); ++f) {
      const fam::Family family = families[f];
      char label[64];
      std::snprintf(label, sizeof label, "family %zu/%zu %s", f + 1, families.size(),
                    fam::familyName(family));
      std::vector<PreparedPair> pairs;
      pairs.reserve(options.pairs_per_family);
      for (Case& c : fam::makeFamily<double>(family, options.pairs_per_family, options.seed)) {
        pairs.push_back(preparePair(std::move(c), family));
        progress.update(done + pairs.size() / 4, std::string(label) + ": reference");
      }
      for (std::size_t i = 0; i < pairs.size(); ++i) {
        PairRecord record{family, pairs[i].c.name, pairs[i].reference, pairs[i].scale,
                          std::vector<Measurement>(num_solvers)};
        for (std::size_t j = 0; j < num_solvers; ++j) {
          const std::size_t s = (i + j) % num_solvers;  // rotate the order
          record.results[s] = measure(solvers[s], pairs[i], options, clock_ns);
        }
        records.push_back(std::move(record));
        progress.update(done + pairs.size() / 4 + (3 * (i + 1)) / 4,
                        std::string(label) + ": timing");
      }
      done += pairs.size();
    }
    progress.finish();
  }
  fcl_disk::registerDiskFunctions(fcl_disk::DiskDistanceMethod::exact);
  const double run_seconds = nsBetween(run_start, Clock::now()) * 1e-9;

  // 2. Summaries: per (solver, family), and per solver over all families.
  std::vector<Summary> summaries;
  for (std::size_t s = 0; s < num_solvers; ++s) {
    std::vector<double> all_ns, all_err;
    std::string all_worst;
    double all_worst_err = -1;
    for (fam::Family family : families) {
      std::vector<double> ns, err;
      std::string worst;
      double worst_err = -1;
      for (const PairRecord& r : records) {
        if (r.family != family) continue;
        ns.push_back(r.results[s].ns);
        if (solvers[s].kind == Kind::fcl_entry) continue;  // no answer, no error
        err.push_back(r.results[s].error);
        if (r.results[s].error > worst_err) {
          worst_err = r.results[s].error;
          worst = r.name;
        }
      }
      if (worst_err > all_worst_err) {
        all_worst_err = worst_err;
        all_worst = worst;
      }
      all_ns.insert(all_ns.end(), ns.begin(), ns.end());
      all_err.insert(all_err.end(), err.begin(), err.end());
      summaries.push_back(
          summarise(solvers[s].name, solvers[s].path, fam::familyName(family), ns, err, worst));
    }
    summaries.push_back(
        summarise(solvers[s].name, solvers[s].path, "all", all_ns, all_err, all_worst));
  }
  auto find = [&](const std::string& solver, const std::string& family) -> const Summary& {
    for (const Summary& s : summaries)
      if (s.solver == solver && s.family == family) return s;
    static Summary none;
    return none;
  };

  // 3. Table (markdown), grouped by family so solvers compare side by side.
  std::printf("# fcl_disk_report\n\n");
  std::printf("machine: %s, %ld logical CPUs; %zu pairs per family x %zu families, seed %llu;\n",
              machineName().c_str(), sysconf(_SC_NPROCESSORS_ONLN),
              static_cast<std::size_t>(options.pairs_per_family), families.size(),
              static_cast<unsigned long long>(options.seed));
  std::printf("time = median of %d batches of the same query (batch ~%.0f ns, clock cost "
              "%.1f ns subtracted); the run took %.0f s.\n",
              options.reps, options.batch_ns, clock_ns, run_seconds);
  std::printf("error = |d - d_ref| / (r1 + r2 + |c1 - c2|), d_ref: long-double "
              "reference; FCL's overlap value -1 read as 0.\n\n");
  std::printf("| family | solver | path | pairs | median ns | p99 ns | median err | max err |\n");
  std::printf("|---|---|---|---:|---:|---:|---:|---:|\n");
  std::vector<std::string> family_order{"all"};
  for (fam::Family f : families) family_order.push_back(fam::familyName(f));
  for (const std::string& family : family_order) {
    for (const Solver& solver : solvers) {
      const Summary& s = find(solver.name, family);
      std::printf("| %s | %s | %s | %zu | %s | %s | %s | %s |\n", family.c_str(),
                  solver.name.c_str(), solver.path.c_str(), s.pairs, formatNs(s.median_ns).c_str(),
                  formatNs(s.p99_ns).c_str(), formatErr(s.median_err).c_str(),
                  formatErr(s.max_err).c_str());
    }
  }

  // 4. Per family: the exact solver against the closed form and the fastest
  //    thin-cylinder GJK (h = 1e-6), ratios of medians and of p99s within this run.
  std::printf("\n## Per family: exact vs almohamad_selim, GJK h=1e-6 and exact in float (one "
              "run)\n\n");
  std::printf("| family | exact median ns | exact p99 ns | almohamad_selim median / p99 ns | "
              "exact / almohamad_selim, median | p99 | fastest GJK h=1e-6 median / p99 ns | "
              "GJK / exact, median | p99 | exact_float median / p99 ns | float / double, "
              "median | p99 |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const std::string& family : family_order) {
    const Summary& e = find("exact", family);
    const Summary& a = find("almohamad_selim", family);
    const Summary& g1 = find("gjk_libccd_h1e-6", family);
    const Summary& g2 = find("gjk_indep_h1e-6", family);
    const Summary& g = g1.median_ns <= g2.median_ns ? g1 : g2;
    const Summary& f = find("exact_float", family);
    std::printf("| %s | %s | %s | %s / %s | %.2fx | %.2fx | %s / %s (%s) | %.1fx | %.1fx | "
                "%s / %s | %.2fx | %.2fx |\n",
                family.c_str(), formatNs(e.median_ns).c_str(), formatNs(e.p99_ns).c_str(),
                formatNs(a.median_ns).c_str(), formatNs(a.p99_ns).c_str(),
                e.median_ns / a.median_ns, e.p99_ns / a.p99_ns, formatNs(g.median_ns).c_str(),
                formatNs(g.p99_ns).c_str(), g.solver == "gjk_libccd_h1e-6" ? "libccd" : "indep",
                g.median_ns / e.median_ns, g.p99_ns / e.p99_ns, formatNs(f.median_ns).c_str(),
                formatNs(f.p99_ns).c_str(), f.median_ns / e.median_ns, f.p99_ns / e.p99_ns);
  }

  // 5. Headline figures (ratios of medians over all pairs, this run).
  const Summary& exact = find("exact", "all");
  const Summary& as = find("almohamad_selim", "all");
  const Summary& exact_direct = find("exact_direct", "all");
  const Summary& as_direct = find("almohamad_selim_direct", "all");
  const Summary& ccd6 = find("gjk_libccd_h1e-6", "all");
  const Summary& indep6 = find("gjk_indep_h1e-6", "all");
  const Summary& fastest_gjk = ccd6.median_ns <= indep6.median_ns ? ccd6 : indep6;
  std::printf("\n## Headline figures (medians over all %zu pairs, one run)\n\n", records.size());
  std::printf("- exact / almohamad_selim median time: %.2fx (%s ns / %s ns; target <= 5x)\n",
              exact.median_ns / as.median_ns, formatNs(exact.median_ns).c_str(),
              formatNs(as.median_ns).c_str());
  std::printf("- fastest GJK thin cylinder h=1e-6 (%s) / exact median time: %.1fx (%s ns / %s "
              "ns; target >= 10x)\n",
              fastest_gjk.solver.c_str(), fastest_gjk.median_ns / exact.median_ns,
              formatNs(fastest_gjk.median_ns).c_str(), formatNs(exact.median_ns).c_str());
  std::printf("- hook overhead, exact: (fcl::distance - direct) / fcl::distance = %.1f%% "
              "(%s ns vs %s ns direct; target < 10%%)\n",
              100 * (exact.median_ns - exact_direct.median_ns) / exact.median_ns,
              formatNs(exact.median_ns).c_str(), formatNs(exact_direct.median_ns).c_str());
  std::printf("- hook overhead, almohamad_selim: %.1f%% (%s ns vs %s ns direct)\n",
              100 * (as.median_ns - as_direct.median_ns) / as.median_ns,
              formatNs(as.median_ns).c_str(), formatNs(as_direct.median_ns).c_str());
  const Summary& entry = find("fcl_entry_only", "all");
  std::printf("- the entry path alone (fcl_entry_only: fcl::distance on the disk pair with a "
              "result already at 0, the Disk test included, no solver): %s ns, %.1f%% of "
              "the exact query; the overhead above is %s ns\n",
              formatNs(entry.median_ns).c_str(), 100 * entry.median_ns / exact.median_ns,
              formatNs(exact.median_ns - exact_direct.median_ns).c_str());

  // 6. The exact solver against its promise, with the cases that break it.
  std::size_t exact_index = 0;
  while (solvers[exact_index].name != "exact") ++exact_index;
  std::vector<const PairRecord*> violations;
  for (const PairRecord& r : records)
    if (!(r.results[exact_index].error <= 1e-12)) violations.push_back(&r);
  std::printf("- exact max error: %s of the scene size (%s); pairs above the 1e-12 bound: "
              "%zu of %zu\n",
              formatErr(exact.max_err).c_str(), exact.worst_case.c_str(), violations.size(),
              records.size());
  for (std::size_t i = 0; i < violations.size() && i < 12; ++i) {
    const PairRecord& r = *violations[i];
    std::printf("  - %s (seed %llu): exact %.17g, reference %.17g, error %s\n", r.name.c_str(),
                static_cast<unsigned long long>(options.seed), r.results[exact_index].distance,
                r.reference, formatErr(r.results[exact_index].error).c_str());
  }
  if (violations.size() > 12) std::printf("  - ... (--pairs-csv lists them all)\n");

  // 7. CSV files.
  std::error_code ec;
  std::filesystem::create_directories(options.out_dir, ec);
  const std::string csv_path = options.out_dir + "/report.csv";
  const std::string pairs_path = options.out_dir + "/report_pairs.csv";
  const std::string png_path = options.out_dir + "/report.png";
  {
    std::ofstream csv(csv_path);
    if (!csv) {
      std::fprintf(stderr, "fcl_disk_report: cannot write %s\n", csv_path.c_str());
      return 1;
    }
    csv << "solver,path,family,pairs,median_ns,p99_ns,median_rel_err,max_rel_err,worst_case\n";
    csv.precision(6);
    for (const Summary& s : summaries) {
      if (s.solver == "fcl_entry_only") continue;  // no error to plot
      csv << s.solver << ',' << s.path << ',' << s.family << ',' << s.pairs << ','
          << s.median_ns << ',' << s.p99_ns << ',' << s.median_err << ',' << s.max_err << ','
          << s.worst_case << '\n';
    }
  }
  std::printf("\nwrote %s\n", csv_path.c_str());
  if (options.pairs_csv) {
    std::ofstream csv(pairs_path);
    csv << "family,case,solver,ns,distance,reference,scale,rel_err\n";
    for (const PairRecord& r : records) {
      for (std::size_t s = 0; s < num_solvers; ++s) {
        if (solvers[s].kind == Kind::fcl_entry) continue;
        const Measurement& m = r.results[s];
        csv << fam::familyName(r.family) << ',' << r.name << ',' << solvers[s].name << ','
            << std::setprecision(4) << m.ns << ',' << std::setprecision(17) << m.distance << ','
            << r.reference << ',' << r.scale << ',' << std::setprecision(4) << m.error << '\n';
      }
    }
    std::printf("wrote %s\n", pairs_path.c_str());
  }

  // 8. The plot.
  if (options.plot && !runPlot(FCL_DISK_PLOT_SCRIPT, csv_path, png_path)) return 1;
  if (options.shapes) {
    const int status = runShapeSection(options, clock_ns);
    if (status != 0) return status;
  }
  if (options.penetration) return runPenetrationSection(options, clock_ns);
  return 0;
}

// A fixed workload for instruction counts (docs/performance.md, "Instructions"):
// one disk-disk solver called on the first 2000 pairs of one family of
// test/disk_families.h (seed 20240601), ten passes (or PASSES), nothing else timed or
// printed but the sum of the distances (and, for the exact solver, after the
// workload, its mean iteration count on the pairs it answers rim to rim). Run it
// under callgrind and divide the solver's inclusive count by 2000 x passes
// (20000 by default):
//
//   valgrind --tool=callgrind --callgrind-out-file=cg.out ./build/bench/disk_pair_calls random exact
//   callgrind_annotate --inclusive=yes cg.out | grep -m1 'exactDiskDistance<double>'
//
// Instruction counts are not moved by the load of a shared machine, so they
// compare commits where wall-clock medians cannot. A pass count makes the run
// long enough to time two libraries against each other with farm-bench:
//
//   B="env LD_LIBRARY_PATH=OTHER ./build/bench/disk_pair_calls random exact 1000"
//   farm-bench -n 10 --vs "$B" -- ./build/bench/disk_pair_calls random exact 1000
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "disk_families.h"
#include "fcl_disk/fcl_disk.h"

namespace {
constexpr int kPairs = 2000;
constexpr int kDefaultPasses = 10;
constexpr std::uint64_t kSeed = 20240601;
}  // namespace

int main(int argc, char** argv) {
  using namespace fcl_disk_families;
  const bool known_solver = (argc == 3 || argc == 4) &&
                            (std::strcmp(argv[2], "exact") == 0 ||
                             std::strcmp(argv[2], "almohamad_selim") == 0);
  const int passes = argc == 4 ? std::atoi(argv[3]) : kDefaultPasses;
  const Family* family = nullptr;
  for (const Family& f : allFamilies()) {
    if (argc >= 3 && std::string(argv[1]) == familyName(f)) family = &f;
  }
  if (!known_solver || family == nullptr || passes < 1) {
    std::fprintf(stderr, "usage: %s FAMILY exact|almohamad_selim [PASSES]\nfamilies:", argv[0]);
    for (const Family f : allFamilies()) std::fprintf(stderr, " %s", familyName(f));
    std::fprintf(stderr, "\n");
    return 2;
  }
  const bool exact = std::strcmp(argv[2], "exact") == 0;
  const auto cases = makeFamily<double>(*family, kPairs, kSeed);
  double sum = 0.0;
  int rim_rim = 0, iterations = 0;  // the exact solver's, over the first pass
  for (int pass = 0; pass < passes; ++pass) {
    for (const auto& c : cases) {
      if (!exact) {
        sum += fcl_disk::almohamadSelimDiskDistance(c.r1, c.X_W1, c.r2, c.X_W2).distance;
        continue;
      }
      const auto result = fcl_disk::exactDiskDistance(c.r1, c.X_W1, c.r2, c.X_W2);
      sum += result.distance;
      if (pass == 0 && result.feature == fcl_disk::DiskPairFeature::rim_rim) {
        ++rim_rim;
        iterations += result.iterations;
      }
    }
  }
  std::printf("%d calls, sum of distances %.17g\n", kPairs * passes, sum);
  if (exact) {
    std::printf("%d rim-rim answers, %.2f iterations on average\n", rim_rim,
                rim_rim > 0 ? double(iterations) / rim_rim : 0.0);
  }
  return 0;
}

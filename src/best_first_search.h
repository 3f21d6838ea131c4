// Internal: the best-first search shared by the distance traversals of meshes
// (src/mesh_distance.h) and octrees (src/octree_distance.h).
// docs/meshes_and_octrees.md, "Distance traversal".
#pragma once

#include <algorithm>
#include <functional>
#include <optional>
#include <vector>

namespace fcl_disk {
namespace internal {

/// This thread's scratch queue for a search over Entry. Returned from a call
/// the traversal cannot see into: in a shared library every use of a
/// thread_local calls __tls_get_addr, and with the variable in the inlined
/// search the compiler derived its address again on every push and pop
/// (about 100 calls a query on docs/scenes.md's mesh); the reference it
/// returns is an ordinary one.
template <typename Entry>
[[gnu::noinline]] std::vector<Entry>& scratchQueue() {
  thread_local std::vector<Entry> queue;
  return queue;
}

/// FCL's stop rule for distance traversals (MeshShapeDistanceTraversalNode::
/// canStop): nothing with lower bound `bound` can improve `best` by more than
/// the request's tolerances.
inline bool cannotImprove(double bound, double best, double rel_err, double abs_err) {
  return bound >= best - abs_err && bound * (1 + rel_err) >= best;
}

/// Opens `root`, then the nodes its opening offers, nearest first: Entry holds
/// a lower bound `bound` on what the node holds and orders by operator> (the
/// queue is a min-heap on it). `open(entry, offer)` opens a node, calling
/// offer(child) for each child worth opening. The nearest child offered (the
/// first of equals) is opened next without passing through the queue when
/// nothing queued is nearer; then nothing queued can beat the best answer
/// when that child cannot. The search ends when the next node's bound cannot
/// improve the answer (`cannot_improve(bound)`), when `finished()` after an
/// opening, or when nothing is left. `queue`: the caller's scratch.
template <typename Entry, typename Open, typename CannotImprove, typename Finished>
void bestFirstSearch(std::vector<Entry>& queue, const Entry& root, Open&& open,
                     CannotImprove&& cannot_improve, Finished&& finished) {
  queue.clear();
  const auto push = [&queue](const Entry& entry) {
    queue.push_back(entry);
    std::push_heap(queue.begin(), queue.end(), std::greater<Entry>());
  };
  std::optional<Entry> next = root;
  while (next || !queue.empty()) {
    if (!next) {
      next = queue.front();
      std::pop_heap(queue.begin(), queue.end(), std::greater<Entry>());
      queue.pop_back();
    }
    if (cannot_improve(next->bound)) break;
    std::optional<Entry> nearest;
    open(*next, [&](const Entry& child) {
      if (!nearest) {
        nearest = child;
      } else if (child.bound < nearest->bound) {
        push(*nearest);
        nearest = child;
      } else {
        push(child);
      }
    });
    next.reset();
    if (nearest) {
      if (queue.empty() || nearest->bound <= queue.front().bound) {
        next = nearest;
      } else {
        push(*nearest);
      }
    }
    if (finished()) break;
  }
}

}  // namespace internal
}  // namespace fcl_disk

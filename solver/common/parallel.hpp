// Deterministic parallel loops. The index range is cut into fixed blocks
// whatever the thread count, each block's result is kept apart and the
// results are combined in block order: a sum has the same bits on 1, 2 or 64
// threads, and for any schedule.
#pragma once

#include <algorithm>
#include <cstddef>
#include <thread>
#include <vector>

#ifdef _OPENMP
#define SPLAT_PARALLEL_PRAGMA(directive) _Pragma(#directive)
#else
#define SPLAT_PARALLEL_PRAGMA(directive)
#endif

namespace splat {

// The most OpenMP threads a run may ask for: the hardware threads of this
// machine (std::thread::hardware_concurrency, at least 1).
inline int max_threads() {
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

// Sum over the blocks [first, last) of [0, n) (`block` indices each, the last
// one shorter) of body(first, last), added in block order starting from
// `zero`. Blocks run in parallel (OpenMP, guided schedule: long runs of
// neighbouring blocks first, for cache locality, short ones last, for
// balance) when n is at least min_parallel; body must only write what its own
// block owns.
template <class T, class Body>
T block_sum(std::size_t n, std::size_t block, std::size_t min_parallel, const T& zero,
            Body&& body) {
  const std::size_t blocks = (n + block - 1) / block;
  std::vector<T> part(blocks, zero);
  const long long count = static_cast<long long>(blocks);
  const bool parallel = n >= min_parallel;
  SPLAT_PARALLEL_PRAGMA(omp parallel for schedule(guided) if (parallel))
  for (long long bk = 0; bk < count; ++bk) {
    const std::size_t k = static_cast<std::size_t>(bk);
    part[k] = body(k * block, std::min(n, (k + 1) * block));
  }
  T total = zero;
  for (const T& p : part) total += p;
  return total;
}

// Runs body(first, last) for every block of [0, n), in parallel when n is at
// least min_parallel (a block_sum without a result).
template <class Body>
void for_each_block(std::size_t n, std::size_t block, std::size_t min_parallel, Body&& body) {
  const std::size_t blocks = (n + block - 1) / block;
  const long long count = static_cast<long long>(blocks);
  const bool parallel = n >= min_parallel;
  SPLAT_PARALLEL_PRAGMA(omp parallel for schedule(guided) if (parallel))
  for (long long bk = 0; bk < count; ++bk) {
    const std::size_t k = static_cast<std::size_t>(bk);
    body(k * block, std::min(n, (k + 1) * block));
  }
}

}  // namespace splat

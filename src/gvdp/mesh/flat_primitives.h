// The data-parallel primitives the level-by-level kd-tree builder is written in, on the CPU
// thread pool: each is one CUB call on the GPU (exclusiveScan: cub::DeviceScan::ExclusiveScan
// over a transform iterator; segmentedReduce: cub::DeviceSegmentedReduce::Reduce). Results do
// not depend on the number of threads: scans are of integers, and reductions use an operator
// that is a total order (kdtree.h betterSplit), so any association gives the same element.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "gvdp/base/parallel.h"

namespace gvdp::detail {

constexpr int64_t FLAT_CHUNK = 1 << 14;

// out[i] = value(0) + ... + value(i - 1) for i in [0, n]; out has n + 1 elements (out[n]: the
// total). Chunk sums, their scan, then each chunk's scan.
template <class T, class Value>
void exclusiveScan(int64_t n, Value value, std::vector<T>& out) {
  out.assign(static_cast<size_t>(n) + 1, T{});
  int64_t chunks = (n + FLAT_CHUNK - 1) / FLAT_CHUNK;
  std::vector<T> sums(static_cast<size_t>(chunks) + 1, T{});
  parallelFor(
      chunks,
      [&](int64_t c) {
        T s{};
        for (int64_t i = c * FLAT_CHUNK, e = std::min(n, (c + 1) * FLAT_CHUNK); i < e; ++i)
          s = s + value(i);
        sums[static_cast<size_t>(c)] = s;
      },
      1);
  T run{};
  for (int64_t c = 0; c < chunks; ++c) {
    T s = sums[static_cast<size_t>(c)];
    sums[static_cast<size_t>(c)] = run;
    run = run + s;
  }
  parallelFor(
      chunks,
      [&](int64_t c) {
        T s = sums[static_cast<size_t>(c)];
        for (int64_t i = c * FLAT_CHUNK, e = std::min(n, (c + 1) * FLAT_CHUNK); i < e; ++i) {
          out[static_cast<size_t>(i)] = s;
          s = s + value(i);
        }
      },
      1);
  out[static_cast<size_t>(n)] = run;
}

// out[s] = the best of value(i) for i in [begin[s], begin[s + 1]) (identity when empty), for
// `segments` segments. Segments are cut into pieces of at most FLAT_CHUNK, reduced in parallel,
// then each segment's pieces: one node of a million events and a million nodes of one event
// both keep every thread busy.
template <class T, class Value, class Better>
void segmentedReduce(const std::vector<uint32_t>& begin, int64_t segments, T identity, Value value,
                     Better better, std::vector<T>& out) {
  std::vector<uint32_t> pieceBegin;
  exclusiveScan<uint32_t>(
      segments,
      [&](int64_t s) {
        uint32_t len = begin[static_cast<size_t>(s) + 1] - begin[static_cast<size_t>(s)];
        return static_cast<uint32_t>((len + FLAT_CHUNK - 1) / FLAT_CHUNK);
      },
      pieceBegin);
  int64_t pieces = pieceBegin[static_cast<size_t>(segments)];
  std::vector<T> partial(static_cast<size_t>(pieces), identity);
  parallelFor(
      pieces,
      [&](int64_t p) {
        // the piece's segment: the last s with pieceBegin[s] <= p (empty segments have none)
        auto s = static_cast<size_t>(std::upper_bound(pieceBegin.begin(),
                                                      pieceBegin.begin() + segments + 1,
                                                      static_cast<uint32_t>(p)) -
                                     pieceBegin.begin() - 1);
        int64_t first = begin[s] + (p - pieceBegin[s]) * FLAT_CHUNK;
        int64_t last = std::min<int64_t>(begin[s + 1], first + FLAT_CHUNK);
        T best = identity;
        for (int64_t i = first; i < last; ++i) {
          T v = value(i);
          if (better(v, best)) best = v;
        }
        partial[static_cast<size_t>(p)] = best;
      },
      4);
  out.assign(static_cast<size_t>(segments), identity);
  parallelFor(
      segments,
      [&](int64_t s) {
        T best = identity;
        for (uint32_t p = pieceBegin[static_cast<size_t>(s)];
             p < pieceBegin[static_cast<size_t>(s) + 1]; ++p)
          if (better(partial[p], best)) best = partial[p];
        out[static_cast<size_t>(s)] = best;
      },
      256);
}

}  // namespace gvdp::detail

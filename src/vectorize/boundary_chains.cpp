// SPDX-License-Identifier: GPL-3.0-or-later
#include "boundary_chains.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <utility>

#include "bands.hpp"

namespace origamic::chains {

Grid<std::int32_t> labels_inside_sheet(Grid<std::int32_t> labels) {
  // The pixels inside that border one outside, row by row, found in bands in parallel.
  std::array<std::vector<std::pair<int, int>>, kBands> band_rings;
  for_bands(labels.rows, [&](int band, int row_begin, int row_end) {
    for (int row = row_begin; row < row_end; ++row)
      for (int col = 0; col < labels.cols; ++col) {
        if (labels(col, row) < 0) continue;
        const bool borders_outside =
            (col > 0 && labels(col - 1, row) < 0) || (col + 1 < labels.cols && labels(col + 1, row) < 0) ||
            (row > 0 && labels(col, row - 1) < 0) || (row + 1 < labels.rows && labels(col, row + 1) < 0);
        if (borders_outside) band_rings[static_cast<std::size_t>(band)].emplace_back(col, row);
      }
  });
  std::vector<std::pair<int, int>> ring, next;
  for (const auto& band : band_rings) ring.insert(ring.end(), band.begin(), band.end());
  while (!ring.empty()) {
    next.clear();
    for (const auto& [col, row] : ring)
      for (const auto& [c, r] : {std::pair{col - 1, row}, {col + 1, row}, {col, row - 1}, {col, row + 1}})
        if (labels.contains(c, r) && labels(c, r) < 0) {
          labels(c, r) = labels(col, row);
          next.emplace_back(c, r);
        }
    ring.swap(next);
  }
  return labels;
}

std::vector<Chain> trace_chains(const Grid<std::int32_t>& labels) {
  const int cols = labels.cols, rows = labels.rows, corner_cols = cols + 1;
  if (cols == 0 || rows == 0) return {};
  auto corner = [&](int c, int r) { return static_cast<std::size_t>(r) * corner_cols + c; };
  struct Edge {
    std::size_t from, to;
    std::int32_t left, right;
  };
  std::vector<Edge> edges;
  // Directed so that the smaller label lies on the left: then each chain runs one way throughout.
  auto directed = [](std::size_t a, std::size_t b, std::int32_t left, std::int32_t right) {
    return left < right ? Edge{a, b, left, right} : Edge{b, a, right, left};
  };
  // The scans run in bands of rows in parallel; each band's edges keep their place in the order.
  // Between pixel rows r - 1 (above) and r, walking +X, above on the left: row by row.
  std::array<std::vector<Edge>, kBands> band_edges;
  for_bands(rows - 1, [&](int band, int begin, int end) {
    for (int r = begin + 1; r < end + 1; ++r)
      for (int c = 0; c < cols; ++c)
        if (labels(c, r - 1) != labels(c, r))
          band_edges[static_cast<std::size_t>(band)].push_back(
              directed(corner(c, r), corner(c + 1, r), labels(c, r - 1), labels(c, r)));
  });
  for (const std::vector<Edge>& band : band_edges) edges.insert(edges.end(), band.begin(), band.end());
  // Between pixel columns c - 1 and c, walking +Y (up), c - 1 on the left: column by column, as the
  // tracing order depends on it, but found row by row (columns are far apart in memory): each band
  // counts its edges per column, and then writes them where its rows fall in each column.
  std::array<std::vector<std::size_t>, kBands> band_next;  // per band and column: where its next edge goes
  for_bands(rows, [&](int band, int begin, int end) {
    std::vector<std::size_t>& count = band_next[static_cast<std::size_t>(band)];
    count.assign(static_cast<std::size_t>(cols), 0);
    for (int r = begin; r < end; ++r)
      for (int c = 1; c < cols; ++c) count[static_cast<std::size_t>(c)] += labels(c - 1, r) != labels(c, r);
  });
  std::size_t total = edges.size();
  for (std::size_t c = 1; c < static_cast<std::size_t>(cols); ++c)
    for (std::vector<std::size_t>& next : band_next) total += std::exchange(next[c], total);
  edges.resize(total);
  for_bands(rows, [&](int band, int begin, int end) {
    std::vector<std::size_t>& next = band_next[static_cast<std::size_t>(band)];
    for (int r = begin; r < end; ++r)
      for (int c = 1; c < cols; ++c)
        if (labels(c - 1, r) != labels(c, r))
          edges[next[static_cast<std::size_t>(c)]++] =
              directed(corner(c, r + 1), corner(c, r), labels(c - 1, r), labels(c, r));
  });

  const std::size_t corners = static_cast<std::size_t>(corner_cols) * (rows + 1);
  std::vector<std::uint8_t> degree(corners, 0);
  std::vector<std::uint32_t> first_out(corners + 1, 0);
  for (const Edge& e : edges) ++degree[e.from], ++degree[e.to], ++first_out[e.from + 1];
  for (std::size_t i = 0; i < corners; ++i) first_out[i + 1] += first_out[i];
  std::vector<std::uint32_t> out(edges.size());
  {
    std::vector<std::uint32_t> fill(first_out.begin(), first_out.end() - 1);
    for (std::uint32_t i = 0; i < edges.size(); ++i) out[fill[edges[i].from]++] = i;
  }
  auto is_junction = [&](std::size_t k) {
    const int c = static_cast<int>(k % corner_cols), r = static_cast<int>(k / corner_cols);
    return degree[k] != 2 || c == 0 || c == cols || r == 0 || r == rows;
  };
  auto lattice = [&](std::size_t k) {
    return LatticePoint{2 * static_cast<int>(k % corner_cols), 2 * static_cast<int>(k / corner_cols)};
  };

  std::vector<bool> used(edges.size(), false);
  std::vector<Chain> chains;
  auto follow = [&](std::uint32_t first) {
    Chain chain{edges[first].left, edges[first].right, {lattice(edges[first].from)}};
    std::uint32_t e = first;
    for (;;) {
      used[e] = true;
      const std::size_t at = edges[e].to;
      chain.corners.push_back(lattice(at));
      if (is_junction(at)) break;
      std::uint32_t next = UINT32_MAX;
      for (std::uint32_t i = first_out[at]; i < first_out[at + 1]; ++i)
        if (!used[out[i]]) next = out[i];
      if (next == UINT32_MAX) break;  // a closed loop is back at its start
      e = next;
    }
    chains.push_back(std::move(chain));
  };
  for (std::size_t k = 0; k < corners; ++k)
    if (degree[k] > 0 && is_junction(k))
      for (std::uint32_t i = first_out[k]; i < first_out[k + 1]; ++i)
        if (!used[out[i]]) follow(out[i]);
  for (std::uint32_t i = 0; i < edges.size(); ++i)
    if (!used[i]) follow(i);
  return chains;
}

}  // namespace origamic::chains

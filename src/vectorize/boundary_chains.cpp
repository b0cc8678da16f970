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

namespace {

// One pixel edge between two labels, from pixel corner to pixel corner, with `left` on its left.
struct Edge {
  std::size_t from, to;
  std::int32_t left, right;
};

// Directed so that the smaller label lies on the left: then each chain runs one way throughout.
Edge directed(std::size_t a, std::size_t b, std::int32_t left, std::int32_t right) {
  return left < right ? Edge{a, b, left, right} : Edge{b, a, right, left};
}

// The pixel corners of a grid of cols x rows pixels, numbered row by row.
struct Corners {
  int cols, rows;

  std::size_t size() const { return static_cast<std::size_t>(cols + 1) * (rows + 1); }
  std::size_t at(int c, int r) const { return static_cast<std::size_t>(r) * (cols + 1) + c; }
  int col(std::size_t k) const { return static_cast<int>(k % (cols + 1)); }
  int row(std::size_t k) const { return static_cast<int>(k / (cols + 1)); }
  bool on_border(std::size_t k) const { return col(k) == 0 || col(k) == cols || row(k) == 0 || row(k) == rows; }
  LatticePoint lattice(std::size_t k) const { return {2 * col(k), 2 * row(k)}; }
};

// The scans run in bands of rows in parallel; each band's edges keep their place in the order.
// Between pixel rows r - 1 (above) and r, walking +X, above on the left: row by row.
std::vector<Edge> edges_between_rows(const Grid<std::int32_t>& labels) {
  const Corners corner{labels.cols, labels.rows};
  std::array<std::vector<Edge>, kBands> band_edges;
  for_bands(labels.rows - 1, [&](int band, int begin, int end) {
    for (int r = begin + 1; r < end + 1; ++r)
      for (int c = 0; c < labels.cols; ++c)
        if (labels(c, r - 1) != labels(c, r))
          band_edges[static_cast<std::size_t>(band)].push_back(
              directed(corner.at(c, r), corner.at(c + 1, r), labels(c, r - 1), labels(c, r)));
  });
  std::vector<Edge> edges;
  for (const std::vector<Edge>& band : band_edges) edges.insert(edges.end(), band.begin(), band.end());
  return edges;
}

using PerBandAndColumn = std::array<std::vector<std::size_t>, kBands>;

// Per band of rows and per column c: the edges between pixel columns c - 1 and c.
PerBandAndColumn edges_between_columns_per_band(const Grid<std::int32_t>& labels) {
  PerBandAndColumn band_count;
  for_bands(labels.rows, [&](int band, int begin, int end) {
    std::vector<std::size_t>& count = band_count[static_cast<std::size_t>(band)];
    count.assign(static_cast<std::size_t>(labels.cols), 0);
    for (int r = begin; r < end; ++r)
      for (int c = 1; c < labels.cols; ++c) count[static_cast<std::size_t>(c)] += labels(c - 1, r) != labels(c, r);
  });
  return band_count;
}

// `edges` followed by those between pixel columns c - 1 and c, walking +Y (up), c - 1 on the left:
// column by column, as the tracing order depends on it, but found row by row (columns are far apart
// in memory): each band counts its edges per column, and then writes them where its rows fall in
// each column.
std::vector<Edge> with_edges_between_columns(const Grid<std::int32_t>& labels, std::vector<Edge> edges) {
  const Corners corner{labels.cols, labels.rows};
  PerBandAndColumn band_next = edges_between_columns_per_band(labels);  // then: where its next edge goes
  std::size_t total = edges.size();
  for (std::size_t c = 1; c < static_cast<std::size_t>(labels.cols); ++c)
    for (std::vector<std::size_t>& next : band_next) total += std::exchange(next[c], total);
  edges.resize(total);
  for_bands(labels.rows, [&](int band, int begin, int end) {
    std::vector<std::size_t>& next = band_next[static_cast<std::size_t>(band)];
    for (int r = begin; r < end; ++r)
      for (int c = 1; c < labels.cols; ++c)
        if (labels(c - 1, r) != labels(c, r))
          edges[next[static_cast<std::size_t>(c)]++] =
              directed(corner.at(c, r + 1), corner.at(c, r), labels(c - 1, r), labels(c, r));
  });
  return edges;
}

// The edges as a graph on the pixel corners.
struct BoundaryGraph {
  Corners corners;
  std::vector<Edge> edges;
  std::vector<std::uint8_t> degree;      // per corner: the edges that meet it
  std::vector<std::uint32_t> first_out;  // per corner and one past the last: where its edges begin in `out`
  std::vector<std::uint32_t> out;        // the edges leaving each corner, corner by corner
};

BoundaryGraph boundary_graph(Corners corners, std::vector<Edge> edges) {
  const std::size_t n = corners.size();
  BoundaryGraph graph{.corners = corners,
                      .edges = std::move(edges),
                      .degree = std::vector<std::uint8_t>(n, 0),
                      .first_out = std::vector<std::uint32_t>(n + 1, 0),
                      .out = {}};
  for (const Edge& e : graph.edges) ++graph.degree[e.from], ++graph.degree[e.to], ++graph.first_out[e.from + 1];
  for (std::size_t i = 0; i < n; ++i) graph.first_out[i + 1] += graph.first_out[i];
  graph.out.resize(graph.edges.size());
  std::vector<std::uint32_t> fill(graph.first_out.begin(), graph.first_out.end() - 1);
  for (std::uint32_t i = 0; i < graph.edges.size(); ++i) graph.out[fill[graph.edges[i].from]++] = i;
  return graph;
}

// The graph's edges followed into chains, each edge into one.
class ChainTracer {
 public:
  explicit ChainTracer(const BoundaryGraph& graph) : graph_(graph), used_(graph.edges.size(), false) {}

  std::vector<Chain> trace() {
    std::vector<Chain> chains;
    for (std::size_t k = 0; k < graph_.corners.size(); ++k)
      if (graph_.degree[k] > 0 && is_junction(k))
        for (std::uint32_t i = graph_.first_out[k]; i < graph_.first_out[k + 1]; ++i)
          if (!used_[graph_.out[i]]) chains.push_back(follow(graph_.out[i]));
    for (std::uint32_t i = 0; i < graph_.edges.size(); ++i)  // the closed loops left
      if (!used_[i]) chains.push_back(follow(i));
    return chains;
  }

 private:
  bool is_junction(std::size_t k) const { return graph_.degree[k] != 2 || graph_.corners.on_border(k); }

  Chain follow(std::uint32_t first) {
    const std::vector<Edge>& edges = graph_.edges;
    Chain chain{edges[first].left, edges[first].right, {graph_.corners.lattice(edges[first].from)}};
    std::uint32_t e = first;
    for (;;) {
      used_[e] = true;
      const std::size_t at = edges[e].to;
      chain.corners.push_back(graph_.corners.lattice(at));
      if (is_junction(at)) break;
      std::uint32_t next = UINT32_MAX;
      for (std::uint32_t i = graph_.first_out[at]; i < graph_.first_out[at + 1]; ++i)
        if (!used_[graph_.out[i]]) next = graph_.out[i];
      if (next == UINT32_MAX) break;  // a closed loop is back at its start
      e = next;
    }
    return chain;
  }

  const BoundaryGraph& graph_;
  std::vector<bool> used_;  // per edge
};

}  // namespace

std::vector<Chain> trace_chains(const Grid<std::int32_t>& labels) {
  if (labels.cols == 0 || labels.rows == 0) return {};
  const Corners corners{labels.cols, labels.rows};
  const BoundaryGraph graph = boundary_graph(corners, with_edges_between_columns(labels, edges_between_rows(labels)));
  return ChainTracer(graph).trace();
}

}  // namespace origamic::chains

// SPDX-License-Identifier: GPL-3.0-or-later
#include "face_pieces.hpp"

#include <algorithm>
#include <boost/container/small_vector.hpp>
#include <climits>
#include <cstdint>
#include <span>
#include <utility>

#include "union_find.hpp"

namespace origamic {
namespace {

// Calls join(i, j) for each run i of `a` and run j of `b` that share a row (neighbouring columns:
// 4-connected). Both are top to bottom and apart within their column.
template <typename RunsA, typename RunsB, typename Join>
void for_each_touching(const RunsA& a, const RunsB& b, Join&& join) {
  std::size_t i = 0;
  for (std::size_t j = 0; j < b.size(); ++j) {
    while (i < a.size() && a[i].r1 <= b[j].r0) ++i;
    for (std::size_t k = i; k < a.size() && a[k].r0 < b[j].r1; ++k) join(k, j);
  }
}

}  // namespace

FacePieces::FacePieces(std::span<const RowRun> runs) {
  if (runs.empty()) return;
  int first = INT_MAX, last = INT_MIN;
  for (const RowRun& run : runs) first = std::min(first, run.c0), last = std::max(last, run.c1 - 1);
  first_col_ = first, cols_ = last + 1 - first;
  std::vector<std::vector<ColumnRun>> columns(static_cast<std::size_t>(cols_));
  for (const RowRun& run : runs)  // row by row: each column's runs grow downwards
    for (int c = run.c0; c < run.c1; ++c) {
      std::vector<ColumnRun>& column = columns[static_cast<std::size_t>(c - first)];
      if (!column.empty() && column.back().r1 == run.row)
        ++column.back().r1;
      else
        column.push_back({run.row, run.row + 1});
    }
  for (const std::vector<ColumnRun>& column : columns) {
    column_begin_.push_back(static_cast<int>(runs_.size()));
    runs_.insert(runs_.end(), column.begin(), column.end());
  }
  column_begin_.push_back(static_cast<int>(runs_.size()));

  // From one side to the other, column by column: each run's piece (the smallest run of it, so
  // far) and the pieces so far that no longer reach the column.
  const auto label = [&](bool from_left, std::vector<int>& labels, std::vector<int>& closed) {
    UnionFind<int> sets(runs_.size());
    labels.assign(runs_.size(), -1);
    closed.assign(static_cast<std::size_t>(cols_), 0);
    int pieces = 0;
    std::vector<int> reaching;
    for (int k = 0; k < cols_; ++k) {
      const int c = from_left ? k : cols_ - 1 - k;
      const int begin = column_begin_[c], end = column_begin_[c + 1];
      pieces += end - begin;
      if (k > 0) {
        const int before = from_left ? c - 1 : c + 1;
        const int before_begin = column_begin_[before];
        for_each_touching(std::span(runs_).subspan(before_begin, column_begin_[before + 1] - before_begin),
                          std::span(runs_).subspan(begin, end - begin), [&](std::size_t i, std::size_t j) {
                            if (sets.join(before_begin + static_cast<int>(i), begin + static_cast<int>(j))) --pieces;
                          });
      }
      reaching.clear();
      for (int b = begin; b < end; ++b) {
        labels[b] = sets.root(b);
        if (std::ranges::find(reaching, labels[b]) == reaching.end()) reaching.push_back(labels[b]);
      }
      closed[c] = pieces - static_cast<int>(reaching.size());
    }
    return pieces;
  };
  pieces_ = label(true, left_label_, closed_left_);
  label(false, right_label_, closed_right_);
}

int FacePieces::pieces_without(int c0, int c1, int r0, int r1) const {
  c0 = std::max(c0, first_col_) - first_col_, c1 = std::min(c1, first_col_ + cols_) - first_col_;
  if (c0 >= c1 || r0 >= r1) return pieces_;
  // The nodes: the pieces left of the rectangle that reach its left side, those right of it that
  // reach its right side, and the runs of its columns above and below it.
  // On the stack: a support's cost asks this of hundreds of thousands of rectangles (seedlike/torus:
  // 890,000 allocations here, an eighth of the design's).
  boost::container::small_vector<int, 16> left, right, middle_begin;
  boost::container::small_vector<ColumnRun, 64> middle;
  const auto column = [&](int c) {
    return std::span(runs_).subspan(column_begin_[c], column_begin_[c + 1] - column_begin_[c]);
  };
  const auto labels_beside = [&](int c, const std::vector<int>& labels, auto& out) {
    for (int b = column_begin_[c]; b < column_begin_[c + 1]; ++b)
      if (std::ranges::find(out, labels[b]) == out.end()) out.push_back(labels[b]);
  };
  if (c0 > 0) labels_beside(c0 - 1, left_label_, left);
  if (c1 < cols_) labels_beside(c1, right_label_, right);
  for (int c = c0; c < c1; ++c) {
    middle_begin.push_back(static_cast<int>(middle.size()));
    for (const ColumnRun& run : column(c)) {
      if (run.r0 < r0) middle.push_back({run.r0, std::min(run.r1, r0)});
      if (run.r1 > r1) middle.push_back({std::max(run.r0, r1), run.r1});
    }
  }
  middle_begin.push_back(static_cast<int>(middle.size()));
  const int left_nodes = static_cast<int>(left.size()), side_nodes = left_nodes + static_cast<int>(right.size());
  UnionFind<int> sets(static_cast<std::size_t>(side_nodes) + middle.size());
  int nodes = side_nodes + static_cast<int>(middle.size());
  const auto middle_of = [&](int k) {
    return std::span<const ColumnRun>(middle.data(), middle.size())
        .subspan(middle_begin[k], middle_begin[k + 1] - middle_begin[k]);
  };
  const auto node_of = [&](const auto& labels, int label, int offset) {
    return offset + static_cast<int>(std::ranges::find(labels, label) - labels.begin());
  };
  if (c0 > 0) {
    const int before = column_begin_[c0 - 1];
    for_each_touching(column(c0 - 1), middle_of(0), [&](std::size_t i, std::size_t j) {
      nodes -= sets.join(node_of(left, left_label_[before + static_cast<int>(i)], 0),
                         side_nodes + middle_begin[0] + static_cast<int>(j));
    });
  }
  for (int k = 1; k < c1 - c0; ++k)
    for_each_touching(middle_of(k - 1), middle_of(k), [&](std::size_t i, std::size_t j) {
      nodes -= sets.join(side_nodes + middle_begin[k - 1] + static_cast<int>(i),
                         side_nodes + middle_begin[k] + static_cast<int>(j));
    });
  if (c1 < cols_) {
    const int after = column_begin_[c1], last = c1 - c0 - 1;
    for_each_touching(middle_of(last), column(c1), [&](std::size_t i, std::size_t j) {
      nodes -= sets.join(side_nodes + middle_begin[last] + static_cast<int>(i),
                         node_of(right, right_label_[after + static_cast<int>(j)], left_nodes));
    });
  }
  return (c0 > 0 ? closed_left_[c0 - 1] : 0) + (c1 < cols_ ? closed_right_[c1] : 0) + nodes;
}

int pieces_less(std::span<const FacePieces::RowRun> runs, std::span<const PixelRect> rects) {
  std::vector<FacePieces::RowRun> left;
  std::vector<std::pair<int, int>> out;  // the columns taken out of a run's row
  for (const FacePieces::RowRun& run : runs) {
    out.clear();
    for (const PixelRect& r : rects)
      if (r.r0 <= run.row && run.row < r.r1 && r.c0 < run.c1 && run.c0 < r.c1) out.emplace_back(r.c0, r.c1);
    std::ranges::sort(out);
    int c = run.c0;
    for (const auto& [c0, c1] : out) {
      if (c0 > c) left.push_back({run.row, c, std::min(c0, run.c1)});
      c = std::max(c, c1);
    }
    if (c < run.c1) left.push_back({run.row, c, run.c1});
  }
  return FacePieces(left).pieces();  // still in row-major order
}

}  // namespace origamic

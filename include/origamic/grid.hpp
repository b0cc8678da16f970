// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <cassert>
#include <cstddef>

#include "origamic/unfilled_vector.hpp"

namespace origamic {

/// A row-major image of values; row 0 is the top row.
template <class T>
struct Grid {
  int cols = 0;
  int rows = 0;
  UnfilledVector<T> values;

  Grid() = default;
  Grid(int cols_, int rows_, const T& fill = T{})
      : cols(cols_), rows(rows_), values(static_cast<std::size_t>(cols_) * rows_, fill) {}
  /// A grid whose values are left unwritten (trivial T): the caller writes every one.
  static Grid unfilled(int cols, int rows) {
    Grid grid;
    grid.cols = cols, grid.rows = rows;
    grid.values.resize(static_cast<std::size_t>(cols) * rows);
    return grid;
  }

  bool contains(int col, int row) const { return col >= 0 && row >= 0 && col < cols && row < rows; }
  std::size_t index(int col, int row) const {
    assert(contains(col, row));
    return static_cast<std::size_t>(row) * cols + col;
  }
  T& operator()(int col, int row) { return values[index(col, row)]; }
  const T& operator()(int col, int row) const { return values[index(col, row)]; }
  std::size_t size() const { return values.size(); }
};

}  // namespace origamic

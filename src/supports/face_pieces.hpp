// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: how many 4-connected pieces a face of the raster plan falls into once a rectangle of
// pixels is taken out of it, in time proportional to the rectangle's columns, not to the face; and
// once several are, in time proportional to the face.
#pragma once

#include <span>
#include <vector>

#include "pixel_rect.hpp"

namespace origamic {

// A face's pixels as runs down its columns, with its pieces labelled column by column from the
// left and from the right: the pieces left of a rectangle and right of it are known, and only the
// columns the rectangle spans are joined up anew.
class FacePieces {
 public:
  struct RowRun {
    int row, c0, c1;  // pixels [c0, c1) of the row
  };
  /// \pre `runs` are the face's pixels along its rows, in row-major order, none overlapping.
  explicit FacePieces(std::span<const RowRun> runs);

  int pieces() const { return pieces_; }
  // The pieces of the face less the pixels [c0, c1) x [r0, r1).
  int pieces_without(int c0, int c1, int r0, int r1) const;

 private:
  struct ColumnRun {
    int r0, r1;  // rows [r0, r1) of its column
  };
  int first_col_ = 0, cols_ = 0;  // the face's columns [first_col_, first_col_ + cols_)
  int pieces_ = 0;
  std::vector<ColumnRun> runs_;    // column by column, top to bottom
  std::vector<int> column_begin_;  // per column, its first run; one more at the end
  std::vector<int> left_label_;    // per run: its piece among the face's columns up to its own
  std::vector<int> right_label_;   // per run: its piece among the face's columns from its own on
  std::vector<int> closed_left_;   // per column: pieces of the columns up to it that do not reach it
  std::vector<int> closed_right_;  // per column: pieces of the columns from it on that do not reach it
};

/// The 4-connected pieces of a face's pixels less those of some rectangles.
/// \pre as FacePieces'.
int pieces_less(std::span<const FacePieces::RowRun> runs, std::span<const PixelRect> rects);

}  // namespace origamic

// SPDX-License-Identifier: GPL-3.0-or-later
#include "disc_width.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace origamic {
namespace {

// One line of the squared distance transform: out[q] = min over p of (q - p)^2 + f[p], the lower
// envelope of the parabolas rooted at each p (f[p] infinite: none there).
class LineTransform {
 public:
  void run(const std::vector<double>& f, std::vector<double>& out) {
    const int n = static_cast<int>(f.size());
    root_.assign(f.size(), 0);
    from_.assign(f.size() + 1, 0);
    out.assign(f.size(), kInf);
    // In doubles: a line may be longer than an int's square root (46,341 pixels).
    const auto square = [](int i) { return static_cast<double>(i) * i; };
    int k = -1;  // the envelope's last parabola
    for (int q = 0; q < n; ++q) {
      if (f[at(q)] == kInf) continue;
      double s = -kInf;  // where q's parabola passes the envelope's last; the first holds from -inf
      while (k >= 0) {
        const int r = root_[at(k)];
        s = ((f[at(q)] + square(q)) - (f[at(r)] + square(r))) / (2.0 * (q - r));
        if (s > from_[at(k)]) break;
        --k;
      }
      ++k;
      root_[at(k)] = q;
      from_[at(k)] = s;
    }
    if (k < 0) return;  // nothing outside: every distance infinite
    from_[at(k + 1)] = kInf;
    for (int q = 0, j = 0; q < n; ++q) {
      while (from_[at(j + 1)] < q) ++j;
      const int r = root_[at(j)];
      out[at(q)] = square(q - r) + f[at(r)];
    }
  }

 private:
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  static std::size_t at(int i) { return static_cast<std::size_t>(i); }
  std::vector<int> root_;
  std::vector<double> from_;
};

}  // namespace

double widest_disc_px(const std::vector<std::pair<int, int>>& pixels) {
  if (pixels.empty()) return 0;
  const auto [leftmost, rightmost] = std::ranges::minmax(pixels, {}, &std::pair<int, int>::first);
  const auto [topmost, bottommost] = std::ranges::minmax(pixels, {}, &std::pair<int, int>::second);
  // The set's box and a ring of outside pixels round it.
  const int left = leftmost.first - 1, top = topmost.second - 1;
  const auto cols = static_cast<std::size_t>(rightmost.first - left + 2);
  const auto rows = static_cast<std::size_t>(bottommost.second - top + 2);
  std::vector<double> squared(cols * rows, 0);
  for (const auto& [x, y] : pixels)
    squared[static_cast<std::size_t>(y - top) * cols + static_cast<std::size_t>(x - left)] =
        std::numeric_limits<double>::infinity();
  LineTransform transform;
  std::vector<double> line, out;
  for (std::size_t c = 0; c < cols; ++c) {
    line.resize(rows);
    for (std::size_t r = 0; r < rows; ++r) line[r] = squared[r * cols + c];
    transform.run(line, out);
    for (std::size_t r = 0; r < rows; ++r) squared[r * cols + c] = out[r];
  }
  double farthest = 0;
  for (std::size_t r = 0; r < rows; ++r) {
    line.assign(squared.begin() + static_cast<std::ptrdiff_t>(r * cols),
                squared.begin() + static_cast<std::ptrdiff_t>((r + 1) * cols));
    transform.run(line, out);
    farthest = std::max(farthest, *std::ranges::max_element(out));
  }
  return 2 * std::sqrt(farthest);
}

// The side of the largest square ending at each pixel, row after row: one more than the least of
// its left, upper and upper-left neighbours'.
bool holds_square_px(const std::vector<std::pair<int, int>>& pixels, int k) {
  if (pixels.empty()) return false;
  const auto [leftmost, rightmost] = std::ranges::minmax(pixels, {}, &std::pair<int, int>::first);
  const int left = leftmost.first;
  const auto cols = static_cast<std::size_t>(rightmost.first - left + 1);
  std::vector<int> above(cols + 1, 0), here(cols + 1, 0);  // per column + 1; 0 before the first
  int row = pixels.front().second;
  std::size_t next = 0;
  while (next < pixels.size()) {
    std::ranges::fill(here, 0);
    for (; next < pixels.size() && pixels[next].second == row; ++next) {
      const auto c = static_cast<std::size_t>(pixels[next].first - left) + 1;
      here[c] = 1 + std::min({here[c - 1], above[c], above[c - 1]});
      if (here[c] >= k) return true;
    }
    std::swap(above, here);
    if (next == pixels.size()) break;
    if (pixels[next].second != row + 1) std::ranges::fill(above, 0);  // a row of none between
    row = pixels[next].second;
  }
  return false;
}

}  // namespace origamic

// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/fold_style.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <utility>

#include "number_text.hpp"
#include "origamic/error.hpp"

namespace origamic {
namespace {

using Interval = std::pair<double, double>;

// Printed patterns, mm. A 2 mm dash is long enough to read at arm's length and short enough that a
// 3 mm fold (W's default) still shows a gap; the mountain's 0.5 mm dot stays visible at a 0.1 mm
// line width in print and at 4 px/mm in the preview.
constexpr double kValleyDash[] = {2.0, 1.0};
constexpr double kMountainDash[] = {2.0, 0.75, 0.5, 0.75};

// Runs and dashes shorter than this (mm) are rounding slivers (of touching insets, of a pattern's
// end), not drawn.
constexpr double kNegligible_mm = 1e-6;

double distance(PlanPoint a, PlanPoint b) { return std::hypot(b.X - a.X, b.Y - a.Y); }

// The parameters t in [0, 1] of the segment p + t (q - p) strictly closer than r to the segment a-b.
// The r-neighbourhood of a-b (two discs and a rectangle) is convex, so the set is one interval: the
// hull of the intervals found in each of the three pieces.
std::optional<Interval> closer_than(PlanPoint p, PlanPoint q, PlanPoint a, PlanPoint b, double r) {
  if (!(r > 0)) return std::nullopt;
  const double dx = q.X - p.X, dy = q.Y - p.Y;
  double lo = 2, hi = -1;
  auto hull = [&](double t0, double t1) {
    if (t0 < t1) lo = std::min(lo, t0), hi = std::max(hi, t1);
  };
  for (const PlanPoint c : {a, b}) {  // |p + t d - c|^2 < r^2
    const double A = dx * dx + dy * dy, B = dx * (p.X - c.X) + dy * (p.Y - c.Y);
    const double C = (p.X - c.X) * (p.X - c.X) + (p.Y - c.Y) * (p.Y - c.Y) - r * r;
    if (A == 0) {
      if (C < 0) hull(0, 1);
      continue;
    }
    const double disc = B * B - A * C;
    if (disc > 0) hull((-B - std::sqrt(disc)) / A, (-B + std::sqrt(disc)) / A);
  }
  const double length = distance(a, b);
  if (length > 0) {  // 0 <= u <= length and |v| < r, in a frame along a-b
    const double ex = (b.X - a.X) / length, ey = (b.Y - a.Y) / length;
    const double u0 = (p.X - a.X) * ex + (p.Y - a.Y) * ey, du = dx * ex + dy * ey;
    const double v0 = -(p.X - a.X) * ey + (p.Y - a.Y) * ex, dv = -dx * ey + dy * ex;
    double t0 = -1e300, t1 = 1e300;
    auto slab = [&](double start, double rate, double min, double max) {
      if (rate == 0) {
        if (start < min || start > max) t0 = 1, t1 = 0;
        return;
      }
      double enter = (min - start) / rate, leave = (max - start) / rate;
      if (enter > leave) std::swap(enter, leave);
      t0 = std::max(t0, enter), t1 = std::min(t1, leave);
    };
    slab(u0, du, 0, length);
    slab(v0, dv, -r, r);
    hull(t0, t1);
  }
  lo = std::max(lo, 0.0), hi = std::min(hi, 1.0);
  if (!(lo < hi)) return std::nullopt;
  return Interval{lo, hi};
}

// Arc length of each vertex of a polyline.
std::vector<double> arc_lengths(const std::vector<PlanPoint>& points) {
  std::vector<double> s(points.size(), 0.0);
  for (std::size_t i = 1; i < points.size(); ++i) s[i] = s[i - 1] + distance(points[i - 1], points[i]);
  return s;
}

// The piece of a polyline between arc lengths from and to.
std::vector<PlanPoint> piece(const std::vector<PlanPoint>& points, const std::vector<double>& s, double from,
                             double to) {
  auto at = [&](double t) {
    const std::size_t i = std::min<std::size_t>(
        static_cast<std::size_t>(std::upper_bound(s.begin(), s.end(), t) - s.begin()), points.size() - 1);
    const std::size_t j = i == 0 ? 1 : i;
    const double span = s[j] - s[j - 1], f = span > 0 ? (t - s[j - 1]) / span : 0;
    if (f >= 1) return points[j];
    return PlanPoint{points[j - 1].X + f * (points[j].X - points[j - 1].X),
                     points[j - 1].Y + f * (points[j].Y - points[j - 1].Y)};
  };
  std::vector<PlanPoint> out{at(from)};
  for (std::size_t i = 0; i < points.size(); ++i)
    if (s[i] > from && s[i] < to) out.push_back(points[i]);
  out.push_back(at(to));
  return out;
}

// The stretches of [0, total] left when the blocked intervals are removed.
std::vector<Interval> complement(std::vector<Interval> blocked, double total) {
  std::ranges::sort(blocked);
  std::vector<Interval> free;
  double at = 0;
  for (const auto& [lo, hi] : blocked) {
    if (lo > at) free.emplace_back(at, std::min(lo, total));
    at = std::max(at, hi);
  }
  if (at < total) free.emplace_back(at, total);
  std::erase_if(free, [](const Interval& run) { return run.second - run.first <= kNegligible_mm; });
  return free;
}

// A period of `pattern` fitted to a line of length L: whole periods and a closing first dash, the
// gaps stretched evenly; shorter than one period plus a dash, the pattern is scaled down to fit that.
std::vector<double> fitted(std::span<const double> pattern, double L) {
  double period = 0;
  for (const double v : pattern) period += v;
  const double first = pattern[0];
  std::vector<double> out(pattern.begin(), pattern.end());
  if (L < period + first) {
    for (double& v : out) v *= L / (period + first);
    return out;
  }
  const double n = std::floor((L - first) / period);
  const double stretch = (L - (n * period + first)) / (n * static_cast<double>(pattern.size() / 2));
  for (std::size_t i = 1; i < out.size(); i += 2) out[i] += stretch;
  return out;
}

Layer layer_of(LineKind kind, FoldStyle style) {
  switch (kind) {
    case LineKind::Mountain:
      return style == FoldStyle::Perforated ? Layer::PerfMountain : Layer::Mountain;
    case LineKind::Valley:
      return style == FoldStyle::Perforated ? Layer::PerfValley : Layer::Valley;
    case LineKind::Cut:
      return Layer::Cut;
    case LineKind::CutOut:
      return Layer::CutOut;
    case LineKind::Outline:
      return Layer::Outline;
  }
  return Layer::Cut;
}

std::string mm_text(double value) { return number_text(value); }

// The stretches of a fold polyline (arc lengths s) within inset_mm of a cut segment.
std::vector<Interval> near_cuts(const PlanPolyline& fold, const std::vector<double>& s,
                                std::span<const PlanPolyline> cuts, double inset_mm) {
  const double r = inset_mm;
  std::vector<Interval> blocked;
  for (std::size_t i = 1; i < fold.points.size(); ++i) {
    const PlanPoint p = fold.points[i - 1], q = fold.points[i];
    const double length = s[i] - s[i - 1];
    for (const PlanPolyline& cut : cuts)
      for (std::size_t k = 1; k < cut.points.size(); ++k) {
        const PlanPoint a = cut.points[k - 1], b = cut.points[k];
        if (std::max(a.X, b.X) + r < std::min(p.X, q.X) || std::min(a.X, b.X) - r > std::max(p.X, q.X) ||
            std::max(a.Y, b.Y) + r < std::min(p.Y, q.Y) || std::min(a.Y, b.Y) - r > std::max(p.Y, q.Y))
          continue;
        if (const auto t = closer_than(p, q, a, b, r))
          blocked.emplace_back(s[i - 1] + t->first * length, s[i - 1] + t->second * length);
      }
  }
  return blocked;
}

// The perforation cuts of one fold, and the runs outside the insets they were spaced along.
struct Perforation {
  std::vector<DrawnLine> lines;
  double runs_mm = 0;  // their total length
  int runs = 0;
};

// The perforation cuts of one fold polyline (arc lengths s) against the cut polylines.
Perforation perforate(const PlanPolyline& fold, const std::vector<double>& s, Layer layer,
                      std::span<const PlanPolyline> cuts, const FoldStyleOptions& options) {
  const double cut = options.perf_cut_mm, gap = options.perf_gap_mm;
  std::vector<Interval> runs = complement(near_cuts(fold, s, cuts, options.inset_mm), s.back());
  Perforation perforation;
  for (const auto& [from, to] : runs) {
    const double L = to - from;
    perforation.runs_mm += L;
    perforation.runs += 1;
    if (L < cut) {
      perforation.lines.push_back({layer, piece(fold.points, s, from, to), {}});
      continue;
    }
    const int n = std::max(1, static_cast<int>(std::floor((L + gap) / (cut + gap))));
    const double step = n > 1 ? cut + (L - n * cut) / (n - 1) : 0;
    const double start = n > 1 ? from : from + (L - cut) / 2;  // a single cut sits in the middle
    for (int k = 0; k < n; ++k) {
      const double a = start + k * step, b = k + 1 == n && n > 1 ? to : a + cut;  // the last ends on the run's end
      perforation.lines.push_back({layer, piece(fold.points, s, a, b), {}});
    }
  }
  // A stretch of the fold between two of its points (where other lines meet it) that the insets
  // block whole keeps one perforation, its middle third, or it would vanish from the plan and the
  // faces either side read as one: a reader parts a fold where a cut reaches its line (0.5 mm folds
  // between two cuts on the capitol; a valley's stretch with a cut 0.056 mm above it).
  for (std::size_t i = 1; i < s.size(); ++i)
    if (s[i] - s[i - 1] > kNegligible_mm &&
        std::ranges::none_of(runs, [&](const Interval& run) { return run.first < s[i] && run.second > s[i - 1]; })) {
      const double third = (s[i] - s[i - 1]) / 3;
      perforation.lines.push_back({layer, piece(fold.points, s, s[i - 1] + third, s[i] - third), {}});
      perforation.runs += 1;
    }
  return perforation;
}

}  // namespace

std::span<const double> fold_dash_pattern(LineKind fold) {
  return fold == LineKind::Mountain ? std::span<const double>(kMountainDash) : std::span<const double>(kValleyDash);
}

std::vector<DrawnLine> draw_fold(const PlanPolyline& fold, std::span<const PlanPolyline> cuts,
                                 const FoldStyleOptions& options) {
  const Layer layer = layer_of(fold.kind, options.style);
  const std::vector<double> s = arc_lengths(fold.points);
  if (options.style == FoldStyle::Score) return {{layer, fold.points, {}}};
  if (options.style == FoldStyle::Dashed) return {{layer, fold.points, fitted(fold_dash_pattern(fold.kind), s.back())}};
  return perforate(fold, s, layer, cuts, options).lines;
}

DrawnPlan draw_plan(const Plan& plan, const FoldStyleOptions& options) {
  check_fold_style(options);
  DrawnPlan drawn;
  drawn.style = options.style;
  std::vector<PlanPolyline> cuts;
  for (const PlanPolyline& line : plan.lines)
    if (is_cut(line.kind)) cuts.push_back(line);
  for (const PlanPolyline& line : plan.lines) {
    if (line.points.size() < 2) continue;
    const Layer layer = layer_of(line.kind, options.style);
    if (is_cut(line.kind)) {
      drawn.lines.push_back({layer, line.points, {}});
      continue;
    }
    const std::vector<double> s = arc_lengths(line.points);
    drawn.fold_mm += s.back();
    if (options.style != FoldStyle::Perforated) {
      drawn.lines.push_back(draw_fold(line, cuts, options).front());
      continue;
    }
    Perforation perforation = perforate(line, s, layer, cuts, options);
    for (DrawnLine& l : perforation.lines) {
      drawn.perforated_mm += arc_lengths(l.points).back();
      drawn.perforations += 1;
      drawn.lines.push_back(std::move(l));
    }
    drawn.inset_removed_mm += s.back() - perforation.runs_mm;
    drawn.perforated_runs += perforation.runs;
  }
  return drawn;
}

std::vector<std::vector<PlanPoint>> dash_pieces(const DrawnLine& line) {
  if (line.dash_mm.empty()) return {line.points};
  const std::vector<double> s = arc_lengths(line.points);
  const double total = s.back();
  std::vector<std::vector<PlanPoint>> pieces;
  double at = 0;
  for (std::size_t i = 0; at < total - kNegligible_mm; i = (i + 1) % line.dash_mm.size()) {
    // The fitted pattern ends on the line's end, up to rounding: the last dash ends exactly there.
    const double to = at + line.dash_mm[i] >= total - kNegligible_mm ? total : at + line.dash_mm[i];
    if (i % 2 == 0 && to - at > kNegligible_mm) pieces.push_back(piece(line.points, s, at, to));
    at = to;
  }
  return pieces;
}

void check_fold_style(const FoldStyleOptions& options) {
  for (const double v : {options.perf_cut_mm, options.perf_gap_mm})
    if (!(v >= 0.1 && v <= 50))
      throw InputError("FoldStyleOptions::perf_cut_mm/FoldStyleOptions::perf_gap_mm",
                       "the cut and gap lengths must each be between 0.1 and 50 mm, not " +
                       mm_text(options.perf_cut_mm) + "," + mm_text(options.perf_gap_mm));
  if (!(options.inset_mm >= 0 && options.inset_mm <= 50))
    throw InputError("FoldStyleOptions::inset_mm", "must be between 0 and 50 mm, not " + mm_text(options.inset_mm));
}

const char* fold_style_name(FoldStyle style) {
  switch (style) {
    case FoldStyle::Score:
      return "score";
    case FoldStyle::Perforated:
      return "perforated";
    case FoldStyle::Dashed:
      return "dashed";
  }
  return "score";
}

std::string fold_style_summary(const FoldStyleOptions& options) {
  std::string text = std::string("fold style ") + fold_style_name(options.style);
  if (options.style == FoldStyle::Perforated)
    text += " (cut " + mm_text(options.perf_cut_mm) + " mm, gap " + mm_text(options.perf_gap_mm) + " mm, inset " +
            mm_text(options.inset_mm) + " mm)";
  if (options.style == FoldStyle::Dashed) text += " (mountain dash-dot, valley dashed)";
  return text;
}

}  // namespace origamic

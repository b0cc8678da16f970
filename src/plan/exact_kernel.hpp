// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: the exact kernel shared by the translation units that build arrangements (exact_plan*.cpp
// through exact_plan_state.hpp; plan_analysis.cpp and tip_repair.cpp, with plan_analysis_geometry.cpp
// and plan_analysis_chords.cpp), and the one conversion of an exact number to the double written out.
#pragma once

// Exact numbers are never shared between threads; without this, every lazily evaluated number pays
// for a std::call_once (a futex system call on completion), which tripled the plan's time. Each
// including translation unit defines it first, so all agree. Threads may read the intervals of
// numbers made before them (approx(): a plain read) while none is made or evaluated exactly, as the
// strip widths' chord searches do (plan_analysis_chords.cpp).
#ifndef CGAL_HAS_NO_THREADS
#error "define CGAL_HAS_NO_THREADS before including exact_kernel.hpp"
#endif

#include <CGAL/Arr_consolidated_curve_data_traits_2.h>
#include <CGAL/Arr_extended_dcel.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

#include <bit>
#include <cstdint>
#include <type_traits>
#include <utility>

namespace origamic::exact {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using FT = Kernel::FT;
using Point = Kernel::Point_2;
using SegmentTraits = CGAL::Arr_segment_traits_2<Kernel>;
// Each inserted segment carries an index (into its caller's table of what the segment is);
// overlapping pieces keep every index. Each face carries one label.
using Traits = CGAL::Arr_consolidated_curve_data_traits_2<SegmentTraits, std::int32_t>;
using Dcel = CGAL::Arr_face_extended_dcel<Traits, std::int32_t>;
using Arrangement = CGAL::Arrangement_2<Traits, Dcel>;

// The exact rational behind a lazy number (gmpxx: store expressions in a typed variable before use).
using Rational = std::remove_cvref_t<decltype(std::declval<FT>().exact())>;

/// A coordinate as CGAL::to_double gives it, read off its interval without making a new lazy number
/// (as p.x() would): the interval's midpoint when it is tight, else the exact value's double.
inline double approx_coordinate(const Point& p, int i) {
  const CGAL::Interval_nt<false>& interval = i == 0 ? p.approx().x() : p.approx().y();
  double value;
  if (CGAL::fit_in_double(interval, value)) return value;
  if (CGAL::has_smaller_relative_precision(interval, FT::get_relative_precision_of_to_double()))
    return CGAL::to_double(interval);
  return CGAL::to_double(i == 0 ? p.x() : p.y());
}
inline double approx_x(const Point& p) { return approx_coordinate(p, 0); }
inline double approx_y(const Point& p) { return approx_coordinate(p, 1); }

/// The double nearest an exact rational (ties to even).
inline double nearest_double(const Rational& exact) {
  const auto [lo, hi] = CGAL::to_interval(exact);
  if (lo == hi) return lo + 0.0;
  const Rational mid = (Rational(lo) + Rational(hi)) / 2;  // typed: gmpxx expressions must not outlive their operands
  if (exact < mid) return lo;
  if (exact > mid) return hi;
  return (std::bit_cast<std::uint64_t>(lo) & 1) == 0 ? lo : hi;
}

/// The double nearest an exact number (ties to even), so a fold at Y = h - d reads back as the IEEE
/// difference h - d. CGAL's to_double may return any double within its interval instead.
inline double nearest_double(const FT& x) {
  if (const auto [lo, hi] = CGAL::to_interval(x); lo == hi) return lo + 0.0;  // most often; no -0
  return nearest_double(x.exact());
}

/// A point's x (i = 0) or y (i = 1) as nearest_double gives it, read off the point's interval where
/// that is a point (every vertex a file or the pixel lattice gave): no lazy number made, as p.x() would.
inline double nearest_coordinate(const Point& p, int i) {
  const CGAL::Interval_nt<false>& interval = i == 0 ? p.approx().x() : p.approx().y();
  if (interval.inf() == interval.sup()) return interval.inf() + 0.0;
  return nearest_double(i == 0 ? p.x() : p.y());
}

}  // namespace origamic::exact

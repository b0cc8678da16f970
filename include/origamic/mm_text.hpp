// SPDX-License-Identifier: GPL-3.0-or-later
// Millimetres as text in files and messages.
#pragma once

#include <cstdio>
#include <string>

namespace origamic {

/// Fixed decimals, trailing zeros dropped: 1e-6 mm keeps every exact value to far better than
/// 0.001 mm. "-0" is written "0".
inline std::string mm_text(double value) {
  char text[64];
  std::snprintf(text, sizeof text, "%.6f", value);
  std::string s = text;
  s.erase(s.find_last_not_of('0') + 1);
  if (s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  return s;
}

}  // namespace origamic

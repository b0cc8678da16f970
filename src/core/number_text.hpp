// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: a number as people write it in messages and files, the shortest of %g (6 significant
// digits: 200, 0.25, 1e+308), never "200.000000".
#pragma once

#include <cstdio>
#include <string>

namespace origamic {

inline std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

}  // namespace origamic

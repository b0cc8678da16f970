// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: OpenMesh reports through global streams (a refused face, every file read or written);
// while one of these lives, its chatter stays off the user's terminal.
#pragma once

#include <OpenMesh/Core/System/omstream.hh>

namespace origamic {

struct QuietOpenMesh {
  QuietOpenMesh() {
    omerr().disable();
    omlog().disable();
    omout().disable();
  }
  ~QuietOpenMesh() {
    omerr().enable();
    omlog().enable();
    omout().enable();
  }
  QuietOpenMesh(const QuietOpenMesh&) = delete;
  QuietOpenMesh& operator=(const QuietOpenMesh&) = delete;
};

}  // namespace origamic

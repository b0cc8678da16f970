// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace origamic {

/// std::allocator, except that a value made without arguments is default-initialised: a trivial
/// one is left unwritten. An array made so (a grid made Grid::unfilled, the corner normals) is first
/// touched by the loop that fills it, on every core, not by a fill of zeros first (fresh memory costs
/// about 3 ms/MB to touch on the 2-core machine: the 45-degree maps' grids took 48-102 ms to fill
/// before their rays were shot).
template <class T>
struct DefaultInitAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() = default;
  template <class U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    std::construct_at(p, std::forward<Args>(args)...);
  }
};

/// A vector whose resize leaves trivial values unwritten, for a loop (often parallel) that writes
/// every one.
template <class T>
using UnfilledVector = std::vector<T, DefaultInitAllocator<T>>;

}  // namespace origamic

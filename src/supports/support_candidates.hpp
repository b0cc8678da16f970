// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: the candidate supports of a round (seed §4.4, a few per ray: the first faces a support
// can fold onto), from the top and bottom edges of the faces, one per W-wide block column, each with
// its cost and the faces it would cut in two. support_choice.cpp chooses among them.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "support_choice.hpp"
#include "support_picture.hpp"

namespace origamic {

class CandidateFinder {
 public:
  // Candidates will be asked of the faces in `wanted` only. The round and the picture outlive it.
  CandidateFinder(const SupportRound& round, const std::vector<std::int32_t>& wanted, const SupportPicture& picture,
                  SupportReach reach);
  ~CandidateFinder();

  // Whether support s, as it is now (widened), cuts face x in two.
  bool cuts(std::int32_t x, const Candidate& s) const;
  // Whether face x, less support s and the supports `with`, falls into more pieces than less `with`
  // alone: two supports side by side, touching, may each leave a face whole and together part it.
  // False where none of `with` lies over x's box (s alone: its own `cuts`).
  bool cuts_with(std::int32_t x, std::span<const PixelRect> with, const PixelRect& s) const;

  // Candidates from the top (up = true) or bottom edge of face f, one per W-wide block column that
  // f fills on that edge. Thread-safe: the search reads the round, and each thread keeps its own
  // caches.
  std::vector<Candidate> from_edge(std::int32_t f, bool up) const;

 private:
  class Search;
  std::unique_ptr<const Search> search_;
};

/// The candidates of both edges of the faces, found in parallel, then taken in order; a support
/// that cuts the face it holds, or the one it reaches, in two holds nothing, nor (unless
/// split_faces) one that cuts a third face.
std::vector<Candidate> candidates_of(const CandidateFinder& finder, const std::vector<std::int32_t>& faces,
                                     bool split_faces);

}  // namespace origamic

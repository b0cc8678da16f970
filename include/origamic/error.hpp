// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <stdexcept>
#include <string>

namespace origamic {

/// A user's mistake: a bad input file or option, in one line; the command-line tool prints it and
/// exits with status 2. A file's problem names the file in its message. An option's names the option
/// as the library has it, in `field`: a member of the options a call takes ("RasterOptions::px_per_mm",
/// "Sheet"; several joined by '/' where they are at fault together), and what() is "FIELD: PROBLEM".
/// The command-line tool names its flag instead.
struct InputError : std::invalid_argument {
  explicit InputError(const std::string& message) : std::invalid_argument(message), problem(message) {}
  InputError(const std::string& field_name, const std::string& problem_text)
      : std::invalid_argument(field_name + ": " + problem_text), field(field_name), problem(problem_text) {}

  std::string field;    // the option at fault; empty for a file's problem
  std::string problem;  // what is wrong, without the field
};

/// An output file or folder that cannot be written. Reported like an InputError.
struct OutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace origamic

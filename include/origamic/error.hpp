// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <stdexcept>
#include <string>

namespace origamic {

/// A user's mistake: a bad input file or option. The message is one line that names the file or
/// option and the problem; the command-line tool prints it and exits with status 2.
struct InputError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

/// An output file or folder that cannot be written. Reported like an InputError.
struct OutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace origamic

// SPDX-License-Identifier: GPL-3.0-or-later
// The origamic command: parses the command line, runs one subcommand (commands.hpp), reports its
// errors. No algorithm lives here.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <map>
#include <new>
#include <numeric>
#include <string>
#include <string_view>
#include <vector>

#include "commands.hpp"
#include "origamic/error.hpp"
#include "origamic/version.hpp"

namespace origamic::cli {

namespace {

// The library names an option at fault by its field (InputError::field); the command line by its
// flag. Fields joined by '/' are at fault together; each becomes its flag, once.
std::string flags_of(const std::string& fields) {
  static const std::map<std::string, std::string> flag = {
      {"Sheet", "--card"},
      {"PlacementOptions::rotate_deg", "--rotate"},
      {"PlacementOptions::scale", "--scale"},
      {"PlacementOptions::offset_mm", "--offset"},
      {"PlacementOptions::margin_mm", "--margin"},
      {"RasterOptions::px_per_mm", "--px-per-mm"},
      {"SliceOptions::min_strip_mm", "--min-strip"},
      {"AnalysisOptions::min_strip_mm", "--min-strip"},
      {"AnalysisOptions::tolerance_mm", "--tolerance"},
      {"FoldStyleOptions::perf_cut_mm", "--perf"},
      {"FoldStyleOptions::perf_gap_mm", "--perf"},
      {"FoldStyleOptions::inset_mm", "--fold-inset"},
      {"ExportOptions::paper", "--paper"},
      {"ExportOptions::pdf_date_s", "SOURCE_DATE_EPOCH"},
      {"FoldOptions::angle_deg", "--angle"},
      {"FoldOptions::thickness_mm", "--thickness"},
      {"RenderOptions::width_px", "--render-size"},
      {"RenderOptions::height_px", "--render-size"},
  };
  std::string flags;
  for (std::size_t at = 0; at <= fields.size();) {
    const std::size_t end = std::min(fields.find('/', at), fields.size());
    const std::string field = fields.substr(at, end - at);
    const auto known = flag.find(field);
    const std::string name = known != flag.end() ? known->second : field;  // a field no flag sets
    if (flags != name && !flags.ends_with("/" + name)) flags += (flags.empty() ? "" : "/") + name;
    at = end + 1;
  }
  return flags;
}

}  // namespace

// An InputError as the command line says it: the flag for the library's field, the plan's file for
// its lines.
std::string cli_message(const InputError& e, const std::string& plan_file) {
  if (e.field.empty()) return e.what();
  if (e.field == "lines" && !plan_file.empty()) return plan_file + ": " + e.problem;
  return flags_of(e.field) + ": " + e.problem;
}

// An error as one line of plain text: a name or layer read from a file may hold a newline, a tab or
// a terminal escape, which are shown as \xNN instead.
std::string one_line(std::string_view message) {
  std::string line;
  for (const char c : message) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", byte);
      line += escaped;
    } else {
      line += c;
    }
  }
  return line;
}

namespace {

void print_error(std::string_view prefix, std::string_view message, std::string_view suffix = "") {
  std::fprintf(stderr, "origamic: %s%s%s\n", std::string(prefix).c_str(), one_line(message).c_str(),
               std::string(suffix).c_str());
}

// Edits (insertions, deletions, substitutions) between two words: the nearest name is suggested.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  std::iota(row.begin(), row.end(), std::size_t{0});
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0]++;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// "; did you mean X?" for the nearest of `names` within a third of the word's length, or "".
std::string suggestion(std::string_view word, const std::vector<std::string>& names) {
  const std::string* best = nullptr;
  std::size_t fewest = word.size() / 3 + 1;
  for (const std::string& name : names)
    if (const std::size_t d = edit_distance(word, name); d < fewest) fewest = d, best = &name;
  return best ? "; did you mean " + *best + "?" : "";
}

// A parse error in words a user can act on, naming the option and the help that lists it.
std::string parse_problem(const CLI::ParseError& e, const CLI::App& app, int argc, char** argv) {
  const CLI::App* used = nullptr;
  for (const CLI::App* sub : app.get_subcommands({})) if (sub->parsed()) used = sub;
  const std::string help = used ? " (see origamic " + used->get_name() + " --help)" : " (see origamic --help)";
  const std::string message = e.what();
  if (dynamic_cast<const CLI::ExtrasError*>(&e) && used) {
    std::vector<std::string> names;
    for (const CLI::Option* option : used->get_options())
      for (const std::string& long_name : option->get_lnames()) names.push_back("--" + long_name);
    for (int i = 2; i < argc; ++i) {
      const std::string_view word = argv[i];
      if (word.rfind("--", 0) != 0) continue;
      const std::string name(word.substr(0, word.find('=')));
      if (std::ranges::find(names, name) == names.end())
        return name + ": no such option of origamic " + used->get_name() + suggestion(name, names) + help;
    }
  }
  // CLI11 says "Could not convert: --angle = abc".
  if (const auto at = message.find("Could not convert: "); at != std::string::npos) {
    const std::string rest = message.substr(at + 19);
    if (const auto equals = rest.find(" = "); equals != std::string::npos)
      return rest.substr(0, equals) + ": '" + rest.substr(equals + 3) + "' is not a number" + help;
  }
  return message + help;
}

}  // namespace

}  // namespace origamic::cli

int main(int argc, char** argv) {
  using namespace origamic::cli;  // the subcommands and the words of their errors
  CLI::App app{"origamic: Origamic Architecture pop-up plans from 3D models", "origamic"};
  app.set_version_flag("--version,-V", std::string("origamic ") + origamic::version);
  app.require_subcommand(1);
  DesignArgs design_args;
  CLI::App* design = app.add_subcommand("design", "design a pop-up plan for a 3D model");
  add_design_options(*design, design_args);
  FabricationArgs fabrication_args;
  add_fabrication_options(*design, fabrication_args);
  PopupArgs popup_args;
  add_popup_options(*design, popup_args);
  ValidateArgs validate_args;
  CLI::App* validate = app.add_subcommand("validate", "check a plan (DXF), made by origamic or by hand: faces, folds, "
                                                      "validity; exit 0 valid, 3 invalid");
  add_validate_options(*validate, validate_args);
  FoldArgs fold_args;
  CLI::App* fold = app.add_subcommand("fold", "fold a plan (DXF) into its 3D pop-up at an opening angle: a mesh");
  add_fold_options(*fold, fold_args);

  // The first word names a command; `help` asks for the help, as --help does.
  if (argc >= 2 && argv[1][0] != '-') {
    const std::string word = argv[1];
    const std::vector<std::string> commands = {"design", "validate", "fold"};
    if (word == "help") {
      std::fputs(app.help().c_str(), stdout);
      return 0;
    }
    if (std::ranges::find(commands, word) == commands.end()) {
      print_error("", "unknown command '" + word + "'" + suggestion(word, commands),
                  " (the commands are design, validate and fold; see origamic --help)");
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    print_error("", parse_problem(e, app, argc, argv));
    return 2;
  }

  try {
    if (*validate) return run_validate(validate_args);
    if (*fold) return run_fold(fold_args);
    if (*design) return run_design(design_args, fabrication_args, popup_args);
    return 2;  // CLI11 requires one subcommand
  } catch (const origamic::InputError& e) {
    print_error("", cli_message(e));
    return 2;
  } catch (const origamic::OutputError& e) {
    print_error("", e.what());
    return 2;
  } catch (const std::filesystem::filesystem_error& e) {
    print_error("", e.what());
    return 2;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "origamic: out of memory\n");
    return 2;
  } catch (const std::exception& e) {
    print_error("internal error: ", e.what());
    return 2;
  }
}

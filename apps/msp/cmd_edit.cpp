// msp edit SPLINE.msp (--move-region X Y Z RADIUS DX DY DZ | --move-point INDEX DX DY DZ)...
//          -o EDITED.msp [--json]: moves control points of a spline file (spline/surface/edit.h)
// and writes the edited file. Moves apply in command-line order; the report (text, or one JSON
// object with --json) says how many control points moved, over how many domain faces the
// surface changed and which fill patches now miss the surface (they are not refitted).
#include <algorithm>
#include <chrono>
#include <iostream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include <ricci/mesh/errors.h>
#include <spline/io/spline_file.h>
#include <spline/surface/edit.h>

#include "msp/cli.h"
#include "msp/commands.h"

namespace msp {
namespace {

const char* kUsage =
    "msp edit SPLINE.msp [--move-region X Y Z RADIUS DX DY DZ]... "
    "[--move-point INDEX DX DY DZ]... -o EDITED.msp [--json]";

struct Move {
  std::string option;          // "move-region" or "move-point"
  std::vector<double> values;  // 7 or 4 numbers
};

double parse_number(const std::string& text, const std::string& option) {
  try {
    std::size_t used = 0;
    const double x = std::stod(text, &used);
    if (used == text.size()) return x;
  } catch (const std::exception&) {
  }
  throw UsageError("option --" + option + " expects numbers, got '" + text + "'");
}

// Takes the multi-value options out of argv (Args gives each option one value); the rest is
// left for Args.
std::vector<Move> take_moves(int argc, char** argv, std::vector<char*>& rest) {
  std::vector<Move> moves;
  for (int i = 0; i < argc; ++i) {
    const std::string a = argv[i];
    const int count = a == "--move-region" ? 7 : a == "--move-point" ? 4 : 0;
    if (count == 0) {
      rest.push_back(argv[i]);
      continue;
    }
    Move move{a.substr(2), {}};
    if (i + count >= argc) {
      throw UsageError("option " + a + " needs " + std::to_string(count) + " numbers");
    }
    for (int k = 1; k <= count; ++k) move.values.push_back(parse_number(argv[i + k], move.option));
    i += count;
    moves.push_back(move);
  }
  return moves;
}

spline::EditReport apply(spline::SplineSurface& surface, const Move& move) {
  const std::vector<double>& v = move.values;
  if (move.option == "move-region") {
    return spline::move_region(surface, {v[0], v[1], v[2]}, v[3], {v[4], v[5], v[6]});
  }
  if (v[0] != static_cast<double>(static_cast<long long>(v[0]))) {
    throw UsageError("option --move-point expects an integer index, got " + std::to_string(v[0]));
  }
  return spline::move_control_points(surface, {static_cast<int>(v[0])}, {{v[1], v[2], v[3]}});
}

}  // namespace

int run_edit(int argc, char** argv) {
  std::vector<char*> rest;
  const std::vector<Move> moves = take_moves(argc, argv, rest);
  Args args(static_cast<int>(rest.size()), rest.data(), {"json"});
  args.require_known({"output", "json"});
  args.require_positionals(1, kUsage);
  const auto output = args.get("output");
  if (!output) throw UsageError("-o EDITED.msp is required; usage: " + std::string(kUsage));
  if (moves.empty()) {
    throw UsageError("give --move-region or --move-point; usage: " + std::string(kUsage));
  }
  const std::string& input = args.positionals()[0];
  const auto start = std::chrono::steady_clock::now();
  spline::SplineFile file = spline::read_spline_file(input);  // throws: main() reports it
  std::set<int> moved, affected, fills, open_rims;
  double max_displacement = 0.0;
  for (const Move& move : moves) {
    const spline::EditReport report = apply(file.surface, move);
    moved.insert(report.moved_functions.begin(), report.moved_functions.end());
    affected.insert(report.affected_faces.begin(), report.affected_faces.end());
    fills.insert(report.touched_fills.begin(), report.touched_fills.end());
    open_rims.insert(report.touched_open_rims.begin(), report.touched_open_rims.end());
    max_displacement = std::max(max_displacement, report.max_displacement);
  }
  spline::SplineFileProvenance provenance = file.header.provenance;
  provenance["edited_by"] = "msp edit";
  spline::save_spline_surface(file.surface, *output, provenance);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (args.has("json")) {
    nlohmann::ordered_json json = {{"input", input},
                                   {"output", *output},
                                   {"moves", moves.size()},
                                   {"moved_control_points", moved.size()},
                                   {"max_displacement", max_displacement},
                                   {"affected_faces", affected.size()},
                                   {"touched_fills", fills},
                                   {"touched_open_rims", open_rims},
                                   {"seconds", seconds}};
    std::cout << json.dump(2) << "\n";
  } else {
    std::cout << "moved " << moved.size() << " control points (largest move " << max_displacement
              << ") over " << affected.size() << " domain faces; " << fills.size()
              << " fill patches touched (not refitted); wrote " << *output << "\n";
  }
  return 0;
}

}  // namespace msp

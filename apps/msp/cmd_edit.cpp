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

struct Move {
  std::string option;          // "move-region" or "move-point"
  std::vector<double> values;  // 7 or 4 numbers
};

// The moves in command-line order (Args has checked how many values each one has).
std::vector<Move> moves_of(const Args& args) {
  std::vector<Move> moves;
  for (const auto& occurrence : args.occurrences()) {
    if (occurrence.name != "move-region" && occurrence.name != "move-point") continue;
    Move move{occurrence.name, {}};
    for (const auto& v : occurrence.values) {
      move.values.push_back(parse_double(v, "option --" + move.option));
    }
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

const CommandSpec& edit_command() {
  static const CommandSpec spec{
      "edit",
      "move control points of a spline file (.msp): by index or a region",
      {{"SPLINE.msp", "the spline file to edit"}},
      {{"move-region", "X Y Z RADIUS DX DY DZ",
        "move the control points within RADIUS of (X, Y, Z) by (DX, DY, DZ), weighted by a "
        "smooth falloff",
        false, true},
       {"move-point", "INDEX DX DY DZ", "move control point INDEX by (DX, DY, DZ)", false, true},
       {"output", "EDITED.msp", "write the edited spline file", true},
       json_option(),
       quiet_option()}};
  return spec;
}

int run_edit(int argc, char** argv) {
  const Args args(argc, argv, edit_command());
  const std::vector<Move> moves = moves_of(args);
  const auto output = args.get("output");  // required: Args has checked it
  if (moves.empty()) {
    throw UsageError("give --move-region or --move-point (msp edit --help describes the "
                     "command line)");
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

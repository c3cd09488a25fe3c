// msp eval SPLINE.msp (--points P.csv | --closest Q.xyz) [--json]: the surface of a spline file
// at domain points, or at the closest points to points in space (spline/surface/evaluate.h,
// closest_point.h): position, first and second derivatives, unit normal, Gaussian and mean
// curvature. P.csv: one point per line, "face, b0, b1, b2" (the face's barycentric coordinates;
// commas or blanks); Q.xyz: "x y z" per line; empty lines and lines starting with '#' are
// skipped. Text output: one line per point; --json: one object with every point.
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include <ricci/mesh/errors.h>
#include <spline/io/spline_file.h>
#include <spline/surface/closest_point.h>
#include <spline/surface/evaluate.h>

#include "msp/cli.h"
#include "msp/commands.h"
#include "msp/surface_json.h"

namespace msp {
namespace {

// The numbers of each data line of a text file (commas count as blanks), `count` per line.
std::vector<std::vector<double>> read_rows(const std::string& path, std::size_t count) {
  std::ifstream in(path);
  if (!in) throw ricci::IOError(path + ": cannot be read");
  std::vector<std::vector<double>> rows;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    for (char& c : line)
      if (c == ',' || c == ';' || c == '\t' || c == '\r') c = ' ';
    const auto first = line.find_first_not_of(' ');
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    std::vector<double> row;
    std::string field;
    while (fields >> field) {
      std::size_t used = 0;
      double x = 0.0;
      try {
        x = std::stod(field, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != field.size()) {
        throw ricci::InvalidInputError(path + ":" + std::to_string(number) + ": '" + field +
                                       "' is not a number");
      }
      row.push_back(x);
    }
    if (row.size() != count) {
      throw ricci::InvalidInputError(path + ":" + std::to_string(number) + ": expected " +
                                     std::to_string(count) + " numbers, got " +
                                     std::to_string(row.size()));
    }
    rows.push_back(row);
  }
  if (rows.empty()) throw ricci::InvalidInputError(path + ": no points");
  return rows;
}

std::vector<spline::DomainPoint> domain_points(const std::string& path) {
  std::vector<spline::DomainPoint> points;
  int number = 0;
  for (const auto& row : read_rows(path, 4)) {
    ++number;
    if (row[0] != static_cast<double>(static_cast<long long>(row[0])) || row[0] < 0 ||
        row[0] > 2e9) {
      throw ricci::InvalidInputError(path + ": point " + std::to_string(number) +
                                     ": the face must be a non-negative integer");
    }
    points.push_back({static_cast<int>(row[0]), {row[1], row[2], row[3]}});
  }
  return points;
}

std::string text_line(const spline::SurfaceDifferential& d) {
  std::ostringstream line;
  line.precision(17);
  if (d.location.fill >= 0) {
    line << "fill " << d.location.fill << " (" << d.location.fill_parameter.x() << ", "
         << d.location.fill_parameter.y() << ")";
  } else {
    const Eigen::Vector3d& b = d.location.point.barycentric;
    line << "face " << d.location.point.face << " (" << b.x() << ", " << b.y() << ", " << b.z()
         << ")";
  }
  line << " position " << d.position.x() << " " << d.position.y() << " " << d.position.z()
       << " normal " << d.normal.x() << " " << d.normal.y() << " " << d.normal.z() << " K "
       << d.curvature.gaussian << " H " << d.curvature.mean;
  return line.str();
}

}  // namespace

const CommandSpec& eval_command() {
  static const CommandSpec spec{
      "eval",
      "evaluate a spline file: position, derivatives, normal, curvatures (points, closest points)",
      {{"SPLINE.msp", "the spline file to evaluate"}},
      {{"points", "P.csv",
        "evaluate at domain points, one \"face, b0, b1, b2\" per line (one of --points, "
        "--closest)"},
       {"closest", "Q.xyz", "evaluate at the surface points closest to \"x y z\" per line"},
       json_option(),
       quiet_option()}};
  return spec;
}

int run_eval(int argc, char** argv) {
  const Args args(argc, argv, eval_command());
  const auto points_path = args.get("points");
  const auto closest_path = args.get("closest");
  if (points_path.has_value() == closest_path.has_value()) {
    throw UsageError("give one of --points or --closest (msp eval --help describes the "
                     "command line)");
  }
  const std::string& input = args.positionals()[0];
  const spline::SplineSurface surface = spline::load_spline_surface(input);
  nlohmann::json out = nlohmann::json::array();
  if (points_path) {
    const std::vector<spline::DomainPoint> points = domain_points(*points_path);
    for (const auto& d : spline::evaluate_surface(surface, points)) {
      if (args.has("json")) {
        out.push_back(differential_json(d));
      } else {
        std::cout << text_line(d) << "\n";
      }
    }
  } else {
    const auto rows = read_rows(*closest_path, 3);
    Eigen::MatrixX3d targets(static_cast<Eigen::Index>(rows.size()), 3);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      targets.row(static_cast<Eigen::Index>(i)) << rows[i][0], rows[i][1], rows[i][2];
    }
    const spline::ClosestPointIndex index(surface);
    const std::vector<spline::ClosestPoint> found = index.find_all(targets);
    for (std::size_t i = 0; i < found.size(); ++i) {
      const spline::SurfaceDifferential d = spline::evaluate_surface(surface, found[i].location);
      if (args.has("json")) {
        nlohmann::json p = differential_json(d);
        p["target"] = {rows[i][0], rows[i][1], rows[i][2]};
        p["distance"] = found[i].distance;
        out.push_back(p);
      } else {
        std::cout << "distance " << found[i].distance << " " << text_line(d) << "\n";
      }
    }
  }
  if (args.has("json")) {
    const nlohmann::ordered_json json = {{"spline", input}, {"points", out}};
    std::cout << json.dump(2) << "\n";
  }
  return 0;
}

}  // namespace msp

// The spline file's atlas section, knot clouds and control points (spline_file_detail.h).
#include <cmath>
#include <limits>
#include <string>

#include "ricci/topology/slice.h"
#include "spline/io/spline_file_detail.h"

namespace spline::io_detail {
namespace {

std::string str(std::size_t value) { return std::to_string(value); }

void write_ints(ByteWriter& out, const std::vector<int>& values) {
  out.count(values.size());
  for (int v : values) out.i32(v);
}

// Indices in [lo, hi); strictly ascending when `ascending`.
std::vector<int> read_ints(ByteReader& in, int lo, int hi, bool ascending,
                           const std::string& what) {
  std::vector<int> values(in.count(4, what));
  for (std::size_t i = 0; i < values.size(); ++i) {
    values[i] = in.i32();
    if (values[i] < lo || values[i] >= hi) {
      in.invalid(what + " [" + str(i) + "] = " + std::to_string(values[i]) + " is outside [" +
                 std::to_string(lo) + ", " + std::to_string(hi) + ")");
    }
    if (ascending && i > 0 && values[i] <= values[i - 1]) {
      in.invalid(what + " are not strictly ascending at [" + str(i) + "]");
    }
  }
  return values;
}

double read_finite(ByteReader& in, const std::string& what) {
  const double value = in.f64();
  if (!std::isfinite(value)) in.invalid(what + " is not finite");
  return value;
}

void write_chart(ByteWriter& out, const ricci::Chart& chart) {
  out.u8(static_cast<std::uint8_t>(chart.kind));
  out.i32(chart.source);
  write_ints(out, chart.faces);
  for (std::size_t r = 0; r < chart.faces.size(); ++r) {
    for (int k = 0; k < 3; ++k) out.i32(chart.corners(static_cast<Eigen::Index>(r), k));
  }
  write_ints(out, chart.to_original_vertex);
  for (Eigen::Index v = 0; v < chart.positions.rows(); ++v) {
    out.f64(chart.positions(v, 0));
    out.f64(chart.positions(v, 1));
  }
}

ricci::Chart read_chart(ByteReader& in, const FaceCorners& corners, int vertex_count,
                        const std::string& what) {
  ricci::Chart chart;
  const std::uint8_t kind = in.u8();
  if (kind > static_cast<std::uint8_t>(ricci::ChartKind::face)) {
    in.invalid(what + " has an unknown kind " + std::to_string(kind));
  }
  chart.kind = static_cast<ricci::ChartKind>(kind);
  chart.source = in.i32();
  const int face_count = static_cast<int>(corners.size());
  chart.faces = read_ints(in, 0, face_count, true, what + " faces");
  const auto rows = static_cast<Eigen::Index>(chart.faces.size());
  if (in.remaining() / 12 < chart.faces.size()) {
    in.fail("inconsistent counts: " + what + "'s corners do not fit in its section");
  }
  chart.corners.resize(rows, 3);
  for (Eigen::Index r = 0; r < rows; ++r) {
    for (int k = 0; k < 3; ++k) chart.corners(r, k) = in.i32();
  }
  chart.to_original_vertex = read_ints(in, 0, vertex_count, false, what + " vertices");
  const auto copies = static_cast<Eigen::Index>(chart.to_original_vertex.size());
  if (in.remaining() / 16 < chart.to_original_vertex.size()) {
    in.fail("inconsistent counts: " + what + "'s positions do not fit in its section");
  }
  chart.positions.resize(copies, 2);
  for (Eigen::Index v = 0; v < copies; ++v) {
    chart.positions(v, 0) = read_finite(in, what + " position " + str(v));
    chart.positions(v, 1) = read_finite(in, what + " position " + str(v));
  }
  for (Eigen::Index r = 0; r < rows; ++r) {
    const int face = chart.faces[r];
    for (int k = 0; k < 3; ++k) {
      const int copy = chart.corners(r, k);
      if (copy < 0 || copy >= copies) {
        in.invalid(what + " face " + std::to_string(face) + " has corner " + std::to_string(copy) +
                   " outside its " + str(copies) + " vertices");
      }
      if (chart.to_original_vertex[copy] != corners[face][k]) {
        in.invalid(what + " face " + std::to_string(face) + " corner " + std::to_string(k) +
                   " is not the mesh face's vertex");
      }
    }
  }
  return chart;
}

}  // namespace

FaceCorners face_corners(const ricci::Mesh& mesh) {
  FaceCorners corners(mesh.n_faces());
  for (auto f : mesh.faces()) {
    const auto hs = ricci::face_halfedges(mesh, f);
    for (int k = 0; k < 3; ++k) corners[f.idx()][k] = mesh.to_vertex_handle(hs[k]).idx();
  }
  return corners;
}

void write_atlas(ByteWriter& out, const ricci::AffineAtlas& atlas) {
  out.u8(atlas.root_is_cone ? 1 : 0);
  out.i32(atlas.uncovered_faces);
  for (double x : {atlas.root_curvature, atlas.domain_diameter,
                   atlas.domain_max_relative_length_error, atlas.domain_max_absolute_length_error,
                   atlas.max_transition_residual, atlas.max_side_pairing_residual,
                   atlas.relator_holonomy_angle, atlas.relator_holonomy_translation}) {
    out.f64(x);
  }
  out.count(atlas.in_domain.size());
  for (char c : atlas.in_domain) out.u8(c ? 1 : 0);
  write_ints(out, atlas.neighbourhood_chart);
  out.count(atlas.charts.size());
  for (const ricci::Chart& chart : atlas.charts) write_chart(out, chart);
  out.count(atlas.transitions.size());
  for (const ricci::Transition& t : atlas.transitions) {
    out.i32(t.chart_a);
    out.i32(t.chart_b);
    out.f64(t.motion.angle);
    out.vec2(t.motion.translation);
    out.f64(t.residual);
    write_ints(out, t.faces);
  }
  out.count(atlas.face_transitions.size());
  for (const auto& list : atlas.face_transitions) write_ints(out, list);
}

ricci::AffineAtlas read_atlas(ByteReader& in, const FaceCorners& corners, int vertex_count) {
  ricci::AffineAtlas atlas;
  const int faces = static_cast<int>(corners.size());
  const std::uint8_t cone = in.u8();
  if (cone > 1) in.invalid("root_is_cone is " + std::to_string(cone));
  atlas.root_is_cone = cone != 0;
  atlas.uncovered_faces = in.i32();
  atlas.root_curvature = read_finite(in, "root curvature");
  atlas.domain_diameter = read_finite(in, "domain diameter");
  if (!(atlas.domain_diameter > 0.0)) in.invalid("the domain diameter is not positive");
  atlas.domain_max_relative_length_error = in.f64();
  atlas.domain_max_absolute_length_error = in.f64();
  atlas.max_transition_residual = in.f64();
  atlas.max_side_pairing_residual = in.f64();
  atlas.relator_holonomy_angle = in.f64();
  atlas.relator_holonomy_translation = in.f64();
  if (in.count(1, "domain flags") != corners.size()) {
    in.fail("inconsistent counts: the domain mask does not have one flag per face");
  }
  atlas.in_domain.resize(corners.size());
  for (char& c : atlas.in_domain) {
    const std::uint8_t flag = in.u8();
    if (flag > 1) in.invalid("a domain flag is " + std::to_string(flag));
    c = static_cast<char>(flag);
  }
  // Checked against the chart count once the charts are read.
  atlas.neighbourhood_chart =
      read_ints(in, -1, std::numeric_limits<int>::max(), false, "neighbourhood charts");
  if (atlas.neighbourhood_chart.size() != corners.size()) {
    in.fail("inconsistent counts: the neighbourhood charts do not have one entry per face");
  }
  atlas.charts.resize(in.count(21, "charts"));  // kind, source, two empty lists
  if (atlas.charts.empty()) in.invalid("there are no charts");
  for (std::size_t c = 0; c < atlas.charts.size(); ++c) {
    atlas.charts[c] = read_chart(in, corners, vertex_count, "chart " + str(c));
  }
  const int chart_count = static_cast<int>(atlas.charts.size());
  for (int f = 0; f < faces; ++f) {
    const int chart = atlas.neighbourhood_chart[f];
    if (chart >= chart_count || (chart >= 0 && atlas.charts[chart].slot(f) < 0)) {
      in.invalid("the neighbourhood chart " + std::to_string(chart) + " of face " +
                 std::to_string(f) + " does not hold it");
    }
  }
  atlas.transitions.resize(in.count(48, "transitions"));
  for (std::size_t t = 0; t < atlas.transitions.size(); ++t) {
    ricci::Transition& tr = atlas.transitions[t];
    const std::string what = "transition " + str(t);
    tr.chart_a = in.i32();
    tr.chart_b = in.i32();
    if (tr.chart_a < 0 || tr.chart_a >= tr.chart_b || tr.chart_b >= chart_count) {
      in.invalid(what + " joins charts " + std::to_string(tr.chart_a) + " and " +
                 std::to_string(tr.chart_b) + " (needs 0 <= a < b < " +
                 std::to_string(chart_count) + ")");
    }
    tr.motion.angle = read_finite(in, what + " angle");
    tr.motion.translation.x() = read_finite(in, what + " translation");
    tr.motion.translation.y() = read_finite(in, what + " translation");
    tr.residual = in.f64();
    tr.faces = read_ints(in, 0, faces, true, what + " faces");
  }
  const std::size_t lists = in.count(8, "face transition lists");
  if (lists != corners.size()) {
    in.fail("inconsistent counts: " + str(lists) + " face transition lists for " + str(faces) +
            " faces");
  }
  atlas.face_transitions.resize(lists);
  const int transition_count = static_cast<int>(atlas.transitions.size());
  for (std::size_t f = 0; f < lists; ++f) {
    atlas.face_transitions[f] =
        read_ints(in, 0, transition_count, false, "transitions of face " + str(f));
  }
  return atlas;
}

void write_clouds(ByteWriter& out, const std::vector<KnotCloud>& clouds) {
  out.count(clouds.size());
  for (const KnotCloud& cloud : clouds) {
    out.u32(static_cast<std::uint32_t>(cloud.knots.size()));
    for (const Eigen::Vector2d& knot : cloud.knots) out.vec2(knot);
  }
}

std::vector<KnotCloud> read_clouds(ByteReader& in) {
  std::vector<KnotCloud> clouds(in.count(4, "knot clouds"));
  for (std::size_t v = 0; v < clouds.size(); ++v) {
    const std::uint32_t knots = in.u32();
    if (knots > static_cast<std::uint32_t>(kMaxDmsDegree + 1)) {
      in.invalid("knot cloud " + str(v) + " has " + std::to_string(knots) + " knots (at most " +
                 std::to_string(kMaxDmsDegree + 1) + ")");
    }
    clouds[v].knots.resize(knots);
    for (Eigen::Vector2d& knot : clouds[v].knots) {
      knot = in.vec2();
      if (!knot.allFinite()) in.invalid("knot cloud " + str(v) + " has a non-finite knot");
    }
  }
  return clouds;
}

void write_points(ByteWriter& out, const Eigen::MatrixX3d& points) {
  out.count(static_cast<std::size_t>(points.rows()));
  for (Eigen::Index r = 0; r < points.rows(); ++r) out.vec3(points.row(r).transpose());
}

Eigen::MatrixX3d read_points(ByteReader& in, Eigen::Index expected_rows, const std::string& what) {
  const auto rows = static_cast<Eigen::Index>(in.count(24, what + "s"));
  if (rows != expected_rows) {
    in.fail("inconsistent counts: " + std::to_string(rows) + " " + what + "s for " +
            std::to_string(expected_rows) + " functions");
  }
  Eigen::MatrixX3d points(rows, 3);
  for (Eigen::Index r = 0; r < rows; ++r) {
    points.row(r) = in.vec3().transpose();
    if (!points.row(r).allFinite()) {
      in.invalid(what + " " + std::to_string(r) + " is not finite");
    }
  }
  return points;
}

}  // namespace spline::io_detail

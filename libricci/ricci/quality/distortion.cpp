#include "ricci/quality/distortion.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "ricci/mesh/errors.h"
#include "ricci/util/parallel.h"

namespace ricci {
namespace {

using Lengths3 = std::array<double, 3>;  // l[k] = length of the edge opposite corner k

Lengths3 face_lengths(const Mesh& mesh, const Eigen::VectorXd& lengths, FaceHandle f) {
  Lengths3 l{};
  int k = 0;
  for (auto h : mesh.fh_range(f)) {
    // Halfedge h runs from corner k to corner k+1, so it is opposite corner k+2.
    l[(k + 2) % 3] = lengths[mesh.edge_handle(h).idx()];
    ++k;
  }
  return l;
}

// Corner angle opposite side a in a triangle with sides a, b, c (stable half-angle form).
double corner_angle(double a, double b, double c) {
  double num = (a - b + c) * (a + b - c);
  double den = (a + b + c) * (-a + b + c);
  return 2.0 * std::atan(std::sqrt(std::max(num, 0.0) / den));
}

double heron_area(const Lengths3& l) {
  // Kahan's stable form: sort descending.
  std::array<double, 3> s = l;
  std::sort(s.begin(), s.end(), std::greater<>());
  double a = s[0], b = s[1], c = s[2];
  double p = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c));
  return 0.25 * std::sqrt(std::max(p, 0.0));
}

// Triangle with sides l placed as 0 at origin, corner 1 on the x axis; returns the edge vectors
// from corner 0 to corners 1 and 2 as columns.
Eigen::Matrix2d canonical_frame(const Lengths3& l) {
  double theta0 = corner_angle(l[0], l[1], l[2]);
  Eigen::Matrix2d m;
  m << l[2], l[1] * std::cos(theta0), 0.0, l[1] * std::sin(theta0);
  return m;
}

double quasi_conformal(const Lengths3& from, const Lengths3& to) {
  Eigen::Matrix2d jacobian = canonical_frame(to) * canonical_frame(from).inverse();
  Eigen::JacobiSVD<Eigen::Matrix2d> svd(jacobian);
  return svd.singularValues()[0] / svd.singularValues()[1];
}

bool valid_triangle(const Lengths3& l) {
  return l[0] + l[1] > l[2] && l[1] + l[2] > l[0] && l[2] + l[0] > l[1] && l[0] > 0 && l[1] > 0 && l[2] > 0;
}

double percentile(std::vector<double>& values, double q) {
  if (values.empty()) return 1.0;
  size_t k = static_cast<size_t>(q * static_cast<double>(values.size() - 1) + 0.5);
  std::nth_element(values.begin(), values.begin() + static_cast<long>(k), values.end());
  return values[k];
}

Eigen::VectorXd embedded_lengths(const Mesh& mesh) {
  Eigen::VectorXd lengths(mesh.n_edges());
  parallel_for(mesh.n_edges(), 0, [&](size_t e) {
    lengths[static_cast<Eigen::Index>(e)] = mesh.calc_edge_length(EdgeHandle(static_cast<int>(e)));
  });
  return lengths;
}

enum class FaceKind : char { measured, excluded, degenerate };

// measure_distortion's figures by face (ratios: three per face), then only the measured faces'
// in face order (compact()).
struct FaceFigures {
  std::vector<FaceKind> kind;
  std::vector<double> log_surface, log_flat, ratios, qc, area;

  explicit FaceFigures(size_t faces)
      : kind(faces, FaceKind::excluded), log_surface(faces), log_flat(faces), ratios(3 * faces),
        qc(faces), area(faces) {}

  // Face f's figures into slot f (face-parallel callers: each face its own slot).
  void measure(size_t f, const Lengths3& a, const Lengths3& b) {
    if (!valid_triangle(a) || !valid_triangle(b)) {
      kind[f] = FaceKind::degenerate;
      return;
    }
    kind[f] = FaceKind::measured;
    area[f] = heron_area(a);
    log_surface[f] = std::log(area[f]);
    log_flat[f] = std::log(heron_area(b));
    for (size_t k = 0; k < 3; ++k) {
      const double before = corner_angle(a[k], a[(k + 1) % 3], a[(k + 2) % 3]);
      const double after = corner_angle(b[k], b[(k + 1) % 3], b[(k + 2) % 3]);
      ratios[3 * f + k] = after / before;
    }
    qc[f] = quasi_conformal(a, b);
  }

  // Keeps the measured faces' figures, in face order.
  void compact() {
    size_t kept = 0;
    for (size_t f = 0; f < kind.size(); ++f) {
      if (kind[f] != FaceKind::measured) continue;
      log_surface[kept] = log_surface[f];
      log_flat[kept] = log_flat[f];
      qc[kept] = qc[f];
      area[kept] = area[f];
      for (size_t k = 0; k < 3; ++k) ratios[3 * kept + k] = ratios[3 * f + k];
      ++kept;
    }
    for (auto* list : {&log_surface, &log_flat, &qc, &area}) list->resize(kept);
    ratios.resize(3 * kept);
  }
};

}  // namespace

DistortionReport measure_distortion(const Mesh& mesh, const Eigen::VectorXd& lengths,
                                    const DistortionOptions& options) {
  if (lengths.size() != static_cast<long>(mesh.n_edges())) {
    throw InvalidInputError("distortion: " + std::to_string(lengths.size()) + " lengths for " +
                            std::to_string(mesh.n_edges()) + " edges");
  }
  const Eigen::VectorXd original = embedded_lengths(mesh);
  // Face-parallel, each face its own slots; the sums below run in face order (the same results
  // on any number of threads).
  FaceFigures figures(mesh.n_faces());
  parallel_for(mesh.n_faces(), 0, [&](size_t f) {
    if (!options.excluded_faces.empty() && options.excluded_faces[f]) return;
    const FaceHandle face(static_cast<int>(f));
    figures.measure(f, face_lengths(mesh, original, face), face_lengths(mesh, lengths, face));
  });
  int skipped = 0;
  for (size_t f = 0; f < figures.kind.size(); ++f) {
    if (figures.kind[f] != FaceKind::degenerate) continue;
    if (!options.skip_degenerate) {
      throw InvalidInputError("distortion: face " + std::to_string(f) + " is degenerate");
    }
    ++skipped;
  }
  figures.compact();
  std::vector<double>&log_surface = figures.log_surface, &log_flat = figures.log_flat,
                     &ratios = figures.ratios, &qc = figures.qc;
  double area_weighted_qc = 0, total_area = 0;
  for (size_t i = 0; i < qc.size(); ++i) {
    area_weighted_qc += figures.area[i] * qc[i];
    total_area += figures.area[i];
  }
  DistortionReport report;
  report.faces = static_cast<int>(log_surface.size());
  report.skipped_faces = skipped;
  if (report.faces == 0) return report;
  // Normalise both total areas to 1 in log space: log(A / sum A) = log A - log sum A.
  auto log_total = [](const std::vector<double>& logs) {
    double peak = *std::max_element(logs.begin(), logs.end()), sum = 0;
    for (double x : logs) sum += std::exp(x - peak);
    return peak + std::log(sum);
  };
  double shift = log_total(log_surface) - log_total(log_flat);
  double sum_sq = 0;
  for (size_t i = 0; i < log_surface.size(); ++i) {
    double d = log_surface[i] - log_flat[i] - shift;
    sum_sq += d * d;
  }
  report.area_distortion = sum_sq / report.faces;
  report.angle_ratio_p05 = percentile(ratios, 0.05);
  report.angle_ratio_p50 = percentile(ratios, 0.50);
  report.angle_ratio_p95 = percentile(ratios, 0.95);
  double qc_sum = 0;
  for (double x : qc) qc_sum += x;
  report.quasi_conformal_mean = qc_sum / static_cast<double>(qc.size());
  report.quasi_conformal_max = *std::max_element(qc.begin(), qc.end());
  report.quasi_conformal_area_mean = area_weighted_qc / total_area;
  report.quasi_conformal_p50 = percentile(qc, 0.50);
  report.quasi_conformal_p95 = percentile(qc, 0.95);
  return report;
}

}  // namespace ricci

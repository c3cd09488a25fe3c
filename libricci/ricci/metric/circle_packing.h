#pragma once
// Circle-packing metrics (Ricci-flow paper §IV): each vertex carries a radius γ_i, each edge a
// fixed conformal quantity η_ij; edge lengths follow from the background geometry's cosine law.
//   Thurston circle packing:  η = cos Φ, Φ ∈ [0, π/2]  (discrete-surface-ricci-flow eq. 12)
//   inversive distance:       η = I ≥ -1 (free)        (ricci-flow-3d-shape-analysis eq. 7-8)
//   combinatorial:            γ = const, Φ = 0         (manifold-splines §6)
// A conformal deformation changes the radii only. The flow variable is u_i = log γ_i (E2),
// log tanh(γ_i/2) (H2), log tan(γ_i/2) (S2).
#include <Eigen/Core>

#include "ricci/metric/geometry.h"
#include "ricci/metric/mesh_tables.h"

namespace ricci {

/// Which conformal quantity the edges keep.
enum class Scheme { circle_packing, inversive_distance, combinatorial };

/// How the initial radii come from the mesh's lengths: per-corner radii
/// γ_i^{jk} = (l_ij + l_ki - l_jk)/2 averaged (mean, Ricci-flow paper §V) or minimised (min,
/// shape-analysis Alg. 1, makes every I_ij ≥ 1), or fitted by least squares to the lengths
/// (manifold-splines eq. 10; only differs from mean for circle_packing, where Φ is clamped).
enum class RadiusInit { mean, min, least_squares };

std::string to_string(Scheme scheme);

/// Radii and edge quantities of a circle-packing metric.
struct CirclePackingMetric {
  Geometry geometry = Geometry::euclidean;
  Scheme scheme = Scheme::inversive_distance;
  /// Radius per vertex index (γ_i > 0; γ_i < π in S2).
  Eigen::VectorXd gamma;
  /// Per edge index: cos Φ_ij (circle packing, combinatorial) or I_ij (inversive distance).
  Eigen::VectorXd eta;
};

/// Radius from the flow variable u; returns NaN when u is out of range (u ≥ 0 in H2).
inline double radius_from_u(Geometry g, double u) {
  switch (g) {
    case Geometry::euclidean:
      return std::exp(u);
    case Geometry::hyperbolic:
      return u < 0 ? 2.0 * std::atanh(std::exp(u)) : std::nan("");
    default: return 2.0 * std::atan(std::exp(u));
  }
}

/// Flow variable u from a radius.
inline double u_from_radius(Geometry g, double gamma) {
  switch (g) {
    case Geometry::euclidean:
      return std::log(gamma);
    case Geometry::hyperbolic:
      return std::log(std::tanh(0.5 * gamma));
    default: return std::log(std::tan(0.5 * gamma));
  }
}

/// Length of the edge between circles of radii a, b with quantity eta, from
/// f(l/2)^2 = ((1+η) f((a+b)/2)^2 + (1-η) f((a-b)/2)^2) / 2 (the cosine law rewritten without
/// cancellation for small lengths). Returns NaN when no such length exists.
inline double circle_edge_length(Geometry g, double a, double b, double eta) {
  const double p = geometry_sine(g, 0.5 * (a + b)), m = geometry_sine(g, 0.5 * (a - b));
  const double q = 0.5 * ((1.0 + eta) * p * p + (1.0 - eta) * m * m);
  if (!(q > 0)) return std::nan("");
  switch (g) {
    case Geometry::euclidean:
      return 2.0 * std::sqrt(q);
    case Geometry::hyperbolic:
      return 2.0 * std::asinh(std::sqrt(q));
    default: return q < 1.0 ? 2.0 * std::asin(std::sqrt(q)) : std::nan("");
  }
}

/// The edge quantity η that gives length l between radii a and b (inverse of
/// circle_edge_length).
inline double circle_edge_eta(Geometry g, double a, double b, double l) {
  const double h = geometry_sine(g, 0.5 * l);
  const double p = geometry_sine(g, 0.5 * (a + b)), m = geometry_sine(g, 0.5 * (a - b));
  return (2.0 * h * h - p * p - m * m) / (geometry_sine(g, a) * geometry_sine(g, b));
}

/// ∂l/∂u_a for the edge of length l between radii a, b:
/// f(a) (f(a) c(b) + η c(a) f(b)) / f(l), with f, c the geometry sine and cosine
/// (dγ/du = f(γ) in all three geometries). In E2 this is (l² + a² - b²)/(2l).
inline double circle_edge_length_du(Geometry g, double a, double b, double eta, double l) {
  const double fa = geometry_sine(g, a), fb = geometry_sine(g, b);
  return fa * (fa * geometry_cosine(g, b) + eta * geometry_cosine(g, a) * fb) /
         geometry_sine(g, l);
}

/// Radii from flow variables (NaN entries where u is out of range).
[[nodiscard]] Eigen::VectorXd radii_from_u(Geometry g, const Eigen::VectorXd& u);
/// Flow variables from radii.
[[nodiscard]] Eigen::VectorXd u_from_radii(Geometry g, const Eigen::VectorXd& gamma);

/// Initial metric from edge lengths (already in the background geometry's units).
/// Scheme::combinatorial ignores the lengths' shape: γ = 1 in E2, half the mean length in H2/S2.
/// \throw InvalidInputError when a face violates the triangle inequality (its corner radius is
///        not positive), naming the face.
[[nodiscard]] CirclePackingMetric initial_metric(const MeshTables& tables,
                                                 const EdgeLengths& lengths, Geometry geometry,
                                                 Scheme scheme, RadiusInit radii);

/// Edge lengths of a metric with radii gamma. Returns false if an edge has no length.
bool circle_packing_lengths(const MeshTables& tables, Geometry geometry,
                            const Eigen::VectorXd& gamma, const Eigen::VectorXd& eta,
                            EdgeLengths& lengths);

/// Edge lengths of a metric. \throw InvalidInputError naming an edge without a length.
[[nodiscard]] EdgeLengths circle_packing_lengths(const MeshTables& tables,
                                                 const CirclePackingMetric& metric);

}  // namespace ricci

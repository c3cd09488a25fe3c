#include "ricci/metric/circle_packing.h"

#include <algorithm>
#include <limits>
#include <string>

#include "ricci/mesh/errors.h"
#include "ricci/metric/least_squares_fit.h"

namespace ricci {

std::string to_string(Scheme scheme) {
  switch (scheme) {
    case Scheme::circle_packing:
      return "circle-packing";
    case Scheme::inversive_distance:
      return "inversive-distance";
    default: return "combinatorial";
  }
}

Eigen::VectorXd radii_from_u(Geometry g, const Eigen::VectorXd& u) {
  Eigen::VectorXd gamma(u.size());
  for (Eigen::Index i = 0; i < u.size(); ++i) gamma[i] = radius_from_u(g, u[i]);
  return gamma;
}

Eigen::VectorXd u_from_radii(Geometry g, const Eigen::VectorXd& gamma) {
  Eigen::VectorXd u(gamma.size());
  for (Eigen::Index i = 0; i < gamma.size(); ++i) u[i] = u_from_radius(g, gamma[i]);
  return u;
}

namespace {

// Per-corner radii (l_ij + l_ki - l_jk)/2, reduced per vertex by mean or min.
Eigen::VectorXd corner_radii(const MeshTables& t, const EdgeLengths& l, RadiusInit mode) {
  const int nv = t.num_vertices();
  Eigen::VectorXd gamma = mode == RadiusInit::min ? Eigen::VectorXd::Constant(
                                                        nv, std::numeric_limits<double>::infinity())
                                                  : Eigen::VectorXd::Zero(nv);
  for (int f = 0; f < t.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const double opposite = l[t.face_edges(f, k)];
      const double r = 0.5 * (l[t.face_edges(f, (k + 1) % 3)] + l[t.face_edges(f, (k + 2) % 3)] -
                              opposite);
      if (!(r > 0)) {
        throw InvalidInputError("face " + std::to_string(f) +
                                " is degenerate (its lengths violate the triangle inequality)");
      }
      const int v = t.face_vertices(f, k);
      gamma[v] = mode == RadiusInit::min ? std::min(gamma[v], r) : gamma[v] + r;
    }
  }
  if (mode != RadiusInit::min) {
    for (int v = 0; v < nv; ++v) gamma[v] /= t.valence[v];
  }
  return gamma;
}

Eigen::VectorXd fitted_eta(const MeshTables& t, const EdgeLengths& l, Geometry g,
                           const Eigen::VectorXd& gamma, bool clamp) {
  Eigen::VectorXd eta(t.num_edges());
  for (int e = 0; e < t.num_edges(); ++e) {
    const double a = gamma[t.edge_vertices(e, 0)], b = gamma[t.edge_vertices(e, 1)];
    eta[e] = circle_edge_eta(g, a, b, l[e]);
    if (clamp) eta[e] = std::clamp(eta[e], 0.0, 1.0);
  }
  return eta;
}

}  // namespace

CirclePackingMetric initial_metric(const MeshTables& t, const EdgeLengths& lengths, Geometry g,
                                   Scheme scheme, RadiusInit radii) {
  if (lengths.size() != t.num_edges()) {
    throw InvalidInputError("edge lengths have " + std::to_string(lengths.size()) +
                            " entries for " + std::to_string(t.num_edges()) + " edges");
  }
  if (!lengths.allFinite() || !(lengths.minCoeff() > 0)) {
    throw InvalidInputError("edge lengths must be positive and finite");
  }
  CirclePackingMetric m;
  m.geometry = g;
  m.scheme = scheme;
  if (scheme == Scheme::combinatorial) {
    const double r = g == Geometry::euclidean ? 1.0 : 0.5 * lengths.mean();
    m.gamma = Eigen::VectorXd::Constant(t.num_vertices(), r);
    m.eta = Eigen::VectorXd::Ones(t.num_edges());
    return m;
  }
  const RadiusInit corner_mode = radii == RadiusInit::min ? RadiusInit::min : RadiusInit::mean;
  m.gamma = corner_radii(t, lengths, corner_mode);
  if (g == Geometry::spherical) {
    // Radii of spherical circles live in (0, π); a coarse mesh on a small sphere could exceed it.
    if (m.gamma.maxCoeff() >= M_PI) {
      throw InvalidInputError("spherical radii reach π: the lengths are too long for S2");
    }
  }
  const bool clamp = scheme == Scheme::circle_packing;
  if (clamp && radii == RadiusInit::least_squares) {
    m.gamma = fit_circle_packing_radii(t, lengths, g, m.gamma);
  }
  m.eta = fitted_eta(t, lengths, g, m.gamma, clamp);
  return m;
}

bool circle_packing_lengths(const MeshTables& t, Geometry g, const Eigen::VectorXd& gamma,
                            const Eigen::VectorXd& eta, EdgeLengths& lengths) {
  lengths.resize(t.num_edges());
  bool ok = true;
  for (int e = 0; e < t.num_edges(); ++e) {
    const double l = circle_edge_length(g, gamma[t.edge_vertices(e, 0)],
                                        gamma[t.edge_vertices(e, 1)], eta[e]);
    lengths[e] = l;
    ok = ok && l > 0;  // false for NaN too
  }
  return ok;
}

EdgeLengths circle_packing_lengths(const MeshTables& t, const CirclePackingMetric& m) {
  if (m.gamma.size() != t.num_vertices() || m.eta.size() != t.num_edges()) {
    throw InvalidInputError("circle packing metric does not match the mesh's element counts");
  }
  EdgeLengths lengths;
  if (!circle_packing_lengths(t, m.geometry, m.gamma, m.eta, lengths)) {
    for (int e = 0; e < t.num_edges(); ++e) {
      if (!(lengths[e] > 0)) {
        throw InvalidInputError("edge " + std::to_string(e) + " has no " + to_string(m.geometry) +
                                " length for its radii and " + to_string(m.scheme) + " weight");
      }
    }
  }
  return lengths;
}

}  // namespace ricci

#include "spline/fit/normal_equations.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "spline/tessellate/parallel_for.h"

namespace spline::detail {
namespace {

// Reaching faces of every domain face, as ascending domain indices.
std::vector<std::vector<int>> reach_by_domain_index(const ManifoldSplineSpace& space) {
  std::vector<std::vector<int>> reach;
  reach.reserve(space.domain_faces().size());
  for (int face : space.domain_faces()) {
    std::vector<int> r = space.reaching_faces(face);
    for (int& f : r) f = space.domain_index(f);  // ascending faces -> ascending indices
    reach.push_back(std::move(r));
  }
  return reach;
}

// Local columns of the functions of one face's reaching faces (ascending domain indices, m
// functions each): a table by domain index, filled for the current face and cleared after it
// (a binary search per basis sample cost 2% of a fit's instructions).
class ReachColumns {
 public:
  ReachColumns(int faces, int m) : slot_(static_cast<std::size_t>(faces), -1), m_(m) {}
  void set(const std::vector<int>& reach) {
    for (int f : reach_) slot_[f] = -1;
    reach_ = reach;
    for (std::size_t i = 0; i < reach.size(); ++i) slot_[reach[i]] = static_cast<int>(i);
  }
  int operator()(int function) const {
    const int slot = slot_[function / m_];
    if (slot < 0) {
      throw std::logic_error("normal equations: a basis function outside the reaching faces");
    }
    return slot * m_ + function % m_;
  }

 private:
  std::vector<int> slot_, reach_;
  int m_;
};

// Accumulates the rows of one face into a dense local Gram matrix (lower triangle) and
// right-hand side over the face's reaching functions. Rows are sparse (about a third of the
// reaching functions are non-zero at a point), so each row adds only its own outer product.
// Only the columns some row of the face touched are zeroed again and read out (face_columns):
// a face's rows reach about half of its reaching functions, and clearing and scanning the whole
// dense matrix per face cost as much as the rows themselves.
class FaceAccumulator {
 public:
  void reset(int columns) {
    columns_ = columns;
    if (gram.rows() < columns) {  // grows to the largest face; a face uses the top-left block
      gram.setZero(columns, columns);
      rhs.setZero(columns, 3);
    } else {
      for (int j : face_columns_) {
        rhs.row(j).setZero();
        for (int i : face_columns_) gram(i, j) = 0.0;
      }
    }
    for (int j : face_columns_) in_face_[j] = 0;
    face_columns_.clear();
    row_.assign(static_cast<std::size_t>(columns), 0.0);
    mark_.assign(static_cast<std::size_t>(columns), 0);
    in_face_.resize(static_cast<std::size_t>(columns), 0);
    touched_.clear();
  }
  void add(int column, double value) {
    if (!mark_[column]) {
      mark_[column] = 1;
      touched_.push_back(column);
      if (!in_face_[column]) {
        in_face_[column] = 1;
        face_columns_.push_back(column);
      }
    }
    row_[column] += value;
  }
  int columns() const { return columns_; }
  /// The columns touched since reset(), ascending (all other entries are zero).
  const std::vector<int>& face_columns() {
    std::sort(face_columns_.begin(), face_columns_.end());
    return face_columns_;
  }
  // Ends the row: gram += r r^T (lower triangle), rhs += r target^T. Each pair of touched columns
  // once (they come in the samples' order, not sorted, so the pair is put below the diagonal).
  void end_row(const Eigen::RowVector3d& target, bool has_target) {
    for (std::size_t a = 0; a < touched_.size(); ++a) {
      const int p = touched_[a];
      for (std::size_t b = 0; b <= a; ++b) {
        const int q = touched_[b];
        gram(std::max(p, q), std::min(p, q)) += row_[p] * row_[q];
      }
      if (has_target) rhs.row(p) += row_[p] * target;
    }
    for (int i : touched_) {
      row_[i] = 0.0;
      mark_[i] = 0;
    }
    touched_.clear();
  }
  Eigen::MatrixXd gram;
  Eigen::MatrixX3d rhs;

 private:
  std::vector<double> row_;
  std::vector<char> mark_, in_face_;
  std::vector<int> touched_, face_columns_;
  int columns_ = 0;
};

// Data rows, then three thin-plate rows per quadrature point, of one face.
void accumulate_face(const ManifoldSplineSpace& space, int face, const std::vector<int>& reach,
                     const FaceRowsSpec& spec, const std::vector<DomainPoint>& parameters,
                     const Eigen::MatrixX3d& points, const PointBasisValues* known,
                     bool keep_gradients, FaceAccumulator& acc, FaceDataRows& kept,
                     ReachColumns& local_column) {
  acc.reset(static_cast<int>(reach.size()) * space.functions_per_face());
  local_column.set(reach);
  const auto add = [&](int function, double value) {
    acc.add(local_column(function), value);
    kept.function.push_back(function);
    kept.value.push_back(value);
  };
  for (int k : spec.points) {
    const auto point = static_cast<std::size_t>(k);
    if (known && !keep_gradients && known->holds(point, parameters[point])) {
      const auto block = static_cast<std::size_t>(known->block[point]);
      const std::vector<int>& function = known->function[block];
      const std::vector<double>& value = known->value[block];
      const int first = known->first[point];
      for (int e = first; e < first + known->count[point]; ++e) add(function[e], value[e]);
    } else if (keep_gradients) {
      // Values of a first-order evaluation have the bits of a values-only one.
      for (const auto& s : space.evaluate_basis(parameters[point], -1, {},
                                                BasisDerivatives::first)) {
        add(s.function, s.jet.value);
        kept.gradient.push_back(s.jet.gradient);
      }
    } else {
      for (const auto& s : space.evaluate_basis(parameters[point], -1, {}, BasisDerivatives::none))
        add(s.function, s.jet.value);
    }
    kept.start.push_back(static_cast<int>(kept.function.size()));
    acc.end_row(points.row(k), true);
  }
  if (spec.thin_plate_weight <= 0.0) return;
  const Eigen::RowVector3d zero = Eigen::RowVector3d::Zero();
  for (const auto& q : triangle_quadrature()) {
    const double w = std::sqrt(spec.thin_plate_weight * q.weight);
    const auto samples = space.evaluate_basis({face, q.bary});
    // Next to the hole the functions of its faces are missing, so the basis is no partition of
    // unity there: even a plane then needs curved combinations, which the energy would fight.
    if (!is_partition_of_unity(samples)) continue;
    const double factors[3] = {w, w * std::sqrt(2.0), w};
    for (int h = 0; h < 3; ++h) {
      for (const auto& s : samples) {
        if (s.jet.hessian[h] != 0.0)
          acc.add(local_column(s.function), factors[h] * s.jet.hessian[h]);
      }
      acc.end_row(zero, false);
    }
  }
}

}  // namespace

const std::vector<QuadraturePoint>& triangle_quadrature() {
  static const std::vector<QuadraturePoint> rule = [] {
    const double a = 0.445948490915965, wa = 0.223381589678011;
    const double b = 0.091576213509771, wb = 0.109951743655322;
    return std::vector<QuadraturePoint>{
        {{a, a, 1 - 2 * a}, wa}, {{a, 1 - 2 * a, a}, wa}, {{1 - 2 * a, a, a}, wa},
        {{b, b, 1 - 2 * b}, wb}, {{b, 1 - 2 * b, b}, wb}, {{1 - 2 * b, b, b}, wb}};
  }();
  return rule;
}

NormalEquations assemble_normal_equations(const ManifoldSplineSpace& space,
                                          const std::vector<FaceRowsSpec>& rows_by_face,
                                          const std::vector<DomainPoint>& parameters,
                                          const Eigen::MatrixX3d& points, double anchor,
                                          const Eigen::MatrixX3d& initial, int threads,
                                          const PointBasisValues* known, bool keep_gradients) {
  const int m = space.functions_per_face();
  const int faces = space.domain_face_count();
  const std::vector<std::vector<int>> reach = reach_by_domain_index(space);
  threads = std::max(1, std::min(threads, faces));
  // Per worker: the non-zero entries of its faces' local Gram matrices (lower triangle, global
  // indices). Supports are small (knot clouds hug their vertices): a face's local Gram matrix
  // is ~95% zeros, so only its non-zeros are kept, and the sparse matrix is built once.
  std::vector<std::vector<Eigen::Triplet<double>>> entries(static_cast<std::size_t>(threads));
  std::vector<Eigen::MatrixX3d> rhs(static_cast<std::size_t>(threads));
  std::vector<FaceDataRows> kept(static_cast<std::size_t>(faces));  // each face: one worker
  run_workers(threads, [&](int t) {
    auto& out = entries[t];
    rhs[t].setZero(space.function_count(), 3);
    FaceAccumulator acc;
    ReachColumns local_column(faces, m);
    for (int d = t; d < faces; d += threads) {
      const FaceRowsSpec& spec = rows_by_face[d];
      if (spec.points.empty() && spec.thin_plate_weight <= 0.0) continue;
      const std::vector<int>& r = reach[d];
      accumulate_face(space, space.domain_faces()[d], r, spec, parameters, points, known,
                      keep_gradients, acc, kept[d], local_column);
      const int k = acc.columns();
      std::vector<int> global(static_cast<std::size_t>(k));
      for (int c = 0; c < k; ++c) global[c] = r[c / m] * m + c % m;  // ascending with c
      // Ascending j, then i >= j, as a scan of the whole lower triangle would emit them.
      const std::vector<int>& columns = acc.face_columns();
      for (std::size_t jj = 0; jj < columns.size(); ++jj) {
        const int j = columns[jj];
        rhs[t].row(global[j]) += acc.rhs.row(j);
        for (std::size_t ii = jj; ii < columns.size(); ++ii) {
          const int i = columns[ii];
          const double v = acc.gram(i, j);
          if (v != 0.0) out.emplace_back(global[i], global[j], v);
        }
      }
    }
  });
  std::size_t total = static_cast<std::size_t>(space.function_count());
  for (const auto& e : entries) total += e.size();
  std::vector<Eigen::Triplet<double>> all;
  all.reserve(total);
  for (int t = 0; t < threads; ++t) {
    all.insert(all.end(), entries[t].begin(), entries[t].end());
    std::vector<Eigen::Triplet<double>>().swap(entries[t]);
    if (t > 0) rhs[0] += rhs[t];
  }
  for (int i = 0; i < space.function_count(); ++i) all.emplace_back(i, i, anchor);
  NormalEquations out;
  out.lower.resize(space.function_count(), space.function_count());
  out.lower.setFromTriplets(all.begin(), all.end());
  out.rhs = rhs[0] + anchor * initial;
  out.data_rows = std::move(kept);
  return out;
}

PointBasisValues take_data_rows(NormalEquations& equations,
                                const std::vector<FaceRowsSpec>& rows_by_face,
                                const std::vector<DomainPoint>& parameters) {
  PointBasisValues out;
  out.at.assign(parameters.size(), DomainPoint{-1, Eigen::Vector3d::Zero()});
  out.block.assign(parameters.size(), 0);
  out.first.assign(parameters.size(), 0);
  out.count.assign(parameters.size(), 0);
  bool gradients = false;
  for (std::size_t d = 0; d < rows_by_face.size(); ++d) {
    FaceDataRows& rows = equations.data_rows[d];
    const auto& listed = rows_by_face[d].points;
    for (std::size_t i = 0; i < listed.size(); ++i) {
      const auto k = static_cast<std::size_t>(listed[i]);
      out.at[k] = parameters[k];
      out.block[k] = static_cast<int>(d);
      out.first[k] = rows.start[i];
      out.count[k] = rows.start[i + 1] - rows.start[i];
    }
    gradients = gradients || !rows.gradient.empty();
    out.function.push_back(std::move(rows.function));
    out.value.push_back(std::move(rows.value));
    out.gradient.push_back(std::move(rows.gradient));
  }
  if (!gradients) out.gradient.clear();
  return out;
}

Eigen::MatrixX3d residuals_at_parameters(const NormalEquations& equations,
                                         const std::vector<FaceRowsSpec>& rows_by_face,
                                         const Eigen::MatrixX3d& points,
                                         const Eigen::MatrixX3d& control_points) {
  Eigen::MatrixX3d residual = Eigen::MatrixX3d::Zero(points.rows(), 3);
  for (std::size_t d = 0; d < rows_by_face.size(); ++d) {
    const FaceDataRows& rows = equations.data_rows[d];
    const auto& listed = rows_by_face[d].points;
    for (std::size_t i = 0; i < listed.size(); ++i) {
      Eigen::RowVector3d f = Eigen::RowVector3d::Zero();
      for (int e = rows.start[i]; e < rows.start[i + 1]; ++e)
        f += rows.value[e] * control_points.row(rows.function[e]);
      residual.row(listed[i]) = f - points.row(listed[i]);
    }
  }
  return residual;
}

}  // namespace spline::detail

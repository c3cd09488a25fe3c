#include "spline/baseline/loop_surface.h"

#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTable.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/ptexIndices.h>
#include <opensubdiv/far/stencilTable.h>
#include <opensubdiv/far/stencilTableFactory.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <array>
#include <string>

#include "ricci/mesh/errors.h"

namespace spline {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

namespace {

using StencilTable = Far::StencilTableReal<double>;
using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// Largest number of patch points of one Loop patch (12 for a box spline, 18 for a Gregory triangle).
constexpr int kMaxPatchPoints = 20;

// Parametric slack allowed on locations coming from closest-point queries.
constexpr double kParamSlack = 1e-9;

std::unique_ptr<Far::TopologyRefiner> make_refiner(const std::vector<std::array<int, 3>>& corners, int vertices) {
  std::vector<int> per_face(corners.size(), 3);
  std::vector<int> indices;
  indices.reserve(3 * corners.size());
  for (const auto& c : corners) indices.insert(indices.end(), c.begin(), c.end());
  Far::TopologyDescriptor desc;
  desc.numVertices = vertices;
  desc.numFaces = static_cast<int>(corners.size());
  desc.numVertsPerFace = per_face.data();
  desc.vertIndicesPerFace = indices.data();
  Sdc::Options sdc;
  // Open scans: boundary edges become smooth cubic B-spline curves the surface ends on.
  sdc.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
  using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
  std::unique_ptr<Far::TopologyRefiner> refiner(
      Factory::Create(desc, Factory::Options(Sdc::SCHEME_LOOP, sdc)));
  if (!refiner) throw ricci::InvalidInputError("LoopSurface: OpenSubdiv rejected the control mesh topology");
  return refiner;
}

// Converts an OpenSubdiv stencil table to a sparse matrix (stencils by control points).
RowSparse to_sparse(const StencilTable& table, int control_points) {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(table.GetControlIndices().size());
  const auto& sizes = table.GetSizes();
  const auto& indices = table.GetControlIndices();
  const auto& weights = table.GetWeights();
  size_t offset = 0;  // running, so tables built without offsets convert too
  for (int i = 0; i < table.GetNumStencils(); ++i) {
    for (int k = 0; k < sizes[static_cast<size_t>(i)]; ++k, ++offset) {
      entries.emplace_back(i, indices[offset], weights[offset]);
    }
  }
  RowSparse m(table.GetNumStencils(), control_points);
  m.setFromTriplets(entries.begin(), entries.end());
  return m;
}

}  // namespace

struct LoopSurface::Impl {
  ricci::Mesh control;
  std::vector<std::array<int, 3>> corners;
  std::vector<std::array<int, 3>> neighbours;  // face across the edge opposite each corner
  std::vector<int> ptex;                       // ptex face of each control face
  std::unique_ptr<Far::TopologyRefiner> refiner;
  std::unique_ptr<Far::PatchTable> patches;
  std::unique_ptr<Far::PatchMap> patch_map;
  std::unique_ptr<const StencilTable> point_stencils;  // every patch point over the control points
  RowSparse point_matrix;                              // the same as a matrix

  const Far::PatchTable::PatchHandle& find(const LoopLocation& loc) const {
    if (loc.face < 0 || loc.face >= static_cast<int>(corners.size()) || !(loc.u >= -kParamSlack) ||
        !(loc.v >= -kParamSlack) || !(loc.u + loc.v <= 1.0 + kParamSlack)) {
      throw ricci::InvalidInputError("LoopSurface: location (face " + std::to_string(loc.face) + ", u " +
                                     std::to_string(loc.u) + ", v " + std::to_string(loc.v) +
                                     ") is outside the control faces");
    }
    const auto* handle = patch_map->FindPatch(ptex[static_cast<size_t>(loc.face)], clamp01(loc.u), clamp01(loc.v));
    if (!handle) throw ricci::InvalidInputError("LoopSurface: no patch at face " + std::to_string(loc.face));
    return *handle;
  }

  static double clamp01(double x) { return x < 0.0 ? 0.0 : (x > 1.0 ? 1.0 : x); }
};

LoopSurface::LoopSurface(const ricci::Mesh& control, const LoopSurfaceOptions& options)
    : impl_(std::make_unique<Impl>()) {
  if (control.n_vertices() < 4 || control.n_faces() < 2) {
    throw ricci::InvalidInputError("LoopSurface: the control mesh needs at least 4 vertices and 2 faces, got " +
                                   std::to_string(control.n_vertices()) + " and " +
                                   std::to_string(control.n_faces()));
  }
  if (options.isolation_level < 1 || options.isolation_level > 10) {
    throw ricci::InvalidInputError("LoopSurface: isolation_level " + std::to_string(options.isolation_level) +
                                   " is outside 1..10");
  }
  Impl& m = *impl_;
  m.control = control;
  m.corners.resize(control.n_faces());
  m.neighbours.resize(control.n_faces());
  for (auto f : control.faces()) {
    auto& c = m.corners[static_cast<size_t>(f.idx())];
    int k = 0;
    for (auto v : control.fv_range(f)) {
      if (k == 3) throw ricci::InvalidInputError("LoopSurface: face " + std::to_string(f.idx()) + " is not a triangle");
      c[static_cast<size_t>(k++)] = v.idx();
    }
    if (k != 3) throw ricci::InvalidInputError("LoopSurface: face " + std::to_string(f.idx()) + " is not a triangle");
    auto& n = m.neighbours[static_cast<size_t>(f.idx())];
    for (auto h : control.fh_range(f)) {
      int a = control.from_vertex_handle(h).idx(), b = control.to_vertex_handle(h).idx();
      for (size_t j = 0; j < 3; ++j) {
        if (c[j] != a && c[j] != b) {
          auto opposite = control.opposite_halfedge_handle(h);
          n[j] = control.is_boundary(opposite) ? -1 : control.face_handle(opposite).idx();
        }
      }
    }
  }

  m.refiner = make_refiner(m.corners, static_cast<int>(control.n_vertices()));
  Far::PatchTableFactory::Options patch_options(static_cast<unsigned>(options.isolation_level));
  patch_options.SetEndCapType(Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS);
  patch_options.SetPatchPrecision<double>();
  m.refiner->RefineAdaptive(patch_options.GetRefineAdaptiveOptions());
  m.patches.reset(Far::PatchTableFactory::Create(*m.refiner, patch_options));
  m.patch_map = std::make_unique<Far::PatchMap>(*m.patches);

  Far::PtexIndices ptex(*m.refiner);
  m.ptex.resize(m.corners.size());
  for (size_t f = 0; f < m.corners.size(); ++f) m.ptex[f] = ptex.GetFaceId(static_cast<int>(f));

  // Patch point indices run over all refined levels (control points first), then local points.
  Far::StencilTableFactoryReal<double>::Options stencil_options;
  stencil_options.generateIntermediateLevels = true;
  stencil_options.generateControlVerts = true;
  stencil_options.generateOffsets = true;
  stencil_options.factorizeIntermediateLevels = true;
  std::unique_ptr<const StencilTable> refined(
      Far::StencilTableFactoryReal<double>::Create(*m.refiner, stencil_options));
  const StencilTable* local = m.patches->GetLocalPointStencilTable<double>();
  if (local && local->GetNumStencils() > 0) {
    m.point_stencils.reset(
        Far::StencilTableFactoryReal<double>::AppendLocalPointStencilTable(*m.refiner, refined.get(), local));
  } else {
    m.point_stencils = std::move(refined);
  }
  const int expected = m.refiner->GetNumVerticesTotal() + m.patches->GetNumLocalPoints();
  if (!m.point_stencils || m.point_stencils->GetNumStencils() != expected) {
    throw ricci::SolverError("LoopSurface: OpenSubdiv produced " +
                             std::to_string(m.point_stencils ? m.point_stencils->GetNumStencils() : 0) +
                             " patch-point stencils, expected " + std::to_string(expected));
  }
  m.point_matrix = to_sparse(*m.point_stencils, num_control_points());
}

LoopSurface::~LoopSurface() = default;

int LoopSurface::num_control_points() const { return static_cast<int>(impl_->control.n_vertices()); }

const ricci::Mesh& LoopSurface::control_mesh() const { return impl_->control; }

int LoopSurface::neighbour(int face, int k) const {
  return impl_->neighbours[static_cast<size_t>(face)][static_cast<size_t>(k)];
}

int LoopSurface::corner(int face, int k) const { return impl_->corners[static_cast<size_t>(face)][static_cast<size_t>(k)]; }

Eigen::SparseMatrix<double, Eigen::RowMajor> LoopSurface::design_matrix(const std::vector<LoopLocation>& locations) const {
  const Impl& m = *impl_;
  std::vector<double> s(locations.size()), t(locations.size());
  Far::LimitStencilTableFactoryReal<double>::LocationArrayVec arrays(locations.size());
  for (size_t i = 0; i < locations.size(); ++i) {
    (void)m.find(locations[i]);  // validates before OpenSubdiv silently drops a location
    s[i] = Impl::clamp01(locations[i].u);
    t[i] = Impl::clamp01(locations[i].v);
    arrays[i].ptexIdx = m.ptex[static_cast<size_t>(locations[i].face)];
    arrays[i].numLocations = 1;
    arrays[i].s = &s[i];
    arrays[i].t = &t[i];
  }
  RowSparse a(static_cast<Eigen::Index>(locations.size()), num_control_points());
  if (locations.empty()) return a;
  Far::LimitStencilTableFactoryReal<double>::Options options;
  options.generate1stDerivatives = false;
  std::unique_ptr<const Far::LimitStencilTableReal<double>> table(Far::LimitStencilTableFactoryReal<double>::Create(
      *m.refiner, arrays, m.point_stencils.get(), m.patches.get(), options));
  if (!table || table->GetNumStencils() != static_cast<int>(locations.size())) {
    throw ricci::SolverError("LoopSurface: OpenSubdiv returned " +
                             std::to_string(table ? table->GetNumStencils() : 0) + " limit stencils for " +
                             std::to_string(locations.size()) + " locations");
  }
  return to_sparse(*table, num_control_points());
}

Eigen::MatrixX3d LoopSurface::patch_points(const Eigen::MatrixX3d& control) const {
  if (control.rows() != num_control_points()) {
    throw ricci::InvalidInputError("LoopSurface::patch_points: " + std::to_string(control.rows()) +
                                   " control points for a mesh of " + std::to_string(num_control_points()));
  }
  return impl_->point_matrix * control;
}

LoopPoint LoopSurface::evaluate(const Eigen::MatrixX3d& patch_points, const LoopLocation& location) const {
  const Impl& m = *impl_;
  const auto& handle = m.find(location);
  auto cvs = m.patches->GetPatchVertices(handle);
  if (cvs.size() > kMaxPatchPoints) throw ricci::SolverError("LoopSurface: a patch has too many points");
  double w[kMaxPatchPoints], wu[kMaxPatchPoints], wv[kMaxPatchPoints];
  m.patches->EvaluateBasis(handle, Impl::clamp01(location.u), Impl::clamp01(location.v), w, wu, wv);
  LoopPoint p;
  for (int k = 0; k < cvs.size(); ++k) {
    Eigen::Vector3d q = patch_points.row(cvs[k]).transpose();
    p.position += w[k] * q;
    p.du += wu[k] * q;
    p.dv += wv[k] * q;
  }
  return p;
}

}  // namespace spline

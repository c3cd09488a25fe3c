#pragma once
// The spline file (.msp): a SplineSurface saved with everything its evaluation needs, so that
// the surface read back evaluates bit for bit like the saved one (docs/spline-file.md describes
// the layout and the versioning rule).
//
// What is stored: the domain mesh (positions, faces in corner order), the parts of the affine
// atlas the spline space reads (charts, transitions, the per-face chart choice, the domain mask,
// the atlas' scalar figures), the degree, every vertex's home knot cloud, the control points,
// the singular vertex, the fills (rim, planar triangulation with its knot clouds, control points,
// plane, boundary curve, seam figures), the open rims and the skipped-face mask. What is not:
// the atlas' construction data (cut graph, sliced mesh, layout, polygon word, side pairings,
// holonomies); a loaded surface's atlas has them empty.
//
// Reading validates everything before it is used: magic, version, section order and lengths,
// counts against the header, indices in range, finite numbers, a manifold consistently oriented
// mesh, charts consistent with the mesh's faces, knot clouds within the bound that guarantees
// the DMS conditions. A bad file throws with a one-line message that starts with the file's
// name; nothing is read past the end of the data and no count allocates more than the file
// holds.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "spline/surface/spline_surface.h"

namespace spline {

/// The format version this library writes and reads.
inline constexpr std::uint32_t kSplineFileVersion = 1;

/// Free-form provenance stored in the header (e.g. {"tool": "msp fit", "input": "scan.off"}).
using SplineFileProvenance = std::map<std::string, std::string>;

/// The JSON header's summary of a file (counts as stored; provenance as given to the writer).
struct SplineFileHeader {
  std::uint32_t version = 0;
  int degree = 0;
  int vertices = 0, faces = 0;  ///< of the domain mesh
  int charts = 0, transitions = 0;
  int control_points = 0;  ///< of the manifold spline (its function count)
  int fills = 0, open_rims = 0;
  int singular_vertex = -1;
  SplineFileProvenance provenance;
};

/// A decoded file: its header and the surface.
struct SplineFile {
  SplineFileHeader header;
  SplineSurface surface;
};

/// The file's bytes.
/// \throw ricci::InvalidInputError when the surface cannot be stored: no spline space, a control
///        point count other than its function count, a fill without a space, or a domain mesh
///        with deleted elements.
[[nodiscard]] std::vector<std::uint8_t> encode_spline_surface(
    const SplineSurface& surface, const SplineFileProvenance& provenance = {});

/// The surface (and header) of a file's bytes; `source` names the file in messages.
/// \throw ricci::IOError on a malformed file (bad magic, another version, truncated, a section
///        out of order, counts that disagree with the header or overrun their section, bad
///        JSON); ricci::InvalidInputError (or its TopologyError) on contents that are not a
///        valid surface (an index out of range, a non-finite number, a non-manifold mesh, a chart
///        that disagrees with the mesh, a knot cloud out of bounds). Messages start "source: ".
[[nodiscard]] SplineFile decode_spline_file(const std::vector<std::uint8_t>& bytes,
                                            const std::string& source = "spline file");

/// Writes the file atomically (a temporary next to `path`, renamed into place).
/// \throw ricci::IOError when it cannot be written; as encode_spline_surface.
void save_spline_surface(const SplineSurface& surface, const std::string& path,
                         const SplineFileProvenance& provenance = {});

/// Reads a file (decode_spline_file of its bytes; a name ending in .gz is decompressed).
/// \throw ricci::IOError when it cannot be read; as decode_spline_file.
[[nodiscard]] SplineFile read_spline_file(const std::string& path);

/// read_spline_file(path).surface.
[[nodiscard]] SplineSurface load_spline_surface(const std::string& path);

}  // namespace spline

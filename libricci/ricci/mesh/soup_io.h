#pragma once
// Strict readers for OFF, OBJ, PLY (ascii and binary) and STL (ascii and binary), each optionally
// gzip-compressed (name.off.gz). Unlike OpenMesh's readers they keep every face as written, so a
// broken file can be described instead of silently repaired, and every error names the line.
#include <string>
#include <string_view>

#include "ricci/mesh/soup.h"

namespace ricci {

/// The mesh file formats read_soup() understands.
enum class MeshFormat { off, obj, ply, stl };

/// Format chosen by the extension (case-insensitive; a trailing ".gz" is looked through).
/// \throw IOError naming the extension when it is not .off, .obj, .ply or .stl.
[[nodiscard]] MeshFormat format_from_extension(const std::string& path);

/// Reads a mesh file into a polygon soup. Out-of-range indices, faces of fewer than 3 vertices,
/// malformed numbers, truncated data and files without faces are refused; topological defects
/// (non-manifold, non-orientable, degenerate, NaN coordinates) are kept for diagnose().
/// STL vertices are merged by exact position, since STL stores every triangle apart.
/// \throw IOError "<file>:<line>: <problem>" (or "<file>: <problem>" when no line applies).
[[nodiscard]] PolygonSoup read_soup(const std::string& path);

/// Parses file contents already in memory; `name` is used in messages only.
/// \throw IOError as read_soup().
[[nodiscard]] PolygonSoup parse_soup(std::string_view data, MeshFormat format,
                                     const std::string& name);

}  // namespace ricci

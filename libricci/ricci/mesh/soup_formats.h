#pragma once
// Internal: one parser per file format, all called through parse_soup().
#include <string>
#include <string_view>

#include "ricci/mesh/soup.h"

namespace ricci::detail {

PolygonSoup parse_off(std::string_view data, const std::string& name);
PolygonSoup parse_obj(std::string_view data, const std::string& name);
PolygonSoup parse_ply(std::string_view data, const std::string& name);
PolygonSoup parse_stl(std::string_view data, const std::string& name);

/// Refuses a soup whose indices leave [0, #V), whose faces have fewer than 3 vertices, or that
/// has no faces; names the face's line when the soup has one. \throw IOError.
void check_soup_indices(const PolygonSoup& soup, const std::string& name);

}  // namespace ricci::detail

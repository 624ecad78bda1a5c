// Internal: the box of an OpenCASCADE BREP text's vertices ("CASCADE Topology V1..V3", as
// FreeCAD saves shapes in its documents), with the shape's one location applied. A box stock's
// shape has its corners as vertices, so their box is the stock; for a curved solid it is not,
// and the caller reads only box shapes this way.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "ncjoule/removal.hpp"

namespace ncjoule::projects_detail {

// std::nullopt with `why` when the text is not a BREP, has no vertex, or has more than one
// location or a location that turns the shape.
std::optional<Box3> brep_vertex_bounds(std::string_view text, std::string& why);

} // namespace ncjoule::projects_detail

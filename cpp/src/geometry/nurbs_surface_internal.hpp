#pragma once
// Private constants shared by the NurbsSurface translation units (nurbs_surface*.cpp).

namespace netshape::geometry::detail {

/// Relative size below which a cross product S_u × S_v counts as degenerate.
inline constexpr double kDegenerateRel = 1e-10;

}  // namespace netshape::geometry::detail

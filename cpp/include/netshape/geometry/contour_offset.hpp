#pragma once
/// \file contour_offset.hpp
/// 2-D contour offsets with round (arc) corners, for cutter-radius offsets and pocket rings, computed
/// with CGAL's circle-segment offsets (CGAL::approximated_offset_2 / approximated_inset_2: the Minkowski
/// sum with a disk, arcs kept as arcs) and Boolean operations on circle-segment polygons (islands).
/// CGAL's straight skeleton would give mitred corners; these are round, as a cutter of radius d makes.
/// CGAL lives only in contour_offset.cpp; inputs and outputs are double-precision Eigen/Block types.
///
/// Output rings are closed loops of toolpath::Block lines and arcs in the XY plane (plane xy, z given).
/// Outer boundaries of a region run counter-clockwise, boundaries around islands (holes) clockwise.

#include <vector>

#include "netshape/core/types.hpp"
#include "netshape/toolpath/block.hpp"
#include "netshape/toolpath/toolpath.hpp"

namespace netshape::geometry {

/// One closed ring of line/arc blocks.
struct OffsetRing {
  std::vector<toolpath::Block> blocks;  ///< closed: the last block ends where the first starts
  bool hole = false;                    ///< true if the ring bounds a hole (runs clockwise)

  /// Signed area enclosed [mm²] (counter-clockwise positive), exact for the arcs.
  double area() const;
  /// Points along the ring, arcs split so the chord error is at most `chord_tolerance` [mm]: (k, 2),
  /// first point not repeated at the end.
  Points2 polyline(double chord_tolerance) const;
};

/// A region: outer boundary (n, 2) and islands (each (k, 2)), vertices in order, not repeated at the end.
/// Orientation of the input does not matter. Checked: ≥ 3 vertices, finite, simple (no self-
/// intersection) — a self-intersecting contour throws std::invalid_argument naming it.
struct Region {
  Points2 outer;
  std::vector<Points2> islands;
  void validate() const;
};

/// Offset of the region by `distance` [mm]: distance < 0 shrinks (inward: the points of the region at
/// least |d| from its boundary, islands grown by |d|), distance > 0 grows (outward: the region ⊕ disk d).
/// Corners become arcs of radius |d|. Empty result = nothing left. `tolerance` [mm] bounds CGAL's rational
/// approximation of the offset (its eps).
std::vector<OffsetRing> offset_region(const Region& region, double distance, double tolerance = 1e-6);

/// Pocket rings: inward offsets at the tool radius, then every `step_over` further, until nothing is
/// left. Result[k] holds the rings of level k (several where the pocket splits).
std::vector<std::vector<OffsetRing>> pocket_rings(const Region& region, double tool_radius, double step_over,
                                                  double tolerance = 1e-6);

/// The rings as a tool path at height z [mm]: per ring a rapid above the start (z + clearance), a plunge
/// (line), the ring's lines and arcs at `feed` [mm/s], a retract; innermost level first.
toolpath::Toolpath rings_toolpath(const std::vector<std::vector<OffsetRing>>& levels, double z, double clearance,
                                  double feed, double spindle_rpm = 10000.0, int tool = 1);

}  // namespace netshape::geometry

#pragma once
/// \file raster.hpp
/// Iso-parametric raster tool paths over a NURBS design surface: passes along iso-curves, step-over from
/// a scallop-height target (adjusted for the surface's normal curvature across the passes), CC points
/// offset by a stock allowance (Yang & Kweon eq. 12) and turned into CL (tool-tip) points for the cutter
/// (cutter_location.hpp). Normals are flipped as a whole if they face away from the tool on average
/// (mean n·axis < 0 over a 9 × 9 grid): the material lies on the far side of the surface. The result is a toolpath::Toolpath of rapids and lines.

#include "netshape/core/types.hpp"
#include "netshape/cutter/cutter.hpp"
#include "netshape/geometry/nurbs_surface.hpp"
#include "netshape/toolpath/toolpath.hpp"

namespace netshape::geometry {

/// Options of raster_toolpath. Plain value type; validate() checks it.
struct RasterOptions {
  cutter::Cutter cutter = cutter::Cutter::ball_end(10.0, 2, 0.5235987755982988);
  Vec3 axis = Vec3::UnitZ();       ///< tool axis (tip → spindle), constant over the path
  double scallop_height = 0.01;    ///< target scallop height h [mm] (used when step_over is 0)
  double step_over = 0.0;          ///< fixed step between passes measured on the surface [mm]; 0 = from h
  double chord_tolerance = 0.005;  ///< max deviation of the CL polyline from the CL curve of a pass [mm]
  double stock_allowance = 0.0;    ///< offset distance d along the normal added to the CC points [mm]
  bool along_u = true;             ///< passes follow u (iso-curves v = const) and step over in v
  bool zigzag = true;              ///< alternate pass direction (else retract and return)
  double feed = 20.0;              ///< cutting feed [mm/s]
  double plunge_feed = 0.0;        ///< feed of the plunge onto the first pass [mm/s]; 0 = feed
  double clearance = 5.0;          ///< rapid height above the highest CL point, along the axis [mm]
  double spindle_rpm = 10000.0;    ///< [rev/min], stored in every block
  int tool = 1;                    ///< tool number stored in every block

  void validate() const;
};

/// Step between neighbouring passes [mm, along the surface] for which a ball (or the corner of a bull
/// nose) of radius `radius` leaves scallops of height h on a surface of normal curvature `curvature`
/// across the passes [1/mm] (positive convex towards the tool, negative concave). Flat surface:
/// 2·sqrt(h·(2R − h)). Curved: the two tool centres on the offset circle of radius ρ ± R and the cusp at
/// ρ ± h from the centre of curvature give cos(θ/2) = ((ρ + h)² + (ρ + R)² − R²) / (2 (ρ + h)(ρ + R))
/// with signed ρ = 1/curvature, step = |ρ|·θ.
double scallop_step(double radius, double scallop_height, double curvature);

/// Raster tool path over the whole surface. Throws std::invalid_argument for bad options (a flat end
/// mill needs an explicit step_over) and netshape::Error if a pass cannot be sampled.
toolpath::Toolpath raster_toolpath(const NurbsSurface& surface, const RasterOptions& options);

}  // namespace netshape::geometry

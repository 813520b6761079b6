#pragma once
/// \file geometry.hpp  Area umbrella of netshape::geometry (one include per concept header of the area).
#include "netshape/geometry/basis.hpp"
#include "netshape/geometry/nurbs_curve.hpp"
#include "netshape/geometry/nurbs_surface.hpp"
#include "netshape/geometry/primitives.hpp"
#include "netshape/geometry/offset.hpp"
#include "netshape/geometry/cutter_location.hpp"
#include "netshape/geometry/raster.hpp"
#include "netshape/geometry/triangle_mesh.hpp"
#include "netshape/geometry/stl.hpp"
#include "netshape/geometry/contour_offset.hpp"

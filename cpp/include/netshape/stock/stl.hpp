#pragma once
/// \file stl.hpp
/// Mesh export of a Z-map as a closed solid (binary STL).
///
/// The mesh joins the node heights (cell centres), so it spans [x0 + dx/2, x1 − dx/2] ×
/// [y0 + dy/2, y1 − dy/2]: top: two triangles per grid square; four walls from the boundary nodes
/// down to `bottom`; the bottom: a fan around its centre. Every edge is shared by exactly two
/// triangles with opposite orientation (outward normals). Triangle count:
/// 2(nx−1)(ny−1) + 6·((nx−1) + (ny−1)). Needs nx, ny ≥ 2.

#include <cstdint>
#include <string>

#include "netshape/stock/zmap.hpp"

namespace netshape::stock {

/// Number of triangles `write_stl` writes.
std::int64_t stl_triangle_count(const ZMap& zmap);

/// Write the Z-map as a binary STL [mm] to `path`, atomically (temporary file in the same folder,
/// then rename): the file is written whole or not at all. Throws std::invalid_argument if the folder
/// does not exist or the grid is smaller than 2 × 2, netshape::Error on I/O failure.
void write_stl(const ZMap& zmap, const std::string& path);

}  // namespace netshape::stock

#pragma once
/// \file stl.hpp
/// STL triangle files, ASCII and binary. Reading merges exactly coincident vertices; writing is atomic
/// (a temporary file renamed over the target, so the file is whole or absent).

#include <string>

#include "netshape/geometry/triangle_mesh.hpp"

namespace netshape::geometry {

/// Vertices and faces read from an STL file.
struct StlData {
  Points3 vertices;   ///< (v, 3) [mm] (units as in the file)
  Faces faces;        ///< (m, 3)
  std::string name;   ///< ASCII "solid" name or the binary header text (trimmed)
};

/// Read an ASCII or binary STL (detected from the size implied by the binary header, then "solid").
/// Throws netshape::ParseError (file, line) on malformed text, std::invalid_argument on truncation.
StlData read_stl(const std::string& path);
/// Read and build a TriangleMesh.
TriangleMesh load_stl(const std::string& path);
/// Write vertices/faces as STL (binary by default) with facet normals from the vertex order.
void write_stl(const std::string& path, const Points3& vertices, const Faces& faces, bool binary = true,
               const std::string& name = "netshape");

}  // namespace netshape::geometry

#pragma once
/// \file stl_writer.hpp
/// The binary STL writer of netshape (meshes of the geometry area, Z-maps of the stock area): an
/// 80-byte header, the triangle count (uint32, little-endian host), then per triangle its unit normal
/// from the vertex order (right-handed: counter-clockwise seen from outside; zero for a degenerate
/// triangle) and its three vertices as float32 [mm], and a zero attribute word. Triangles are streamed
/// through a buffer, so a mesh never has to exist in memory.

#include <array>
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "netshape/core/types.hpp"

namespace netshape {

class BinaryStlWriter {
 public:
  /// Writes the header (`header` truncated to 80 bytes, zero-padded) and `count` triangles to come.
  BinaryStlWriter(std::ostream& out, const std::string& header, std::uint32_t count);
  using Float3 = std::array<float, 3>;
  /// Append one triangle given in double [mm]: the unit normal from these vertices, the vertices stored
  /// as float32.
  void triangle(const Vec3& a, const Vec3& b, const Vec3& c);
  /// Append one triangle given in float32 [mm] (stored as given): the unit normal of the stored vertices
  /// (edge vectors in float, cross product in double).
  void triangle(const Float3& a, const Float3& b, const Float3& c);
  /// Flush the buffer; throws netshape::Error when fewer or more triangles than announced were given.
  void finish();
  std::uint32_t written() const noexcept { return written_; }

 private:
  void flush();
  void put(const Vec3& normal, const float (&v)[3][3]);
  std::ostream& out_;
  std::vector<char> buf_;
  std::uint32_t count_;
  std::uint32_t written_ = 0;
};

}  // namespace netshape

// Binary STL records through a buffer.
#include "netshape/core/stl_writer.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "netshape/core/error.hpp"

namespace netshape {

namespace {
constexpr std::size_t record = 50;        // bytes per triangle
constexpr std::size_t buffered = 4096;    // triangles per write
}  // namespace

BinaryStlWriter::BinaryStlWriter(std::ostream& out, const std::string& header, std::uint32_t count)
    : out_(out), count_(count) {
  char h[80] = {};
  std::memcpy(h, header.data(), std::min<std::size_t>(header.size(), sizeof h));
  out_.write(h, sizeof h);
  out_.write(reinterpret_cast<const char*>(&count_), 4);
  buf_.reserve(record * buffered);
}

void BinaryStlWriter::triangle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 x = (b - a).cross(c - a);
  const Vec3 n = x.norm() > 0 ? Vec3(x.normalized()) : Vec3::Zero();
  const float v[3][3] = {{static_cast<float>(a[0]), static_cast<float>(a[1]), static_cast<float>(a[2])},
                         {static_cast<float>(b[0]), static_cast<float>(b[1]), static_cast<float>(b[2])},
                         {static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2])}};
  put(n, v);
}

void BinaryStlWriter::triangle(const Float3& a, const Float3& b, const Float3& c) {
  // edge vectors in float (the stored values), cross product and length in double
  const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
  const double wx = c[0] - a[0], wy = c[1] - a[1], wz = c[2] - a[2];
  double nx = uy * wz - uz * wy, ny = uz * wx - ux * wz, nz = ux * wy - uy * wx;
  const double n = std::sqrt(nx * nx + ny * ny + nz * nz);
  if (n > 0) {
    nx /= n;
    ny /= n;
    nz /= n;
  }
  const float v[3][3] = {{a[0], a[1], a[2]}, {b[0], b[1], b[2]}, {c[0], c[1], c[2]}};
  put(Vec3(nx, ny, nz), v);
}

void BinaryStlWriter::put(const Vec3& normal, const float (&v)[3][3]) {
  float rec[12] = {static_cast<float>(normal[0]), static_cast<float>(normal[1]), static_cast<float>(normal[2])};
  std::memcpy(rec + 3, v, sizeof v);
  const std::size_t at = buf_.size();
  buf_.resize(at + record);
  std::memcpy(buf_.data() + at, rec, 48);
  buf_[at + 48] = 0;
  buf_[at + 49] = 0;
  ++written_;
  if (buf_.size() >= record * buffered) flush();
}

void BinaryStlWriter::flush() {
  out_.write(buf_.data(), static_cast<std::streamsize>(buf_.size()));
  buf_.clear();
}

void BinaryStlWriter::finish() {
  flush();
  if (written_ != count_)
    throw Error("STL writer: " + std::to_string(written_) + " triangles written, " + std::to_string(count_) +
                " announced");
}

}  // namespace netshape

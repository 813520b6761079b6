#include "netshape/stock/stl.hpp"

#include <array>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <vector>

#include "netshape/core/error.hpp"

namespace netshape::stock {

std::int64_t stl_triangle_count(const ZMap& z) {
  const std::int64_t a = z.nx() - 1, b = z.ny() - 1;
  return 2 * a * b + 6 * (a + b);
}

namespace {
using V = std::array<float, 3>;

class StlWriter {
 public:
  explicit StlWriter(std::ofstream& out) : out_(out) { buf_.reserve(50 * 4096); }
  void tri(const V& a, const V& b, const V& c) {
    // normal from the (counter-clockwise seen from outside) vertex order
    const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
    const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
    double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    const double n = std::sqrt(nx * nx + ny * ny + nz * nz);
    if (n > 0) { nx /= n; ny /= n; nz /= n; }
    const float f[12] = {static_cast<float>(nx), static_cast<float>(ny), static_cast<float>(nz),
                         a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2]};
    const std::size_t at = buf_.size();
    buf_.resize(at + 50);
    std::memcpy(buf_.data() + at, f, 48);
    buf_[at + 48] = 0;
    buf_[at + 49] = 0;
    if (buf_.size() >= 50 * 4096) flush();
    ++count_;
  }
  void flush() {
    out_.write(buf_.data(), static_cast<std::streamsize>(buf_.size()));
    buf_.clear();
  }
  std::int64_t count() const { return count_; }

 private:
  std::ofstream& out_;
  std::vector<char> buf_;
  std::int64_t count_ = 0;
};
}  // namespace

void write_stl(const ZMap& z, const std::string& path) {
  namespace fs = std::filesystem;
  NETSHAPE_CHECK(z.nx() >= 2 && z.ny() >= 2, "zmap.shape", std::to_string(z.ny()) + "x" + std::to_string(z.nx()),
                 "STL export needs at least 2 x 2 nodes");
  NETSHAPE_CHECK(!path.empty(), "path", path, "must not be empty");
  const fs::path target(path);
  fs::path dir = target.parent_path();
  if (dir.empty()) dir = ".";
  NETSHAPE_CHECK(fs::is_directory(dir), "path", path, "its folder does not exist");
  std::random_device rd;
  const fs::path tmp = dir / ("." + target.filename().string() + "." + std::to_string(rd()) + ".tmp");
  const std::int64_t ntri = stl_triangle_count(z);
  NETSHAPE_CHECK(ntri <= 0xFFFFFFFFLL, "zmap.nodes", z.nx() * static_cast<double>(z.ny()), "too many triangles for STL");
  try {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw Error("cannot open '" + tmp.string() + "' for writing");
    char header[80] = {};
    std::snprintf(header, sizeof header, "netshape Z-map %dx%d nodes, mm", z.nx(), z.ny());
    out.write(header, 80);
    const std::uint32_t n32 = static_cast<std::uint32_t>(ntri);
    out.write(reinterpret_cast<const char*>(&n32), 4);
    StlWriter w(out);
    const int nx = z.nx(), ny = z.ny();
    const auto& H = z.heights();
    const float zb = static_cast<float>(z.bottom());
    auto top = [&](int i, int j) -> V {
      return {static_cast<float>(z.node_x(j)), static_cast<float>(z.node_y(i)), static_cast<float>(H(i, j))};
    };
    auto bot = [&](int i, int j) -> V { return {static_cast<float>(z.node_x(j)), static_cast<float>(z.node_y(i)), zb}; };
    // top (normals up): counter-clockwise seen from +Z
    for (int i = 0; i + 1 < ny; ++i)
      for (int j = 0; j + 1 < nx; ++j) {
        w.tri(top(i, j), top(i, j + 1), top(i + 1, j + 1));
        w.tri(top(i, j), top(i + 1, j + 1), top(i + 1, j));
      }
    // walls: boundary loop counter-clockwise seen from +Z; outward normals
    std::vector<std::array<int, 2>> loop;
    loop.reserve(2 * (nx + ny));
    for (int j = 0; j + 1 < nx; ++j) loop.push_back({0, j});
    for (int i = 0; i + 1 < ny; ++i) loop.push_back({i, nx - 1});
    for (int j = nx - 1; j > 0; --j) loop.push_back({ny - 1, j});
    for (int i = ny - 1; i > 0; --i) loop.push_back({i, 0});
    const std::size_t m = loop.size();
    for (std::size_t k = 0; k < m; ++k) {
      const auto p = loop[k], q = loop[(k + 1) % m];
      w.tri(bot(p[0], p[1]), bot(q[0], q[1]), top(q[0], q[1]));
      w.tri(bot(p[0], p[1]), top(q[0], q[1]), top(p[0], p[1]));
    }
    // bottom: fan about the centre, clockwise seen from +Z (normals down)
    const V c = {static_cast<float>(0.5 * (z.node_x(0) + z.node_x(nx - 1))),
                 static_cast<float>(0.5 * (z.node_y(0) + z.node_y(ny - 1))), zb};
    for (std::size_t k = 0; k < m; ++k) {
      const auto p = loop[k], q = loop[(k + 1) % m];
      w.tri(c, bot(q[0], q[1]), bot(p[0], p[1]));
    }
    w.flush();
    out.flush();
    if (!out) throw Error("writing '" + tmp.string() + "' failed");
    out.close();
    if (w.count() != ntri) throw Error("internal: STL triangle count mismatch");
    fs::rename(tmp, target);
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
}

}  // namespace netshape::stock

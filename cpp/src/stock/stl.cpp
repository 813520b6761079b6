#include "netshape/stock/stl.hpp"

#include <array>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "netshape/core/atomic_file.hpp"
#include "netshape/core/error.hpp"
#include "netshape/core/stl_writer.hpp"

namespace netshape::stock {

std::int64_t stl_triangle_count(const ZMap& z) {
  const std::int64_t a = z.nx() - 1, b = z.ny() - 1;
  return 2 * a * b + 6 * (a + b);
}

void write_stl(const ZMap& z, const std::string& path) {
  NETSHAPE_CHECK(z.nx() >= 2 && z.ny() >= 2, "zmap.shape", std::to_string(z.ny()) + "x" + std::to_string(z.nx()),
                 "STL export needs at least 2 x 2 nodes");
  const std::int64_t ntri = stl_triangle_count(z);
  NETSHAPE_CHECK(ntri <= 0xFFFFFFFFLL, "zmap.nodes", z.nx() * static_cast<double>(z.ny()), "too many triangles for STL");
  char header[80] = {};
  std::snprintf(header, sizeof header, "netshape Z-map %dx%d nodes, mm", z.nx(), z.ny());
  write_file_atomically(path, [&](std::ostream& out) {
    BinaryStlWriter w(out, header, static_cast<std::uint32_t>(ntri));
    const int nx = z.nx(), ny = z.ny();
    const auto& H = z.heights();
    // vertices in float32, so the normals are those of the stored vertices
    using F3 = BinaryStlWriter::Float3;
    auto f = [](double x) { return static_cast<float>(x); };
    const float zb = f(z.bottom());
    auto top = [&](int i, int j) { return F3{f(z.node_x(j)), f(z.node_y(i)), f(H(i, j))}; };
    auto bot = [&](int i, int j) { return F3{f(z.node_x(j)), f(z.node_y(i)), zb}; };
    // top (normals up): counter-clockwise seen from +Z
    for (int i = 0; i + 1 < ny; ++i)
      for (int j = 0; j + 1 < nx; ++j) {
        w.triangle(top(i, j), top(i, j + 1), top(i + 1, j + 1));
        w.triangle(top(i, j), top(i + 1, j + 1), top(i + 1, j));
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
      w.triangle(bot(p[0], p[1]), bot(q[0], q[1]), top(q[0], q[1]));
      w.triangle(bot(p[0], p[1]), top(q[0], q[1]), top(p[0], p[1]));
    }
    // bottom: fan about the centre, clockwise seen from +Z (normals down)
    const F3 c{f(0.5 * (z.node_x(0) + z.node_x(nx - 1))), f(0.5 * (z.node_y(0) + z.node_y(ny - 1))), zb};
    for (std::size_t k = 0; k < m; ++k) {
      const auto p = loop[k], q = loop[(k + 1) % m];
      w.triangle(c, bot(q[0], q[1]), bot(p[0], p[1]));
    }
    w.finish();
  });
}

}  // namespace netshape::stock

#include <doctest/doctest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <tuple>
#include <vector>

#include <unistd.h>

#include "netshape/stock/stl.hpp"
#include "netshape/stock/sweep.hpp"

using netshape::Vec3;
using netshape::stock::ZMap;

TEST_CASE("stl: closed, outward oriented solid with the documented triangle count") {
  ZMap z(0.0, 10.0, 0.0, 6.0, 0.5, 5.0, 1.0);
  netshape::stock::sweep_line(z, netshape::cutter::Cutter::ball_end(4.0, 2, 0.5), Vec3(-1, 3, 3), Vec3(11, 3, 3));
  // one folder per process: ctest runs this test under several instruction sets at once
  const auto dir = std::filesystem::temp_directory_path() / ("netshape_test_stl_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto path = (dir / "z.stl").string();
  netshape::stock::write_stl(z, path);
  std::ifstream in(path, std::ios::binary);
  std::vector<char> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::uint32_t n;
  std::memcpy(&n, data.data() + 80, 4);
  CHECK(n == netshape::stock::stl_triangle_count(z));
  CHECK(data.size() == 84 + 50 * std::size_t(n));
  // every directed edge once, and its reverse once: closed and consistently oriented
  using P = std::tuple<float, float, float>;
  std::map<std::pair<P, P>, int> edges;
  double signed_volume = 0.0;
  for (std::uint32_t t = 0; t < n; ++t) {
    float f[12];
    std::memcpy(f, data.data() + 84 + 50 * t, 48);
    P v[3] = {{f[3], f[4], f[5]}, {f[6], f[7], f[8]}, {f[9], f[10], f[11]}};
    for (int k = 0; k < 3; ++k) ++edges[{v[k], v[(k + 1) % 3]}];
    const Vec3 a(f[3], f[4], f[5]), b(f[6], f[7], f[8]), c(f[9], f[10], f[11]);
    signed_volume += a.dot(b.cross(c)) / 6.0;
  }
  bool closed = true;
  for (const auto& [e, count] : edges) closed = closed && count == 1 && edges.count({e.second, e.first}) == 1;
  CHECK(closed);
  CHECK(signed_volume > 0.0);  // outward normals
  CHECK_THROWS_WITH_AS(netshape::stock::write_stl(z, "/nonexistent-folder/x.stl"), doctest::Contains("folder"),
                       std::invalid_argument);
  ZMap thin(0.0, 1.0, 0.0, 10.0, 1.0, 1.0, 0.0);
  CHECK_THROWS_AS(netshape::stock::write_stl(thin, (dir / "t.stl").string()),
                  std::invalid_argument);
  std::filesystem::remove_all(dir);
}

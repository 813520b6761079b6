// Atomic output files and the binary STL writer (core): a failed write leaves the target as it was and
// no temporary file behind; the STL records are the documented 50-byte layout.
#include <doctest/doctest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unistd.h>

#include "netshape/core/atomic_file.hpp"
#include "netshape/core/error.hpp"
#include "netshape/core/stl_writer.hpp"

using namespace netshape;
namespace fs = std::filesystem;

namespace {
std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}
}  // namespace

TEST_CASE("write_file_atomically: whole or not at all") {
  const fs::path dir = fs::temp_directory_path() / ("netshape_atomic_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path target = dir / "out.txt";
  write_file_atomically(target.string(), [](std::ostream& o) { o << "first"; }, false);
  CHECK(slurp(target) == "first");
  CHECK_THROWS_AS(write_file_atomically(target.string(),
                                        [](std::ostream& o) {
                                          o << "half";
                                          throw std::runtime_error("disk full");
                                        }),
                  std::runtime_error);
  CHECK(slurp(target) == "first");  // untouched
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir)) files += e.is_regular_file() ? 1 : 0;
  CHECK(files == 1);  // no temporary file left
  CHECK_THROWS_WITH_AS(write_file_atomically((dir / "no" / "x.txt").string(), [](std::ostream&) {}),
                       doctest::Contains("folder does not exist"), std::invalid_argument);
  fs::remove_all(dir);
}

TEST_CASE("BinaryStlWriter: header, count, normal and vertices per record") {
  std::ostringstream os;
  BinaryStlWriter w(os, "unit", 2);
  w.triangle(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0));                      // normal +Z
  w.triangle(BinaryStlWriter::Float3{0, 0, 0}, {0, 0, 1}, {1, 0, 0});           // (0,0,1) × (1,0,0): normal +Y
  w.finish();
  const std::string s = os.str();
  REQUIRE(s.size() == 84 + 2 * 50);
  CHECK(std::string(s.data(), 4) == "unit");
  std::uint32_t n = 0;
  std::memcpy(&n, s.data() + 80, 4);
  CHECK(n == 2);
  float r[12];
  std::memcpy(r, s.data() + 84, 48);
  CHECK(r[0] == 0.0f);
  CHECK(r[1] == 0.0f);
  CHECK(r[2] == 1.0f);
  CHECK(r[6] == 1.0f);  // second vertex x
  std::memcpy(r, s.data() + 134, 48);
  CHECK(r[1] == 1.0f);  // (0,0,1) × (1,0,0) = (0,1,0)
  BinaryStlWriter short_one(os, "x", 3);
  short_one.triangle(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0));
  CHECK_THROWS_AS(short_one.finish(), Error);
}

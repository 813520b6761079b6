#include "netshape/geometry/stl.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <array>
#include <vector>

#include "netshape/core/atomic_file.hpp"
#include "netshape/core/error.hpp"
#include "netshape/core/stl_writer.hpp"

namespace netshape::geometry {

namespace {
struct Builder {
  std::map<std::array<double, 3>, std::int64_t> index;
  std::vector<std::array<double, 3>> verts;
  std::vector<std::array<std::int64_t, 3>> faces;
  std::int64_t add(const std::array<double, 3>& p) {
    auto [it, inserted] = index.emplace(p, static_cast<std::int64_t>(verts.size()));
    if (inserted) verts.push_back(p);
    return it->second;
  }
  StlData finish(std::string name) {
    StlData d;
    d.name = std::move(name);
    d.vertices.resize(static_cast<Eigen::Index>(verts.size()), 3);
    for (std::size_t i = 0; i < verts.size(); ++i)
      d.vertices.row(static_cast<Eigen::Index>(i)) << verts[i][0], verts[i][1], verts[i][2];
    d.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
    for (std::size_t i = 0; i < faces.size(); ++i)
      d.faces.row(static_cast<Eigen::Index>(i)) << faces[i][0], faces[i][1], faces[i][2];
    return d;
  }
};

std::string trim(std::string s) {
  for (char& c : s)
    if (!(c >= 32 && c < 127)) c = ' ';
  const auto a = s.find_first_not_of(" \t\r\n");
  if (a == std::string::npos) return "";
  const auto b = s.find_last_not_of(" \t\r\n");
  return s.substr(a, b - a + 1);
}

StlData read_ascii(const std::string& path, const std::string& text) {
  std::istringstream in(text);
  std::string line, name;
  long lineno = 0;
  Builder b;
  std::vector<std::array<double, 3>> loop;
  bool in_solid = false, ended = false;
  while (std::getline(in, line)) {
    ++lineno;
    std::istringstream ls(line);
    std::string word;
    if (!(ls >> word)) continue;
    if (word == "solid") {
      std::getline(ls, name);
      name = trim(name);
      in_solid = true;
    } else if (word == "facet" || word == "outer") {
      // normals are recomputed from the vertex order; "outer loop" starts the vertices
      if (word == "outer") loop.clear();
    } else if (word == "vertex") {
      std::array<double, 3> p{};
      for (int c = 0; c < 3; ++c) {
        std::string tok;
        if (!(ls >> tok)) throw ParseError(path, lineno, 0, "vertex needs three coordinates");
        char* end = nullptr;
        p[c] = std::strtod(tok.c_str(), &end);
        if (end == tok.c_str() || *end != '\0' || !std::isfinite(p[c]))
          throw ParseError(path, lineno, 0, "bad vertex coordinate '" + tok + "'");
      }
      loop.push_back(p);
    } else if (word == "endloop") {
      if (loop.size() != 3)
        throw ParseError(path, lineno, 0, "a facet needs exactly 3 vertices, got " + std::to_string(loop.size()));
      b.faces.push_back({b.add(loop[0]), b.add(loop[1]), b.add(loop[2])});
      loop.clear();
    } else if (word == "endfacet") {
    } else if (word == "endsolid") {
      ended = true;
    } else {
      throw ParseError(path, lineno, 0, "unexpected word '" + word + "' in ASCII STL");
    }
  }
  if (!in_solid) throw ParseError(path, 1, 0, "not an STL file (no 'solid' and not a valid binary STL)");
  if (!ended) throw ParseError(path, lineno, 0, "ASCII STL ends without 'endsolid'");
  if (b.faces.empty()) throw ParseError(path, lineno, 0, "STL holds no facets");
  return b.finish(name);
}
}  // namespace

StlData read_stl(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  NETSHAPE_CHECK(f.good(), "path", path, "cannot open the STL file");
  std::string data((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (data.size() >= 84) {
    std::uint32_t n = 0;
    std::memcpy(&n, data.data() + 80, 4);  // little-endian hosts (x86, ARM)
    if (data.size() == 84 + 50ull * n && n > 0) {
      Builder b;
      for (std::uint32_t k = 0; k < n; ++k) {
        const char* rec = data.data() + 84 + 50ull * k;
        std::array<std::array<double, 3>, 3> tri{};
        for (int v = 0; v < 3; ++v)
          for (int c = 0; c < 3; ++c) {
            float x;
            std::memcpy(&x, rec + 12 + 12 * v + 4 * c, 4);
            NETSHAPE_CHECK(std::isfinite(x), ("facet " + std::to_string(k) + " vertex").c_str(), x, "must be finite");
            tri[v][c] = x;
          }
        b.faces.push_back({b.add(tri[0]), b.add(tri[1]), b.add(tri[2])});
      }
      return b.finish(trim(data.substr(0, 80)));
    }
  }
  if (data.compare(0, 5, "solid") == 0) return read_ascii(path, data);
  throw ParseError(path, 0, 0, data.size() >= 84 ? "not an STL file: binary size does not match its facet count "
                                                   "and the text does not start with 'solid'"
                                                 : "not an STL file: too short");
}

TriangleMesh load_stl(const std::string& path) {
  StlData d = read_stl(path);
  return TriangleMesh(std::move(d.vertices), std::move(d.faces));
}

void write_stl(const std::string& path, const Points3& V, const Faces& F, bool binary, const std::string& name) {
  NETSHAPE_CHECK(F.rows() >= 1, "faces.rows", F.rows(), "need at least one triangle");
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      NETSHAPE_CHECK(F(f, c) >= 0 && F(f, c) < V.rows(), ("faces[" + std::to_string(f) + "]").c_str(), F(f, c),
                     "vertex index out of range");
  auto normal = [&](Eigen::Index f) {
    const Vec3 a = V.row(F(f, 0)).transpose(), b = V.row(F(f, 1)).transpose(), c = V.row(F(f, 2)).transpose();
    const Vec3 x = (b - a).cross(c - a);
    return x.norm() > 0 ? Vec3(x.normalized()) : Vec3::Zero();
  };
  write_file_atomically(path, [&](std::ostream& o) {
    if (binary) {
      BinaryStlWriter w(o, name, static_cast<std::uint32_t>(F.rows()));
      for (Eigen::Index f = 0; f < F.rows(); ++f)
        w.triangle(V.row(F(f, 0)).transpose(), V.row(F(f, 1)).transpose(), V.row(F(f, 2)).transpose());
      w.finish();
      return;
    }
    o.precision(17);
    o << "solid " << name << "\n";
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
      const Vec3 nn = normal(f);
      o << "  facet normal " << nn.x() << ' ' << nn.y() << ' ' << nn.z() << "\n    outer loop\n";
      for (int v = 0; v < 3; ++v)
        o << "      vertex " << V(F(f, v), 0) << ' ' << V(F(f, v), 1) << ' ' << V(F(f, v), 2) << "\n";
      o << "    endloop\n  endfacet\n";
    }
    o << "endsolid " << name << "\n";
  }, binary);
}

}  // namespace netshape::geometry

// Median-split BVH of the obstacle triangles (see triangle_bvh.hpp).
#include "posture/triangle_bvh.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace netshape::detail {

namespace {
constexpr int kLeafSize = 4;

struct Builder {
  std::vector<Vec3> a, b, c, centre;
  std::vector<int> order;
  std::vector<BvhNode>& nodes;

  int build(int first, int count) {
    BvhNode node{Vec3::Constant(INFINITY), Vec3::Constant(-INFINITY), first, 0, -1, -1};
    Vec3 clo = node.lo, chi = node.hi;
    for (int k = first; k < first + count; ++k) {
      const int t = order[static_cast<std::size_t>(k)];
      for (const Vec3* p : {&a[t], &b[t], &c[t]}) {
        node.lo = node.lo.cwiseMin(*p);
        node.hi = node.hi.cwiseMax(*p);
      }
      clo = clo.cwiseMin(centre[t]);
      chi = chi.cwiseMax(centre[t]);
    }
    const int index = static_cast<int>(nodes.size());
    nodes.push_back(node);
    if (count <= kLeafSize) {
      nodes[static_cast<std::size_t>(index)].count = count;
      return index;
    }
    int dim;
    (chi - clo).maxCoeff(&dim);
    const int half = count / 2;
    auto begin = order.begin() + first;
    std::nth_element(begin, begin + half, begin + count,
                     [&](int i, int j) { return centre[i][dim] < centre[j][dim]; });
    const int left = build(first, half);
    const int right = build(first + half, count - half);
    nodes[static_cast<std::size_t>(index)].left = left;
    nodes[static_cast<std::size_t>(index)].right = right;
    return index;
  }
};
}  // namespace

TriangleBvh::TriangleBvh(const geometry::TriangleMesh& mesh) {
  const Points3& V = mesh.vertices();
  const geometry::Faces& F = mesh.faces();
  Builder bld{{}, {}, {}, {}, {}, nodes};
  const double scale = std::max((mesh.bbox_max() - mesh.bbox_min()).norm(), 1e-300);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Vec3 p = V.row(F(f, 0)).transpose(), q = V.row(F(f, 1)).transpose(), r = V.row(F(f, 2)).transpose();
    if (0.5 * (q - p).cross(r - p).norm() <= 1e-14 * scale * scale) continue;  // as TriangleMesh's tree
    bld.a.push_back(p);
    bld.b.push_back(q);
    bld.c.push_back(r);
    bld.centre.push_back((p + q + r) / 3.0);
  }
  bld.order.resize(bld.a.size());
  std::iota(bld.order.begin(), bld.order.end(), 0);
  nodes.reserve(2 * bld.a.size() / kLeafSize + 2);
  bld.build(0, static_cast<int>(bld.a.size()));
  for (int t : bld.order) {
    a.push_back(bld.a[static_cast<std::size_t>(t)]);
    b.push_back(bld.b[static_cast<std::size_t>(t)]);
    c.push_back(bld.c[static_cast<std::size_t>(t)]);
    const Vec3 &p = a.back(), &q = b.back(), &s = c.back();
    lo.push_back(p.cwiseMin(q).cwiseMin(s));
    hi.push_back(p.cwiseMax(q).cwiseMax(s));
    m.push_back((p + q + s) / 3.0);
    r.push_back(std::sqrt(std::max({(p - m.back()).squaredNorm(), (q - m.back()).squaredNorm(),
                                    (s - m.back()).squaredNorm()})));
    n.push_back((q - p).cross(s - p).normalized());
    d.push_back(n.back().dot(p));
  }
}

}  // namespace netshape::detail

// The only translation unit of netshape::geometry's meshes that sees CGAL (AABB tree, Simple_cartesian<double>).
#include "netshape/geometry/triangle_mesh.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "netshape/core/error.hpp"

namespace netshape::geometry {

namespace {
using K = CGAL::Simple_cartesian<double>;
using Point = K::Point_3;
using Triangle = K::Triangle_3;
using Iterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<K, Iterator>;
using Traits = CGAL::AABB_traits<K, Primitive>;
using Tree = CGAL::AABB_tree<Traits>;

inline Point to_point(const Eigen::Ref<const Points3>& a, Eigen::Index k) { return Point(a(k, 0), a(k, 1), a(k, 2)); }
void check_rows(const Eigen::Ref<const Points3>& a, const char* field) {
  for (Eigen::Index k = 0; k < a.rows(); ++k)
    for (int c = 0; c < 3; ++c)
      NETSHAPE_CHECK(std::isfinite(a(k, c)), (std::string(field) + "[" + std::to_string(k) + "]").c_str(), a(k, c),
                     "must be finite [mm]");
}
constexpr double nan = std::numeric_limits<double>::quiet_NaN();
}  // namespace

struct TriangleMesh::Impl {
  Points3 vertices;
  Faces faces;
  std::vector<Triangle> triangles;  // non-degenerate faces only
  std::vector<int> face_of;         // triangles[k] is face face_of[k]
  Tree tree;
  double area = 0.0;
  Vec3 lo, hi;
};

TriangleMesh::TriangleMesh(Points3 vertices, Faces faces) {
  auto impl = std::make_shared<Impl>();
  NETSHAPE_CHECK(vertices.rows() >= 3, "vertices.rows", vertices.rows(), "need at least 3 vertices");
  NETSHAPE_CHECK(faces.rows() >= 1, "faces.rows", faces.rows(), "need at least one triangle");
  check_rows(vertices, "vertices");
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      NETSHAPE_CHECK(faces(f, c) >= 0 && faces(f, c) < vertices.rows(),
                     ("faces[" + std::to_string(f) + "]").c_str(), faces(f, c), "vertex index out of range");
  impl->vertices = std::move(vertices);
  impl->faces = std::move(faces);
  const auto& V = impl->vertices;
  impl->lo = V.colwise().minCoeff().transpose();
  impl->hi = V.colwise().maxCoeff().transpose();
  const double scale = std::max((impl->hi - impl->lo).norm(), 1e-300);
  for (Eigen::Index f = 0; f < impl->faces.rows(); ++f) {
    const Vec3 a = V.row(impl->faces(f, 0)).transpose(), b = V.row(impl->faces(f, 1)).transpose(),
               c = V.row(impl->faces(f, 2)).transpose();
    const double ar = 0.5 * (b - a).cross(c - a).norm();
    impl->area += ar;
    if (ar <= 1e-14 * scale * scale) continue;
    impl->triangles.emplace_back(Point(a.x(), a.y(), a.z()), Point(b.x(), b.y(), b.z()), Point(c.x(), c.y(), c.z()));
    impl->face_of.push_back(static_cast<int>(f));
  }
  NETSHAPE_CHECK(!impl->triangles.empty(), "faces", impl->faces.rows(), "all triangles have zero area");
  impl->tree.insert(impl->triangles.cbegin(), impl->triangles.cend());
  impl->tree.build();
  impl->tree.accelerate_distance_queries();
  impl_ = std::move(impl);
}

TriangleMesh::~TriangleMesh() = default;

TriangleMesh TriangleMesh::from_triangles(const Eigen::Ref<const Points3>& corners) {
  NETSHAPE_CHECK(corners.rows() % 3 == 0 && corners.rows() > 0, "corners.rows", corners.rows(),
                 "must be a positive multiple of 3");
  Faces f(corners.rows() / 3, 3);
  for (Eigen::Index k = 0; k < f.rows(); ++k) f.row(k) << 3 * k, 3 * k + 1, 3 * k + 2;
  return TriangleMesh(Points3(corners), std::move(f));
}

const Points3& TriangleMesh::vertices() const noexcept { return impl_->vertices; }
const Faces& TriangleMesh::faces() const noexcept { return impl_->faces; }
Eigen::Index TriangleMesh::face_count() const noexcept { return impl_->faces.rows(); }
double TriangleMesh::area() const noexcept { return impl_->area; }
Vec3 TriangleMesh::bbox_min() const noexcept { return impl_->lo; }
Vec3 TriangleMesh::bbox_max() const noexcept { return impl_->hi; }

Points3 TriangleMesh::face_normals() const {
  const auto& V = impl_->vertices;
  const auto& F = impl_->faces;
  Points3 n(F.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Vec3 a = V.row(F(f, 0)).transpose(), b = V.row(F(f, 1)).transpose(), c = V.row(F(f, 2)).transpose();
    const Vec3 x = (b - a).cross(c - a);
    const double l = x.norm();
    n.row(f) = (l > 0 ? Vec3(x / l) : Vec3::Zero()).transpose();
  }
  return n;
}

void TriangleMesh::distance(const Eigen::Ref<const Points3>& points, Eigen::Ref<VectorXd> out) const {
  NETSHAPE_CHECK(out.size() == points.rows(), "out.size", out.size(), "must equal points.rows");
  check_rows(points, "points");
  for (Eigen::Index k = 0; k < points.rows(); ++k)
    out[k] = std::sqrt(impl_->tree.squared_distance(to_point(points, k)));
}

VectorXd TriangleMesh::distance(const Eigen::Ref<const Points3>& points) const {
  VectorXd out(points.rows());
  distance(points, out);
  return out;
}

ClosestPoints TriangleMesh::closest_points(const Eigen::Ref<const Points3>& points) const {
  check_rows(points, "points");
  ClosestPoints r;
  r.points.resize(points.rows(), 3);
  r.distances.resize(points.rows());
  r.faces.resize(points.rows());
  for (Eigen::Index k = 0; k < points.rows(); ++k) {
    const Point q = to_point(points, k);
    const auto pp = impl_->tree.closest_point_and_primitive(q);
    r.points.row(k) << pp.first.x(), pp.first.y(), pp.first.z();
    r.distances[k] = std::sqrt(CGAL::squared_distance(q, pp.first));
    r.faces[k] = impl_->face_of[static_cast<std::size_t>(pp.second - impl_->triangles.cbegin())];
  }
  return r;
}

namespace {
// Distance along `dir` (from `o`) of an intersection object (point or segment); +inf if not one.
double hit_param(const Tree::Intersection_and_primitive_id<K::Ray_3>::Type::first_type& obj, const Vec3& o,
                 const Vec3& dir, Vec3& at) {
  if (const Point* p = boost::get<Point>(&obj)) {
    at = Vec3(p->x(), p->y(), p->z());
    return (at - o).dot(dir);
  }
  if (const K::Segment_3* s = boost::get<K::Segment_3>(&obj)) {
    const Vec3 a(s->source().x(), s->source().y(), s->source().z()), b(s->target().x(), s->target().y(), s->target().z());
    const double ta = (a - o).dot(dir), tb = (b - o).dot(dir);
    at = ta <= tb ? a : b;
    return std::min(ta, tb);
  }
  return std::numeric_limits<double>::infinity();
}
}  // namespace

RayHits TriangleMesh::ray_hits(const Eigen::Ref<const Points3>& origins,
                               const Eigen::Ref<const Points3>& directions) const {
  NETSHAPE_CHECK(directions.rows() == origins.rows(), "directions.rows", directions.rows(), "must equal origins.rows");
  check_rows(origins, "origins");
  check_rows(directions, "directions");
  RayHits r;
  const Eigen::Index n = origins.rows();
  r.t.setConstant(n, nan);
  r.points.setConstant(n, 3, nan);
  r.faces.setConstant(n, -1);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Vec3 o = origins.row(k).transpose();
    const Vec3 d = directions.row(k).transpose();
    const double dl = d.norm();
    NETSHAPE_CHECK(dl > 0, ("directions[" + std::to_string(k) + "]").c_str(), dl, "must be non-zero");
    const Vec3 u = d / dl;
    const K::Ray_3 ray(Point(o.x(), o.y(), o.z()), K::Vector_3(u.x(), u.y(), u.z()));
    const auto hit = impl_->tree.first_intersection(ray);
    if (!hit) continue;
    Vec3 at;
    const double t = hit_param(hit->first, o, u, at);
    if (!std::isfinite(t)) continue;
    r.t[k] = std::max(0.0, t);
    r.points.row(k) = at.transpose();
    r.faces[k] = impl_->face_of[static_cast<std::size_t>(hit->second - impl_->triangles.cbegin())];
  }
  return r;
}

RayHits TriangleMesh::segment_hits(const Eigen::Ref<const Points3>& a, const Eigen::Ref<const Points3>& b) const {
  NETSHAPE_CHECK(b.rows() == a.rows(), "b.rows", b.rows(), "must equal a.rows");
  check_rows(a, "a");
  check_rows(b, "b");
  const Eigen::Index n = a.rows();
  RayHits r;
  r.t.setConstant(n, nan);
  r.points.setConstant(n, 3, nan);
  r.faces.setConstant(n, -1);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Vec3 o = a.row(k).transpose(), e = b.row(k).transpose();
    const double len = (e - o).norm();
    NETSHAPE_CHECK(len > 0, ("b[" + std::to_string(k) + "]").c_str(), len, "segment must have non-zero length");
    const Vec3 u = (e - o) / len;
    const K::Segment_3 seg(Point(o.x(), o.y(), o.z()), Point(e.x(), e.y(), e.z()));
    if (!impl_->tree.do_intersect(seg)) continue;
    const K::Ray_3 ray(Point(o.x(), o.y(), o.z()), K::Vector_3(u.x(), u.y(), u.z()));
    const auto hit = impl_->tree.first_intersection(ray);
    if (!hit) continue;
    Vec3 at;
    const double t = hit_param(hit->first, o, u, at);
    if (!std::isfinite(t) || t > len * (1 + 1e-12)) continue;
    r.t[k] = std::clamp(t / len, 0.0, 1.0);
    r.points.row(k) = at.transpose();
    r.faces[k] = impl_->face_of[static_cast<std::size_t>(hit->second - impl_->triangles.cbegin())];
  }
  return r;
}

Eigen::Matrix<bool, Eigen::Dynamic, 1> TriangleMesh::segments_intersect(const Eigen::Ref<const Points3>& a,
                                                                       const Eigen::Ref<const Points3>& b) const {
  NETSHAPE_CHECK(b.rows() == a.rows(), "b.rows", b.rows(), "must equal a.rows");
  check_rows(a, "a");
  check_rows(b, "b");
  Eigen::Matrix<bool, Eigen::Dynamic, 1> out(a.rows());
  for (Eigen::Index k = 0; k < a.rows(); ++k) {
    const Point p = to_point(a, k), q = to_point(b, k);
    out[k] = (p == q) ? impl_->tree.squared_distance(p) == 0.0 : impl_->tree.do_intersect(K::Segment_3(p, q));
  }
  return out;
}

}  // namespace netshape::geometry

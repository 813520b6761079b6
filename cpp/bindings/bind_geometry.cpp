// Bindings of the `geometry` area (netshape._core.geometry). Thin: lambdas only turn out-parameters into
// returns and allocate the NumPy outputs that the C++ calls fill in place.
#include <optional>

#include "default_types.hpp"
#include "netshape/core/error.hpp"
#include "netshape/geometry.hpp"
#include "netshape/toolpath/block_arrays.hpp"

namespace py = pybind11;
using namespace netshape;
using namespace netshape::geometry;
using netshape::py_types::RefPoints2;
using netshape::py_types::RefPoints3;
using netshape::py_types::RefVector;

namespace {
using Map3 = Eigen::Map<Points3>;

// A fresh C-ordered (n, 3) float64 array and an Eigen map onto it.
py::array_t<double> new_points(Eigen::Index n) {
  return py::array_t<double>({static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(3)});
}
Map3 map3(py::array_t<double>& a) { return Map3(a.mutable_data(), a.shape(0), 3); }

py::array_t<double> derivs_array(const MatrixXdR& d, int order) {
  const py::ssize_t D = order + 1;
  py::array_t<double> out({D, D, static_cast<py::ssize_t>(3)});
  std::copy(d.data(), d.data() + d.size(), out.mutable_data());
  return out;
}
}  // namespace

void bind_geometry(py::module_& m) {
  m.def("find_span", [](int count, int degree, double u, const VectorXd& knots) {
    NETSHAPE_CHECK(knots.size() == count + degree + 1, "knots.size", knots.size(), "must equal count + degree + 1");
    return find_span(count, degree, u, knots.data());
  }, py::arg("count"), py::arg("degree"), py::arg("u"), py::arg("knots"));
  m.def("basis_function_derivatives",
        py::overload_cast<double, int, const VectorXd&, int>(&basis_function_derivatives), py::arg("u"),
        py::arg("degree"), py::arg("knots"), py::arg("order") = 0,
        "Non-vanishing basis functions and derivatives at u, (order + 1, degree + 1) (P&T A2.3).");

  py::class_<CurveProjection>(m, "CurveProjection")
      .def_readonly("u", &CurveProjection::u)
      .def_readonly("point", &CurveProjection::point)
      .def_readonly("distance", &CurveProjection::distance)
      .def_readonly("iterations", &CurveProjection::iterations)
      .def_readonly("converged", &CurveProjection::converged)
      .def("__repr__", [](const CurveProjection& r) {
        return "CurveProjection(u=" + std::to_string(r.u) + ", distance=" + std::to_string(r.distance) + ")";
      });

  py::class_<SurfaceProjection>(m, "SurfaceProjection")
      .def_readonly("u", &SurfaceProjection::u)
      .def_readonly("v", &SurfaceProjection::v)
      .def_readonly("point", &SurfaceProjection::point)
      .def_readonly("normal", &SurfaceProjection::normal)
      .def_readonly("distance", &SurfaceProjection::distance)
      .def_readonly("iterations", &SurfaceProjection::iterations)
      .def_readonly("converged", &SurfaceProjection::converged)
      .def("__repr__", [](const SurfaceProjection& r) {
        return "SurfaceProjection(u=" + std::to_string(r.u) + ", v=" + std::to_string(r.v) +
               ", distance=" + std::to_string(r.distance) + ")";
      });

  py::class_<NurbsCurve>(m, "NurbsCurve")
      .def(py::init([](int degree, VectorXd knots, Points3 cps, std::optional<VectorXd> w) {
             return NurbsCurve(degree, std::move(knots), std::move(cps), w ? *w : VectorXd());
           }),
           py::arg("degree"), py::arg("knots"), py::arg("control_points"), py::arg("weights") = py::none())
      .def_property_readonly("degree", &NurbsCurve::degree)
      .def_property_readonly("count", &NurbsCurve::count)
      .def_property_readonly("knots", &NurbsCurve::knots)
      .def_property_readonly("control_points", &NurbsCurve::control_points)
      .def_property_readonly("weights", &NurbsCurve::weights)
      .def_property_readonly("is_rational", &NurbsCurve::is_rational)
      .def_property_readonly("domain", &NurbsCurve::domain)
      .def("point", &NurbsCurve::point, py::arg("u"))
      .def("derivatives", &NurbsCurve::derivatives, py::arg("u"), py::arg("order"))
      .def("tangent", &NurbsCurve::tangent, py::arg("u"))
      .def("evaluate", &NurbsCurve::evaluate, py::arg("us"), py::call_guard<py::gil_scoped_release>())
      .def("sample", &NurbsCurve::sample, py::arg("count"))
      .def("insert_knot", &NurbsCurve::insert_knot, py::arg("u"), py::arg("times") = 1)
      .def("knot_multiplicity", &NurbsCurve::knot_multiplicity, py::arg("u"))
      .def("closest_point", &NurbsCurve::closest_point, py::arg("point"), py::arg("tolerance") = 1e-10,
           py::arg("max_iterations") = 50);

  py::class_<NurbsSurface>(m, "NurbsSurface")
      .def(py::init([](int p, int q, VectorXd ku, VectorXd kv, Points3 cps, std::optional<VectorXd> w) {
             return NurbsSurface(p, q, std::move(ku), std::move(kv), std::move(cps), w ? *w : VectorXd());
           }),
           py::arg("degree_u"), py::arg("degree_v"), py::arg("knots_u"), py::arg("knots_v"),
           py::arg("control_points"), py::arg("weights") = py::none())
      .def_property_readonly("degree_u", &NurbsSurface::degree_u)
      .def_property_readonly("degree_v", &NurbsSurface::degree_v)
      .def_property_readonly("count_u", &NurbsSurface::count_u)
      .def_property_readonly("count_v", &NurbsSurface::count_v)
      .def_property_readonly("knots_u", &NurbsSurface::knots_u)
      .def_property_readonly("knots_v", &NurbsSurface::knots_v)
      .def_property_readonly("control_points", &NurbsSurface::control_points)
      .def_property_readonly("weights", &NurbsSurface::weights)
      .def_property_readonly("is_rational", &NurbsSurface::is_rational)
      .def_property_readonly("domain_u", &NurbsSurface::domain_u)
      .def_property_readonly("domain_v", &NurbsSurface::domain_v)
      .def_property_readonly("size", &NurbsSurface::size)
      .def("point", &NurbsSurface::point, py::arg("u"), py::arg("v"))
      .def("derivatives", [](const NurbsSurface& s, double u, double v, int order) {
             return derivs_array(s.derivatives(u, v, order), order);
           }, py::arg("u"), py::arg("v"), py::arg("order"))
      .def("normal", &NurbsSurface::normal, py::arg("u"), py::arg("v"))
      .def("evaluate", [](const NurbsSurface& s, RefPoints2 uv) {
             auto pts = new_points(uv.rows());
             Map3 P = map3(pts);
             Points3 none(0, 3);
             {
               py::gil_scoped_release rel;
               SurfaceWorkspace ws = s.make_workspace();
               s.evaluate(uv, P, none, ws);
             }
             return pts;
           }, py::arg("uv"))
      .def("evaluate_with_normals", [](const NurbsSurface& s, RefPoints2 uv) {
             auto pts = new_points(uv.rows()), nrm = new_points(uv.rows());
             Map3 P = map3(pts), N = map3(nrm);
             {
               py::gil_scoped_release rel;
               SurfaceWorkspace ws = s.make_workspace();
               s.evaluate(uv, P, N, ws);
             }
             return py::make_tuple(pts, nrm);
           }, py::arg("uv"))
      .def("evaluate_grid", [](const NurbsSurface& s, RefVector us, RefVector vs, bool normals) {
             const Eigen::Index n = us.size() * vs.size();
             auto pts = new_points(n);
             auto nrm = new_points(normals ? n : 0);
             Map3 P = map3(pts), N = map3(nrm);
             {
               py::gil_scoped_release rel;
               SurfaceWorkspace ws = s.make_workspace();
               s.evaluate_grid(us, vs, P, N, ws);
             }
             if (normals) return py::object(py::make_tuple(pts, nrm));
             return py::object(pts);
           }, py::arg("us"), py::arg("vs"), py::arg("normals") = true)
      .def("insert_knot_u", &NurbsSurface::insert_knot_u, py::arg("u"), py::arg("times") = 1)
      .def("insert_knot_v", &NurbsSurface::insert_knot_v, py::arg("v"), py::arg("times") = 1)
      .def("swap_uv", &NurbsSurface::swap_uv, "S'(v, u) = S(u, v): same shape, normals flipped.")
      .def("iso_curve_u", &NurbsSurface::iso_curve_u, py::arg("u"))
      .def("iso_curve_v", &NurbsSurface::iso_curve_v, py::arg("v"))
      .def("closest_point", &NurbsSurface::closest_point, py::arg("point"), py::arg("tolerance") = 1e-10,
           py::arg("max_iterations") = 50)
      .def("closest_points", [](const NurbsSurface& s, RefPoints3 pts, double tol, int iters) {
             std::vector<SurfaceProjection> r;
             {
               py::gil_scoped_release rel;
               r = s.closest_points(pts, tol, iters);
             }
             const auto n = static_cast<py::ssize_t>(r.size());
             py::array_t<double> uv({n, py::ssize_t(2)}), d(n);
             auto P = new_points(n), N = new_points(n);
             py::array_t<bool> conv(n);
             for (py::ssize_t k = 0; k < n; ++k) {
               uv.mutable_at(k, 0) = r[k].u;
               uv.mutable_at(k, 1) = r[k].v;
               d.mutable_at(k) = r[k].distance;
               conv.mutable_at(k) = r[k].converged;
               for (int c = 0; c < 3; ++c) {
                 P.mutable_at(k, c) = r[k].point[c];
                 N.mutable_at(k, c) = r[k].normal[c];
               }
             }
             py::dict out;
             out["uv"] = uv;
             out["point"] = P;
             out["normal"] = N;
             out["distance"] = d;
             out["converged"] = conv;
             return out;
           }, py::arg("points"), py::arg("tolerance") = 1e-10, py::arg("max_iterations") = 50,
           "Batched projection: dict of uv (n, 2), point (n, 3), normal (n, 3), distance (n,), converged (n,).");

  m.def("circular_arc", &circular_arc, py::arg("center"), py::arg("x_axis"), py::arg("y_axis"), py::arg("radius"),
        py::arg("start"), py::arg("end"));
  m.def("revolve", &revolve, py::arg("profile"), py::arg("axis_point"), py::arg("axis_direction"),
        py::arg("angle"));
  m.def("bilinear", &bilinear, py::arg("p00"), py::arg("p10"), py::arg("p01"), py::arg("p11"));

  // ---- offsets, CC→CL, raster ----------------------------------------------------------------------
  m.def("offset_points", [](const NurbsSurface& s, RefPoints2 uv, double d) {
          auto out = new_points(uv.rows());
          Map3 O = map3(out);
          {
            py::gil_scoped_release rel;
            SurfaceWorkspace ws = s.make_workspace();
            Points3 none(0, 3);
            offset_points(s, uv, d, O, none, ws);
          }
          return out;
        }, py::arg("surface"), py::arg("uv"), py::arg("distance"));
  m.def("offset_grid", &offset_grid, py::arg("surface"), py::arg("us"), py::arg("vs"), py::arg("distance"),
        py::call_guard<py::gil_scoped_release>());
  m.def("_cc_to_cl", [](const cutter::Cutter& c, RefPoints3 cc, RefPoints3 normals, const Vec3& axis) {
          auto out = new_points(cc.rows());
          Map3 O = map3(out);
          cc_to_cl(c, cc, normals, axis, O);
          return out;
        }, py::arg("cutter"), py::arg("cc"), py::arg("normals"), py::arg("axis"));
  m.def("_cutter_signed_distance", &cutter_signed_distance, py::arg("cutter"), py::arg("tip"), py::arg("axis"),
        py::arg("points"));
  m.def("scallop_step", &scallop_step, py::arg("radius"), py::arg("scallop_height"), py::arg("curvature") = 0.0);
  m.def("_raster_toolpath", [](const NurbsSurface& s, const cutter::Cutter& c, const Vec3& axis, double scallop_height, double step_over, double chord_tolerance,
                               double stock_allowance, bool along_u, bool zigzag, double feed, double plunge_feed,
                               double clearance, double spindle_rpm, int tool) {
          RasterOptions o;
          o.cutter = c;
          o.axis = axis;
          o.scallop_height = scallop_height;
          o.step_over = step_over;
          o.chord_tolerance = chord_tolerance;
          o.stock_allowance = stock_allowance;
          o.along_u = along_u;
          o.zigzag = zigzag;
          o.feed = feed;
          o.plunge_feed = plunge_feed;
          o.clearance = clearance;
          o.spindle_rpm = spindle_rpm;
          o.tool = tool;
          toolpath::Toolpath tp;
          {
            py::gil_scoped_release rel;
            tp = raster_toolpath(s, o);
          }
          toolpath::BlockArrays arrays = toolpath::BlockArrays::from_blocks(tp.blocks);
          return py::make_tuple(std::move(arrays), std::move(tp));
        });

  // ---- triangle meshes (CGAL AABB tree behind a pimpl) ---------------------------------------------
  py::class_<TriangleMesh>(m, "TriangleMesh")
      .def(py::init<Points3, Faces>(), py::arg("vertices"), py::arg("faces"))
      .def_static("from_triangles", &TriangleMesh::from_triangles, py::arg("corners"))
      .def_property_readonly("vertices", &TriangleMesh::vertices)
      .def_property_readonly("faces", &TriangleMesh::faces)
      .def_property_readonly("face_count", &TriangleMesh::face_count)
      .def_property_readonly("area", &TriangleMesh::area)
      .def_property_readonly("bbox_min", &TriangleMesh::bbox_min)
      .def_property_readonly("bbox_max", &TriangleMesh::bbox_max)
      .def("face_normals", &TriangleMesh::face_normals)
      .def("distance", [](const TriangleMesh& mesh, RefPoints3 pts) {
             py::array_t<double> out(pts.rows());
             Eigen::Map<VectorXd> o(out.mutable_data(), pts.rows());
             {
               py::gil_scoped_release rel;
               mesh.distance(pts, o);
             }
             return out;
           }, py::arg("points"))
      .def("closest_points", [](const TriangleMesh& mesh, RefPoints3 pts) {
             ClosestPoints r;
             {
               py::gil_scoped_release rel;
               r = mesh.closest_points(pts);
             }
             return py::make_tuple(r.points, r.distances, r.faces);
           }, py::arg("points"), "(points (n, 3), distances (n,), faces (n,))")
      .def("ray_hits", [](const TriangleMesh& mesh, RefPoints3 o, RefPoints3 d) {
             RayHits r;
             {
               py::gil_scoped_release rel;
               r = mesh.ray_hits(o, d);
             }
             return py::make_tuple(r.t, r.points, r.faces);
           }, py::arg("origins"), py::arg("directions"), "(t (n,) [mm] or NaN, points (n, 3), faces (n,) or -1)")
      .def("segment_hits", [](const TriangleMesh& mesh, RefPoints3 a, RefPoints3 b) {
             RayHits r;
             {
               py::gil_scoped_release rel;
               r = mesh.segment_hits(a, b);
             }
             return py::make_tuple(r.t, r.points, r.faces);
           }, py::arg("a"), py::arg("b"), "(t (n,) in [0, 1] or NaN, points (n, 3), faces (n,) or -1)")
      .def("segments_intersect", &TriangleMesh::segments_intersect, py::arg("a"), py::arg("b"),
           py::call_guard<py::gil_scoped_release>());

  m.def("read_stl", [](const std::string& path) {
          StlData d = read_stl(path);
          return py::make_tuple(d.vertices, d.faces, d.name);
        }, py::arg("path"), "(vertices (v, 3), faces (m, 3), name)");
  m.def("load_stl", &load_stl, py::arg("path"));
  m.def("write_stl", &write_stl, py::arg("path"), py::arg("vertices"), py::arg("faces"), py::arg("binary") = true,
        py::arg("name") = "netshape");

  // ---- 2-D contour offsets (CGAL circle-segment offsets) -------------------------------------------
  auto ring_dict = [](const OffsetRing& r) {
    const auto n = static_cast<py::ssize_t>(r.blocks.size());
    py::array_t<std::uint8_t> kind(n);
    py::array_t<double> start({n, py::ssize_t(2)}), end({n, py::ssize_t(2)}), center({n, py::ssize_t(2)});
    py::array_t<bool> cw(n);
    for (py::ssize_t i = 0; i < n; ++i) {
      const auto& b = r.blocks[i];
      kind.mutable_at(i) = static_cast<std::uint8_t>(b.kind);
      for (int c = 0; c < 2; ++c) {
        start.mutable_at(i, c) = b.start[c];
        end.mutable_at(i, c) = b.end[c];
        center.mutable_at(i, c) = b.center[c];
      }
      cw.mutable_at(i) = b.clockwise;
    }
    py::dict d;
    d["kind"] = kind;
    d["start"] = start;
    d["end"] = end;
    d["center"] = center;
    d["clockwise"] = cw;
    d["hole"] = r.hole;
    d["area"] = r.area();
    d["polyline"] = r.polyline(1e-3);
    return d;
  };
  m.def("_offset_region", [ring_dict](const Points2& outer, const std::vector<Points2>& islands, double d,
                                      double tol) {
          Region reg{outer, islands};
          std::vector<OffsetRing> rings;
          {
            py::gil_scoped_release rel;
            rings = offset_region(reg, d, tol);
          }
          py::list out;
          for (const auto& r : rings) out.append(ring_dict(r));
          return out;
        }, py::arg("outer"), py::arg("islands"), py::arg("distance"), py::arg("tolerance") = 1e-6);
  m.def("_pocket_rings", [ring_dict](const Points2& outer, const std::vector<Points2>& islands, double R,
                                     double step, double tol) {
          Region reg{outer, islands};
          std::vector<std::vector<OffsetRing>> levels;
          {
            py::gil_scoped_release rel;
            levels = pocket_rings(reg, R, step, tol);
          }
          py::list out;
          for (const auto& lv : levels) {
            py::list l;
            for (const auto& r : lv) l.append(ring_dict(r));
            out.append(l);
          }
          return out;
        }, py::arg("outer"), py::arg("islands"), py::arg("tool_radius"), py::arg("step_over"),
        py::arg("tolerance") = 1e-6);

  m.def("_pocket_toolpath", [](const Points2& outer, const std::vector<Points2>& islands, double R, double step,
                               double z, double clearance, double feed, double rpm, int tool, double tol) {
          Region reg{outer, islands};
          py::gil_scoped_release rel;
          return rings_toolpath(pocket_rings(reg, R, step, tol), z, clearance, feed, rpm, tool);
        }, py::arg("outer"), py::arg("islands"), py::arg("tool_radius"), py::arg("step_over"), py::arg("z"),
        py::arg("clearance"), py::arg("feed"), py::arg("spindle_rpm"), py::arg("tool"), py::arg("tolerance"));
}

// GJK distance bounds between a triangle and a frustum (see convex_distance.hpp).
#include "posture/convex_distance.hpp"

#include <algorithm>
#include <cmath>

namespace netshape::detail {

namespace {
// Closest point of the segment a–b to p with the weights of a and b.
Vec3 closest_on_segment(const Vec3& p, const Vec3& a, const Vec3& b, double& wa, double& wb) {
  const Vec3 d = b - a;
  const double dd = d.squaredNorm();
  const double t = dd > 0 ? std::clamp((p - a).dot(d) / dd, 0.0, 1.0) : 0.0;
  wa = 1.0 - t;
  wb = t;
  return a + t * d;
}
}  // namespace

Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, Vec3* bary) {
  auto done = [&](double wa, double wb, double wc, const Vec3& q) {
    if (bary) *bary = Vec3(wa, wb, wc);
    return q;
  };
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return done(1, 0, 0, a);
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return done(0, 1, 0, b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double t = d1 / (d1 - d3);
    return done(1 - t, t, 0, a + t * ab);
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return done(0, 0, 1, c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double t = d2 / (d2 - d6);
    return done(1 - t, 0, t, a + t * ac);
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return done(0, 1 - t, t, b + t * (c - b));
  }
  const double den = va + vb + vc;
  if (!(den > 1e-300)) {  // degenerate (collinear) triangle: the best of its edges
    Vec3 best = a, w(1.0, 0.0, 0.0);
    double bd = INFINITY, s, t;
    const Vec3* v[3] = {&a, &b, &c};
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3;
      const Vec3 q = closest_on_segment(p, *v[i], *v[j], s, t);
      if ((q - p).squaredNorm() < bd) {
        bd = (q - p).squaredNorm();
        best = q;
        w.setZero();
        w[i] = s;
        w[j] = t;
      }
    }
    return done(w[0], w[1], w[2], best);
  }
  const double v = vb / den, t = vc / den;
  return done(1 - v - t, v, t, a + v * ab + t * ac);
}

namespace {
// Squared distance between the segments p0–p1 and q0–q1 (Ericson, "Real-Time Collision Detection" §5.1.9).
double segment_segment2(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0.0, t = 0.0;
  if (a <= 1e-300 && e <= 1e-300) return r.squaredNorm();
  if (a <= 1e-300) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= 1e-300) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), den = a * e - b * b;
      s = den > 0 ? std::clamp((b * f - c * e) / den, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return (p0 + s * d1 - q0 - t * d2).squaredNorm();
}
}  // namespace

double segment_triangle_distance(const Vec3& p0, const Vec3& p1, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a);
  const double h0 = n.dot(p0 - a), h1 = n.dot(p1 - a);
  if ((h0 <= 0 && h1 >= 0) || (h0 >= 0 && h1 <= 0)) {  // the segment meets the plane: inside the triangle?
    const Vec3 x = h0 == h1 ? p0 : Vec3(p0 + (h0 / (h0 - h1)) * (p1 - p0));
    const double u = n.dot((b - a).cross(x - a)), v = n.dot((c - b).cross(x - b)), w = n.dot((a - c).cross(x - c));
    if (u >= 0 && v >= 0 && w >= 0) return 0.0;
  }
  double d2 = std::min((closest_on_triangle(p0, a, b, c) - p0).squaredNorm(),
                       (closest_on_triangle(p1, a, b, c) - p1).squaredNorm());
  d2 = std::min({d2, segment_segment2(p0, p1, a, b), segment_segment2(p0, p1, b, c), segment_segment2(p0, p1, c, a)});
  return std::sqrt(d2);
}

namespace {
Vec3 frustum_support(const Frustum& f, const Vec3& d) {
  const double dp = d.dot(f.axis);
  Vec3 u = d - dp * f.axis;
  const double un = u.norm();
  if (un > 0) {  // unit and across the axis even when d is nearly along it (the rim point stays on the rim)
    u /= un;
    u -= u.dot(f.axis) * f.axis;
    u.normalize();
  }
  const double s0 = f.z0 * dp + f.r0 * un, s1 = f.z1 * dp + f.r1 * un;
  return s0 >= s1 ? Vec3(f.base + f.z0 * f.axis + f.r0 * u) : Vec3(f.base + f.z1 * f.axis + f.r1 * u);
}

const Vec3& triangle_support(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const double sa = a.dot(d), sb = b.dot(d), sc = c.dot(d);
  return sa >= sb ? (sa >= sc ? a : c) : (sb >= sc ? b : c);
}

// The GJK simplex: points W of C with the triangle points A they came from.
struct Simplex {
  Vec3 W[4], A[4];
  int n = 0;

  // Keep the vertices of weight > 0 (weights wt) and return the weighted point of W, *pa of A.
  Vec3 keep(const double* wt, Vec3& pa) {
    Vec3 v = Vec3::Zero();
    pa.setZero();
    int m = 0;
    for (int i = 0; i < n; ++i) {
      if (wt[i] <= 0) continue;
      v += wt[i] * W[i];
      pa += wt[i] * A[i];
      W[m] = W[i];
      A[m] = A[i];
      ++m;
    }
    n = m;
    return v;
  }

  // Closest point v of conv(W) to the origin; reduces W to the face holding it. False: the origin is inside
  // the tetrahedron (the sets overlap).
  bool closest(Vec3& v, Vec3& pa) {
    const Vec3 o = Vec3::Zero();
    double wt[4] = {1, 0, 0, 0};
    if (n == 2) {
      closest_on_segment(o, W[0], W[1], wt[0], wt[1]);
    } else if (n == 3) {
      Vec3 b;
      closest_on_triangle(o, W[0], W[1], W[2], &b);
      wt[0] = b[0], wt[1] = b[1], wt[2] = b[2];
    } else if (n == 4) {
      static constexpr int kFace[4][4] = {{0, 1, 2, 3}, {0, 1, 3, 2}, {0, 2, 3, 1}, {1, 2, 3, 0}};
      double best = INFINITY;
      bool outside = false;
      for (const auto& fc : kFace) {
        const Vec3 nrm = (W[fc[1]] - W[fc[0]]).cross(W[fc[2]] - W[fc[0]]);
        const double so = -nrm.dot(W[fc[0]]), sl = nrm.dot(W[fc[3]] - W[fc[0]]);
        if (so * sl >= 0 && sl != 0) continue;  // the origin is on the inner side of this face
        outside = true;
        Vec3 b;
        const Vec3 q = closest_on_triangle(o, W[fc[0]], W[fc[1]], W[fc[2]], &b);
        if (q.squaredNorm() < best) {
          best = q.squaredNorm();
          std::fill(wt, wt + 4, 0.0);
          wt[fc[0]] = b[0], wt[fc[1]] = b[1], wt[fc[2]] = b[2];
        }
      }
      if (!outside) return false;
    }
    v = keep(wt, pa);
    return true;
  }
};
}  // namespace

DistanceBounds triangle_frustum(const Vec3& a, const Vec3& b, const Vec3& c, const Frustum& f, double near,
                                double far, double tol) {
  Vec3 pa = (a + b + c) / 3.0;
  Vec3 v = pa - (f.base + 0.5 * (f.z0 + f.z1) * f.axis);
  double lower = 0.0;
  Simplex s;
  for (int it = 0; it < 64; ++it) {
    const double vn = v.norm();
    if (vn <= 1e-12) return {0.0, 0.0, pa};
    const Vec3& sa = triangle_support(a, b, c, -v);
    const Vec3 w = sa - frustum_support(f, v);
    lower = std::max(lower, v.dot(w) / vn);
    if (lower >= far || vn < near || vn - lower <= tol) break;
    bool repeated = false;
    for (int i = 0; i < s.n; ++i) repeated = repeated || (s.W[i] - w).squaredNorm() <= 1e-24;
    if (repeated || s.n == 4) break;  // no further progress in floating point
    s.W[s.n] = w;
    s.A[s.n] = sa;
    ++s.n;
    Vec3 v2, pa2;
    if (!s.closest(v2, pa2)) return {0.0, 0.0, pa};
    if (s.n > 1 && v2.squaredNorm() >= vn * vn) break;  // no progress: |v| is as good as it gets
    v = v2;
    pa = pa2;
  }
  // Rounding in v·w is ~1e-16 of the coordinates; the margin keeps the lower bound certified.
  return {std::max(0.0, lower - 1e-9 * (1.0 + pa.cwiseAbs().maxCoeff())), v.norm(), pa};
}

}  // namespace netshape::detail

#pragma once
/// \file basis.hpp
/// B-spline basis functions (Piegl & Tiller, The NURBS Book, 2nd ed., §2): knot span search (A2.1),
/// non-vanishing basis functions (A2.2) and their derivatives (A2.3), and knot-vector validation.
///
/// Conventions: a B-spline of degree p with n control points has a knot vector U of size n + p + 1;
/// its parameter domain is [U[p], U[n]]. Knot vectors need not be clamped.

#include <cstddef>

#include "netshape/core/types.hpp"

namespace netshape::geometry {

/// Index `span` with U[span] <= u < U[span+1], p <= span <= n - 1 (u = U[n] gives n - 1), by bisection.
/// `count` is the number of control points n. u is clamped into the domain. No allocation.
int find_span(int count, int degree, double u, const double* knots) noexcept;

/// The p + 1 non-vanishing basis functions N_{span-p..span, p}(u) into `out` (size p + 1).
/// `scratch` needs 2 (p + 1) doubles. No allocation (A2.2).
void basis_functions(int span, double u, int degree, const double* knots, double* out, double* scratch) noexcept;

/// Basis functions and their derivatives up to order `order` (A2.3) into `out`, row-major
/// (order + 1, p + 1): out[k (p+1) + j] = d^k N_{span-p+j,p} / du^k. Rows k > p are zero.
/// `scratch` needs ders_scratch_size(p) doubles. No allocation.
void basis_function_derivatives(int span, double u, int degree, int order, const double* knots, double* out,
                                double* scratch) noexcept;

/// Basis functions N (p + 1) and their first derivatives dN (p + 1) at u in one pass: the degree p − 1
/// functions from A2.2 give dN_{i,p} = p (N_{i,p−1}/(U_{i+p} − U_i) − N_{i+1,p−1}/(U_{i+p+1} − U_{i+1})).
/// Faster than basis_function_derivatives for order 1. `scratch` needs 3 (p + 1) doubles. No allocation.
void basis_functions_d1(int span, double u, int degree, const double* knots, double* N, double* dN,
                        double* scratch) noexcept;

/// Scratch size (doubles) basis_function_derivatives needs for degree p.
std::size_t ders_scratch_size(int degree) noexcept;

/// Convenience (allocating) form of basis_function_derivatives: (order + 1, p + 1) array.
MatrixXdR basis_function_derivatives(double u, int degree, const VectorXd& knots, int order);

/// Check a knot vector for `count` control points of degree `degree`: size count + degree + 1,
/// finite, non-decreasing, a non-empty domain, interior multiplicity at most `degree`.
/// Throws std::invalid_argument naming `field`.
void validate_knots(const VectorXd& knots, int degree, int count, const char* field);

/// Binomial coefficient C(n, k) as a double (small n).
double binomial(int n, int k) noexcept;

}  // namespace netshape::geometry

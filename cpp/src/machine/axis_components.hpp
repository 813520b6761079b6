#pragma once
// Evaluation of error components from a CompiledMachine: one prepared function, or the six
// components of one axis at its position q (values, and slopes d/dq when asked). Inline, so that it
// compiles into the chain step of lanes.cpp. A table position refused by the policy (`error` outside
// the table, or q not finite) is reported by returning the refusing function; the caller throws
// (`throw_refused`, the table's own message) or flags the point.
#include <cmath>
#include <stdexcept>

#include "netshape/machine/compiled_machine.hpp"
#include "netshape/machine/table_interpolation.hpp"

namespace netshape::machine::detail {

/// Throws the message of table `f` refusing q (the same `look_up` decides in `ErrorFunction::operator()`).
[[noreturn]] inline void throw_refused(const ErrorFunction& f, double q) {
  f(q);
  throw std::logic_error(f.name + ": a refused table position was accepted");  // not reached
}

/// f(q) into `value` (and df/dq into `slope` when `Slope`; a table's segment slope, 0 where clamped).
/// Returns false, leaving the outputs unset, when f is a table that refuses q.
template <bool Slope>
inline bool prepared_value(const PreparedFunction& f, double q, double& value, double& slope) noexcept {
  switch (f.kind) {
    case ErrorFunction::Kind::polynomial: {
      // Horner; the slope by the same recurrence on the derivative
      const double* c = f.c;
      double r = c[f.n - 1], d = 0.0;
      for (int j = f.n - 2; j >= 0; --j) {
        if (Slope) d = d * q + r;
        r = r * q + c[j];
      }
      value = r;
      if (Slope) slope = d;
      return true;
    }
    case ErrorFunction::Kind::table: {
      const TableLookup at = look_up<Slope>(f.grid, f.out_of_range, q);
      if (at.where == TableLookup::Where::refused) return false;
      value = table_value<Slope>(at, f.c, f.n, 1, 0, &slope);
      return true;
    }
    case ErrorFunction::Kind::zero:
    default:
      value = 0.0;
      if (Slope) slope = 0.0;
      return true;
  }
}

/// The six components of axis k at q: e[0..2] = (EXk, EYk, EZk) [mm], e[3..5] = (EAk, EBk, ECk) [rad],
/// slopes into s[0..5] when `Slope`. Returns the table that refuses q (outputs unset), else nullptr.
template <bool Slope>
inline const ErrorFunction* axis_components(const CompiledMachine& cm, int k, double q, double* e, double* s) {
  const AxisKernel& ker = cm.kernels[k];
  switch (ker.mode) {
    case AxisKernel::Mode::polynomial: {
      const double* c = ker.packed.data();
      const int last = ker.terms - 1;
      for (int i = 0; i < 6; ++i) e[i] = c[last * 6 + i];
      if (Slope)
        for (int i = 0; i < 6; ++i) s[i] = 0.0;
      for (int j = last - 1; j >= 0; --j) {
        for (int i = 0; i < 6; ++i) {
          if (Slope) s[i] = s[i] * q + e[i];
          e[i] = e[i] * q + c[j * 6 + i];
        }
      }
      return nullptr;
    }
    case AxisKernel::Mode::table: {
      const TableLookup at = look_up<Slope>(ker.grid, ker.out_of_range, q);
      if (at.where == TableLookup::Where::refused) return ker.source;
      for (int c = 0; c < 6; ++c) e[c] = table_value<Slope>(at, ker.packed.data(), ker.terms, 6, c, Slope ? s + c : nullptr);
      return nullptr;
    }
    case AxisKernel::Mode::generic:
    default: {
      const PreparedFunction* f = &cm.functions[k * 6];
      double unused = 0.0;
      for (int c = 0; c < 6; ++c)
        if (!prepared_value<Slope>(f[c], q, e[c], Slope ? s[c] : unused)) return f[c].source;
      // periodic terms of the positioning component EKk (component index k): a·sin(w·q + φ)
      for (const auto& t : cm.cyclic[k]) {
        const double arg = t[1] * q + t[2];
        e[k] += t[0] * std::sin(arg);
        if (Slope) s[k] += t[0] * t[1] * std::cos(arg);
      }
      return nullptr;
    }
  }
}

/// axis_components compiled once, in baseline code (compiled_machine.cpp): the batch kernels, whose
/// copies are compiled for wider instruction sets, call this one per lane instead of instantiating the
/// inline template themselves (an out-of-line copy of it in a wide object could be shared by the linker
/// with baseline callers).
template <bool Slope>
const ErrorFunction* axis_components_outlined(const CompiledMachine& cm, int k, double q, double* e, double* s);

}  // namespace netshape::machine::detail

// Compiling a Machine: the constants of the synthesis derived once (prepared error functions, packed
// axis kernels, chains in evaluation order, squareness directions, tilted tip), and the MachineData
// workspace built on them.
#include "netshape/machine/compiled_machine.hpp"

#include <algorithm>
#include <cmath>

#include "axis_components.hpp"
#include "netshape/machine/synthesis.hpp"
#include "rotation.hpp"

namespace netshape::machine {

namespace {
// Function f prepared for evaluation (a polynomial without coefficients becomes zero).
detail::PreparedFunction prepare_function(const ErrorFunction& f) {
  detail::PreparedFunction pf;
  pf.source = &f;
  pf.kind = f.kind;
  pf.out_of_range = f.out_of_range;
  if (f.kind == ErrorFunction::Kind::polynomial) {
    if (f.coefficients.empty()) {
      pf.kind = ErrorFunction::Kind::zero;
    } else {
      pf.n = static_cast<int>(f.coefficients.size());
      pf.c = f.coefficients.data();
    }
  } else if (f.kind == ErrorFunction::Kind::table) {
    pf.n = static_cast<int>(f.positions.size());
    pf.c = f.values.data();
    pf.grid = detail::table_grid(f.positions, true);
  }
  return pf;
}

// The six components of axis k packed for one-pass evaluation when they allow it: no tables (all
// polynomials, zero-padded), or only tables on the same positions with the same policy (zero
// components become zero columns); otherwise `generic`.
detail::AxisKernel prepare_kernel(const Machine& machine, int k) {
  const auto& errs = machine.axes[k].errors;
  if (!machine.axes[k].cyclic.empty()) return detail::AxisKernel{};  // generic: periodic terms added per point
  bool any_table = false, any_poly = false;
  const ErrorFunction* first_table = nullptr;
  for (const ErrorFunction& f : errs) {
    if (f.kind == ErrorFunction::Kind::polynomial && !f.coefficients.empty()) any_poly = true;
    if (f.kind == ErrorFunction::Kind::table) {
      any_table = true;
      if (!first_table) first_table = &f;
    }
  }
  detail::AxisKernel ker;
  if (!any_table) {
    ker.mode = detail::AxisKernel::Mode::polynomial;
    int terms = 1;
    for (const ErrorFunction& f : errs)
      if (f.kind == ErrorFunction::Kind::polynomial) terms = std::max(terms, static_cast<int>(f.coefficients.size()));
    ker.terms = terms;
    ker.packed.assign(static_cast<std::size_t>(terms) * 6, 0.0);
    for (int c = 0; c < 6; ++c)
      if (errs[c].kind == ErrorFunction::Kind::polynomial)
        for (std::size_t j = 0; j < errs[c].coefficients.size(); ++j) ker.packed[j * 6 + c] = errs[c].coefficients[j];
    return ker;
  }
  if (any_poly) return ker;
  for (const ErrorFunction& f : errs) {
    if (f.kind != ErrorFunction::Kind::table) continue;
    if (f.positions != first_table->positions || f.out_of_range != first_table->out_of_range) return ker;
  }
  const int n = static_cast<int>(first_table->positions.size());
  ker.mode = detail::AxisKernel::Mode::table;
  ker.terms = n;
  ker.packed.assign(static_cast<std::size_t>(n) * 6, 0.0);
  for (int c = 0; c < 6; ++c)
    if (errs[c].kind == ErrorFunction::Kind::table)
      for (int i = 0; i < n; ++i) ker.packed[static_cast<std::size_t>(i) * 6 + c] = errs[c].values[i];
  ker.grid = detail::table_grid(first_table->positions, true);
  ker.out_of_range = first_table->out_of_range;
  ker.source = first_table;
  return ker;
}
}  // namespace

CompiledMachine::CompiledMachine(const Machine& machine) {
  machine.validate();
  for (int k = 0; k < 3; ++k) {
    for (int j = 0; j < 6; ++j) functions[k * 6 + j] = prepare_function(machine.axes[k].errors[j]);
    kernels[k] = prepare_kernel(machine, k);
    for (const CyclicTerm& t : machine.axes[k].cyclic)
      cyclic[k].push_back({t.amplitude, 2.0 * pi / t.period, t.phase});
  }
  // Chains in evaluation order, and which Abbe arms grow with which axis (first-order Jacobian).
  tool_steps = 0;
  int ns = 0;
  for (auto it = machine.tool_chain.rbegin(); it != machine.tool_chain.rend(); ++it, ++ns, ++tool_steps)
    steps[ns] = detail::ChainStep{*it, true, machine.axes[*it].origin};
  for (int k : machine.workpiece_chain) steps[ns++] = detail::ChainStep{k, false, machine.axes[k].origin};
  std::array<int, 3> tool_pos{-1, -1, -1}, work_pos{-1, -1, -1};
  for (std::size_t i = 0; i < machine.tool_chain.size(); ++i) tool_pos[machine.tool_chain[i]] = static_cast<int>(i);
  for (std::size_t i = 0; i < machine.workpiece_chain.size(); ++i)
    work_pos[machine.workpiece_chain[i]] = static_cast<int>(i);
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      arm_grows[k][j] = tool_pos[k] >= 0 ? (tool_pos[j] >= 0 ? tool_pos[j] < tool_pos[k] : true)
                                         : (work_pos[j] >= 0 && work_pos[j] >= work_pos[k]);
  // Squareness: X is the reference; Y = Rz(EC0Y) ŷ; Z = Rx(EA0Z) Ry(EB0Z) ẑ. Stored as deviations
  // from the nominal unit vector (exact), direction_linear as first-order deviations.
  double s, cm;
  direction[0] = Vec3::Zero();
  direction_linear[0] = Vec3::Zero();
  detail::sincos_m1(machine.ec0y, s, cm);
  direction[1] = Vec3(-s, cm, 0.0);
  direction_linear[1] = Vec3(-machine.ec0y, 0.0, 0.0);
  direction[2] = detail::tilt_minus_identity(machine.ea0z, machine.eb0z).col(2);  // Rx(a) Ry(b) ẑ - ẑ
  direction_linear[2] = Vec3(machine.eb0z, -machine.ea0z, 0.0);
  tip_nominal = machine.nominal_tip();
  tip_local = machine.tool_length *
              (detail::tilt_minus_identity(machine.spindle_tilt_a, machine.spindle_tilt_b) * machine.tool_direction);
  tip_local_linear =
      machine.tool_length * Vec3(machine.spindle_tilt_a, machine.spindle_tilt_b, 0.0).cross(machine.tool_direction);
}

MachineData::MachineData(const Machine& machine)
    : MachineData(std::make_shared<const CompiledMachine>(machine)) {}

MachineData::MachineData(std::shared_ptr<const CompiledMachine> compiled) : compiled_(std::move(compiled)) {
  for (int k = 0; k < 3; ++k) {
    delta[k].setZero();
    epsilon[k].setZero();
    delta_slope[k].setZero();
    epsilon_slope[k].setZero();
  }
}

template <bool Slope>
const ErrorFunction* detail::axis_components_outlined(const CompiledMachine& cm, int k, double q, double* e,
                                                      double* s) {
  return axis_components<Slope>(cm, k, q, e, s);
}
template const ErrorFunction* detail::axis_components_outlined<false>(const CompiledMachine&, int, double, double*,
                                                                      double*);
template const ErrorFunction* detail::axis_components_outlined<true>(const CompiledMachine&, int, double, double*,
                                                                     double*);

}  // namespace netshape::machine

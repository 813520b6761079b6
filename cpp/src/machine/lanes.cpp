// The one-point exact kernel (the chain step of chain_step.hpp with W = 1) and the choice of the batch
// kernel's instruction set (kernels/lanes.cpp, core/dispatch.hpp).
#include "machine/chain_step.hpp"
#include "machine/kernels/lane_kernels.hpp"

namespace netshape::machine {

namespace {
// The one-point kernel: the Taylor series first; with an angle ≥ 1e-3 rad again with sincos_m1.
template <Outputs O>
Vec3 exact_point_impl(MachineData& data, const Vec3& p, Mat3* jacobian) {
  const CompiledMachine& cm = data.compiled();
  double pin[3][batch_lanes], out[3][batch_lanes], jac[9][batch_lanes];
  for (int c = 0; c < 3; ++c) pin[c][0] = p[c];
  if (chain_pack<1, O, Angles::taylor, false>(cm, data, pin, 0, out, &jac).redo)
    chain_pack<1, O, Angles::exact, false>(cm, data, pin, 0, out, &jac);
  if (O != Outputs::value)
    for (int col = 0; col < 3; ++col)
      for (int r = 0; r < 3; ++r) (*jacobian)(r, col) = jac[3 * col + r][0];
  return Vec3(out[0][0], out[1][0], out[2][0]);
}

const kernels::LaneKernels& lane_kernels_for(simd::Isa isa) {
  return NETSHAPE_SIMD_SELECT_ISA(kernels, lane_kernels, isa);
}

simd::Isa isa_of_width(int width) {
  return width == 8 ? simd::Isa::avx512 : width == 4 ? simd::Isa::avx2 : simd::Isa::baseline;
}
}  // namespace

__attribute__((noinline)) Vec3 detail::exact_point(MachineData& data, const Vec3& p, Mat3* jacobian) {
  return jacobian ? exact_point_impl<Outputs::jacobian>(data, p, jacobian)
                  : exact_point_impl<Outputs::value>(data, p, nullptr);
}

unsigned tip_error_lanes(MachineData& data, const double (&p)[3][batch_lanes], double (&e)[3][batch_lanes],
                         double (*jacobian)[9][batch_lanes]) {
  static const kernels::LaneKernels& k = NETSHAPE_SIMD_SELECT(kernels, lane_kernels);
  return k.lanes(data, p, e, jacobian);
}

bool detail::lanes_width_supported(int width) {
  const simd::Isa isa = isa_of_width(width);
  return simd::runs(isa) && lane_kernels_for(isa).width == width;
}

unsigned detail::tip_error_lanes_width(int width, MachineData& data, const double (&p)[3][batch_lanes],
                                       double (&e)[3][batch_lanes], double (*jacobian)[9][batch_lanes]) {
  NETSHAPE_CHECK(lanes_width_supported(width), "width", width, "must be a vector width this CPU runs");
  return lane_kernels_for(isa_of_width(width)).lanes(data, p, e, jacobian);
}

}  // namespace netshape::machine

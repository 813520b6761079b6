// The machine's batch kernel, one copy per instruction set (kernels/lane_kernels.hpp).
#include "core/simd.hpp"  // first: it wraps the intrinsic headers (see there)

#include "machine/chain_step.hpp"
#include "machine/kernels/lane_kernels.hpp"

namespace netshape::machine::kernels::NETSHAPE_KERNEL_ISA {
namespace {
constexpr int kWidth = simd::native_width;

unsigned lanes(MachineData& data, const double (&p)[3][batch_lanes], double (&e)[3][batch_lanes],
               double (*jacobian)[9][batch_lanes]) {
  return lanes_impl<kWidth>(data, p, e, jacobian);
}
}  // namespace

extern const LaneKernels lane_kernels;
const LaneKernels lane_kernels{&lanes, kWidth};

}  // namespace netshape::machine::kernels::NETSHAPE_KERNEL_ISA

#pragma once
/// \file program.hpp
/// Force along a program: the cutter moves through a toolpath over a Z-map stock; at sample
/// positions along every feed block the elements in material are found from the Z-map
/// (netshape::stock::engaged_elements, before the move to that position is swept), the forces of one
/// revolution are computed with that engagement, and the stock is then cut by the move.

#include <cstdint>

#include "netshape/core/types.hpp"
#include "netshape/cutter/cutter.hpp"
#include "netshape/force/coefficients.hpp"
#include "netshape/force/runout_size_effect.hpp"
#include "netshape/stock/zmap.hpp"
#include "netshape/toolpath/toolpath.hpp"

namespace netshape::force {

struct ProgramForceOptions {
  double step = 0.5;              ///< spacing of force samples along a block [mm] (> 0)
  int samples_per_revolution = 72; ///< angles per revolution at each sample (≥ 8)
  int bins = 360;                 ///< angular bins of the engagement map (≥ 8)
  double disk_height = 0.1;       ///< flat: disk height; ball: cylinder disk height [mm]
  double element_angle = 0.0349065850398866;  ///< ball: Δψ [rad] (default 2°)
  double feed_per_tooth = 0.0;    ///< > 0 overrides feed·60/(rpm·N) of the blocks [mm]
  double spindle_rpm = 0.0;       ///< > 0 overrides the blocks' spindle speed [rev/min]
  void validate() const;
};

/// Coefficients for a program run: linear edge for flat cutters, Feng–Menq for ball cutters; `chip`:
/// the flat cutter's runout and chip-size effect (runout_size_effect.hpp; none: the linear model,
/// bit-identical to the plain kernel); a ball cutter takes its runout (ball_end_model.hpp; ρ = 0:
/// bit-identical) and refuses a chip exponent ≠ 1 (its size effect is Feng–Menq's m_T, m_R).
struct ProgramCoefficients {
  LinearEdgeCoefficients linear_edge{};
  BallEndCoefficients ball_end{};
  RunoutSizeEffect chip{};
};

/// Per sample: position of the tip, block index, feed direction, forces over one revolution.
struct ProgramForces {
  Points3 positions;           ///< (m, 3) tip positions [mm]
  Eigen::VectorXi block;       ///< (m) index of the block in the program
  Points3 feed_direction;      ///< (m, 3) unit horizontal feed direction
  Points3 mean;                ///< (m, 3) mean force per revolution on the cutter, cutting frame [N]
  Points3 peak;                ///< (m, 3) largest |Fx|, |Fy|, |Fz| over the revolution [N]
  VectorXd peak_resultant;     ///< (m) max |F| over the revolution [N]
  VectorXd mean_resultant;     ///< (m) mean |F| [N]
  VectorXd engaged_fraction;   ///< (m) share of the element×bin map in material [-]
  double removed_volume = 0.0; ///< stock removed by the program [mm³]
};

/// Run `program` over `stock` (modified: it ends as the machined part). Rapids and vertical moves
/// are swept but get no force samples. Flat cutters use coefficients.linear_edge, ball cutters
/// coefficients.ball_end; bull-nose cutters are not modelled (std::invalid_argument).
ProgramForces simulate_program(stock::ZMap& stock, const cutter::Cutter& cutter, const toolpath::Toolpath& program,
                               const ProgramCoefficients& coefficients, const ProgramForceOptions& options = {});

}  // namespace netshape::force

#pragma once
/// \file feed_schedule.hpp
/// Feed scheduling from the physics (docs/feeds.md): the largest feed at every force sample of a
/// program that keeps each stated limit, and the pieces a block is split into where its engagement
/// changes.
///
/// The engagement of the cutter does not depend on the feed: at a sample the elements in material
/// are read from the Z-map once (netshape::stock::engaged_elements, before the move to the sample is
/// swept, as netshape::force::simulate_program). With that engagement the force is a sum of two
/// terms in the feed per tooth c [mm]:
///
///     F(θ; c) = c^p · P(θ) + c^q · Q(θ)
///
/// flat end mill (linear edge model): p = 1, q = 0, P the cutting part at c = 1, Q the edge part
/// (exact: h = max(c·sin φ, 0) = c·max(sin φ, 0)); ball end mill (Feng–Menq): p = m_T, q = m_R, P the
/// tangential and Q the radial part at c = 1. A limit on a norm of F over the revolution is then met
/// by the largest c with max_θ |F(θ; c)| ≤ limit: for p = 1, q = 0 a quadratic per angle (the
/// smallest upper root over the angles, closed form), otherwise a bisection on c.
///
/// Limits, each optional (infinity = not stated):
///   force       max_θ |F|                                    ≤ max_force [N]
///   chip        c · max sin φ over the engaged bins          ≤ max_chip [mm]
///   deflection  max_θ |δ(tip)|                               ≤ max_deflection [mm]
///   wall_error  max |e| at the bottom, middle, top of the cut ≤ max_wall_error [mm] (walls generated)
///   power       mean_θ T · 2π·rpm/60                          ≤ max_power [W] (flat end mills)
///   torque      mean_θ T,  T = R·Σ dF_t                      ≤ max_torque [N·m] (flat end mills)
/// Flat end mills: δ and e from the surface-generation model of netshape deflection
/// (deflection::DeflectionModel built from the cutter: square-section cantilever over the stick-out,
/// distributed load, holder compliance, runout; the window and axial depth of stock::immersion at the
/// sample; e at each generated wall's instant as deflection/wall.hpp). Without runout δ and e are
/// linear in c, so their largest c is in closed form, else a bisection. Ball end mills: the bound
/// κ·max_θ |F_xy| (tip) and κ·max_θ |F_y| (wall), κ = g(L; L) + holder compliance [mm/N], the tip's
/// deflection per newton at the tip (deflection::Cantilever): no load on the tool, wherever it acts,
/// deflects any point more (g(x; l) ≤ g(L; L)), so it bounds the deflection when the disks' forces push
/// one way.
/// min_chip gives a lower bound c ≥ min_chip / max sin φ.

#include <cstdint>
#include <limits>

#include "netshape/core/types.hpp"
#include "netshape/cutter/cutter.hpp"
#include "netshape/force/program.hpp"
#include "netshape/stock/zmap.hpp"
#include "netshape/toolpath/toolpath.hpp"

namespace netshape::compensation {

/// What sets a piece's feed. The first six are the columns of FeedSamples::allowed.
enum class FeedLimit : std::uint8_t {
  force = 0, chip = 1, deflection = 2, wall_error = 3, power = 4, torque = 5,
  max_feed = 6,  ///< no physical limit binds: the largest feed
  air = 7,       ///< the tool cuts nothing: the air-cut feed
  programmed = 8,  ///< a vertical feed move (plunge): no force sample, the programmed feed is kept
};
inline constexpr int feed_limit_columns = 6;
const char* to_string(FeedLimit l) noexcept;

/// The limits a schedule keeps. Infinity: not stated.
struct FeedLimits {
  double max_force = std::numeric_limits<double>::infinity();       ///< resultant on the cutter [N]
  double max_chip = std::numeric_limits<double>::infinity();        ///< largest uncut chip [mm]
  double min_chip = 0.0;                                            ///< smallest largest chip [mm]
  double max_deflection = std::numeric_limits<double>::infinity();  ///< tool tip deflection [mm]
  double max_wall_error = std::numeric_limits<double>::infinity();  ///< on final walls [mm]
  double max_power = std::numeric_limits<double>::infinity();       ///< spindle power [W]
  double max_torque = std::numeric_limits<double>::infinity();      ///< spindle torque [N·m]
  double min_feed = 0.0;                                            ///< [mm/s], ≥ 0
  double max_feed = 100.0;                                          ///< [mm/s], finite, > min_feed
  double air_feed = 0.0;                                            ///< [mm/s]; 0: max_feed
  /// Positive limits (or infinity), 0 ≤ min_chip < max_chip, 0 ≤ min_feed < max_feed finite, air_feed
  /// ≥ 0; throws std::invalid_argument naming the field.
  void validate() const;
};

/// Options of the sample pass (the sampling of netshape::force::ProgramForceOptions).
struct FeedScheduleOptions {
  force::ProgramForceOptions sampling{};  ///< step, angles, bins, disks; feed_per_tooth is ignored
  void validate() const;
};

/// Per force sample along the program (m samples), what each limit allows.
struct FeedSamples {
  Points3 positions;        ///< (m, 3) tip positions [mm]
  Eigen::VectorXi block;    ///< (m) block index in the program
  VectorXd fraction;        ///< (m) position in the block as a fraction of its length, in (0, 1]
  Points3 feed_direction;   ///< (m, 3) unit horizontal feed direction
  VectorXd spindle_rpm;     ///< (m) [rev/min]
  Eigen::VectorXi engaged;  ///< (m) 1 where any element is in material
  Eigen::VectorXi walls;    ///< (m) bit 1: a left wall is generated (material within 10° of φ = 0),
                            ///< bit 2: a right wall (within 10° of φ = π)
  VectorXd depth;           ///< (m) height of the engaged material above the tip [mm]
  VectorXd chip_factor;     ///< (m) max sin φ over the engaged bins: largest chip = c·chip_factor [-]
  VectorXd engaged_share;   ///< (m) share of the element × bin map in material [-]
  MatrixXdR allowed;        ///< (m, 6) largest feed [mm/s] each limit allows (FeedLimit 0..5); inf: no bound
  VectorXd lowest;          ///< (m) smallest feed [mm/s] min_chip allows (0 without it)
  VectorXd force;           ///< (m) max_θ |F| at the block's programmed feed [N]
  VectorXd deflection;      ///< (m) flat end mills with a deflection limit: max_θ |δ(tip)| at the
                            ///< programmed feed [mm] (0 otherwise)
  VectorXd wall_error;      ///< (m) flat end mills with a wall-error limit: max |e| over the levels
                            ///< and generated walls at the programmed feed [mm] (0 otherwise)
  double removed_volume = 0.0;  ///< [mm³]
};

/// Cut `program` through `stock` (modified: it ends as the machined part) and at every force sample
/// find what each limit of `limits` allows (see the file comment). Rapids and vertical moves are swept
/// without samples. Flat cutters use coefficients.linear_edge, ball cutters coefficients.ball_end;
/// power and torque are modelled for flat end mills (std::invalid_argument for a ball end mill with
/// either limit); bull-nose cutters are refused as in netshape::force::simulate_program. A cutting
/// sample without a spindle speed throws std::invalid_argument naming the block's line.
FeedSamples feed_samples(stock::ZMap& stock, const cutter::Cutter& cutter, const toolpath::Toolpath& program,
                         const force::ProgramCoefficients& coefficients, const FeedLimits& limits,
                         const FeedScheduleOptions& options = {});

/// Pieces of the blocks with their feeds (k pieces, in program order).
struct FeedPieces {
  Eigen::VectorXi block;     ///< (k) block index
  VectorXd start, end;       ///< (k) fractions of the block's length [-], 0 ≤ start < end ≤ 1
  VectorXd feed;             ///< (k) [mm/s]
  Eigen::VectorXi binding;   ///< (k) FeedLimit that sets the feed
  Eigen::VectorXi sample;    ///< (k) index of the sample that sets it (−1: a piece without samples)
};

/// Split every feed block where its engagement changes and give each piece the smallest allowed feed
/// of its samples. A piece runs over consecutive samples of one block while the samples stay engaged
/// (or in air) and their engaged depth, chip factor and engaged share stay within `tolerance`
/// (relative) of the piece's first sample and generate the same walls. A piece shorter than
/// `min_length` [mm] joins the piece before it when both cut or both are in air (so the entry into
/// material never slows the air before it). The split depends on the engagement only, never on the
/// limits, so raising a limit never lowers a feed. A sample's feed is min(max_feed, its allowed
/// feeds) when engaged and the air feed otherwise; a feed block without samples gets one piece: a
/// vertical line (a plunge) keeps its programmed feed, any other (above the stock) the air feed.
/// `allowed` may differ from samples.allowed (the caller lifts the wall-error column where the wall
/// does not remain). Rapids get no piece.
FeedPieces feed_pieces(const toolpath::Toolpath& program, const FeedSamples& samples,
                       const Eigen::Ref<const MatrixXdR>& allowed, const FeedLimits& limits, double tolerance = 0.1,
                       double min_length = 1.0);

}  // namespace netshape::compensation

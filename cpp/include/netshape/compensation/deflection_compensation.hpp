#pragma once
/// \file deflection_compensation.hpp
/// Wall error along a 2-D contour from tool deflection, and the path compensation schemes of
/// Cho & Suh 1993 §4 (1-D, integrated, sectional) plus an Anderson-accelerated iteration.
///
/// A path is a polyline of tool-tip points R_i (n, 3) [mm] at constant height (2-D contour). The
/// wall is on one side of the feed: left (+Y_c, generated at φ = 0, up milling) or right (−Y_c,
/// φ = π, down milling). n_i is the unit wall normal of the nominal path at point i (the normal of
/// the central-difference tangent, pointing from the axis to the wall). A compensated path moves
/// each point along its nominal normal: P_i = R_i + C_i·n_i, C_i > 0 towards the wall.
///
/// Evaluation (the model, "D[P]"): at each point the engagement (radial window, axial depth) is read
/// from the stock in the state left by the moves before it at their actual positions (see
/// PathOptions::exact_self_removal), in the cutting frame of the nominal tangent at the point (the
/// compensated path turns by dC/ds ~ 1e-4 rad, which moves no material but would couple neighbouring
/// offsets through the frame alone), the cutter deflection at the
/// generation instant of each level is computed (deflection::wall_errors) and the wall error at
/// level z is e_i(z) = (R_i − P_i − δ_i(z))·n_i = −C_i − δ_i(z)·n_i, + when material is left.
///
/// Schemes (unknowns C_i, reference level z_ref, tolerance ε):
/// - one_d: per point, the steady cut of the nominal width W_i: root of E(W, C) = D[W + C] − C
///   (paper eq. 8) by bracketing and regula falsi; exact for a constant width, not otherwise;
/// - integrated (paper steps 1–8): C ← C + λ·e(C) for all points at once until max|e| ≤ ε;
/// - sectional (steps 1–9): from the terminal point backwards, each point solved with its successor
///   fixed by the same update, the material removed before it taken
///   from the pre-path stock minus the tool's swept discs along the earlier points at the trial
///   offset; the final path is evaluated with the Z-map like the others;
/// - accelerated: Anderson acceleration (depth m) of the fixed-point map G(C) = C + λ·e(C): the same
///   fixed point e = 0, fewer evaluations; a step that raises the residual restarts the history.
/// A scheme that does not reach ε within the iteration limit, or whose residual grows, stops with
/// converged = false and a message naming the point and the reason.

#include <cstdint>
#include <string>
#include <vector>

#include "netshape/core/types.hpp"
#include "netshape/cutter/cutter.hpp"
#include "netshape/deflection/wall.hpp"
#include "netshape/stock/engagement.hpp"
#include "netshape/stock/zmap.hpp"

namespace netshape::compensation {

enum class ReferenceLevel : std::uint8_t { bottom = 0, middle = 1, top = 2 };
const char* to_string(ReferenceLevel l) noexcept;
/// "bottom", "middle" or "top"; throws std::invalid_argument otherwise.
ReferenceLevel reference_level_from_string(const std::string& s);

enum class DeflectionScheme : std::uint8_t { one_d = 0, integrated = 1, sectional = 2, accelerated = 3 };
const char* to_string(DeflectionScheme s) noexcept;
/// "one-d" (or "one_d"), "integrated", "sectional" or "accelerated"; throws std::invalid_argument otherwise.
DeflectionScheme deflection_scheme_from_string(const std::string& s);

/// Unit wall normals (n, 2) of the polyline `nominal` (n ≥ 2 points, consecutive points distinct in
/// XY): the normal of the central-difference tangent (one-sided at the ends; at a corner, where the
/// path turns by more than 30° at a point, the outgoing move's), to the left of the feed for
/// WallSide::left, to the right for WallSide::right.
Points2 wall_normals(const Eigen::Ref<const Points3>& nominal, deflection::WallSide side);

struct PathOptions {
  deflection::WallSide side = deflection::WallSide::right;
  int profile_levels = 0;               ///< > 0: also the error at that many heights 0 … A per point
  stock::ImmersionOptions immersion{};  ///< radial scan of the engagement
  /// true (default): the stock Z-map is the material before the contour and the contour's own
  /// removal up to a point is the exact union of the flat end's swept discs along the earlier moves
  /// (what a Z-map sweep computes, without its grid steps, which make the error a step function of
  /// the offsets and stall the iterations); false: the Z-map is swept move by move and read with
  /// stock::immersion.
  bool exact_self_removal = true;
  void validate() const;
};

/// Wall error along a path. Rows are path points.
struct PathWallErrors {
  Points3 positions;               ///< (n, 3) tool tip positions P_i evaluated [mm]
  MatrixXdR error;                 ///< (n, 3) wall error at the bottom, middle, top of the cut [mm]
  Points2 deflection;              ///< (n, 2) deflection in machine XY at the middle level's instant [mm]
  VectorXd normal_deflection;      ///< (n) δ·n at the middle level [mm] (towards the wall > 0)
  VectorXd tangential_deflection;  ///< (n) δ·t (t the feed direction) at the middle level [mm]
  Points2 force;                   ///< (n, 2) force on the cutter in machine XY at that instant [N]
  VectorXd width;                  ///< (n) radial depth of cut from the Z-map [mm] (0 when not engaged)
  VectorXd depth;                  ///< (n) axial depth of cut [mm]
  VectorXd phi_st, phi_ex;         ///< (n) engaged window [rad]
  Eigen::VectorXi engaged;         ///< (n) 1 where the cutter touches material
  Eigen::VectorXi wall_flags;      ///< (n) bit 0: window holds φ = 0 (left wall), bit 1: holds π (right wall)
  MatrixXdR profile;               ///< (n, profile_levels) error at z_k = A·k/(levels − 1) [mm]
};

/// Evaluate the model along P_i = R_i + C_i n_i (`offsets` C (n), `normals` (n, 2)) over the stock
/// (copied, not changed). `model` gives tool, coefficients, feed, beam and load model; its axial
/// depth and engagement are replaced per point by the Z-map's.
PathWallErrors path_wall_errors(const deflection::DeflectionModel& model, const cutter::Cutter& cutter,
                                const stock::ZMap& stock, const Eigen::Ref<const Points3>& nominal,
                                const Eigen::Ref<const Points2>& normals, const Eigen::Ref<const VectorXd>& offsets,
                                const PathOptions& options);

/// 1-D compensation of a steady straight cut of width W [mm] (paper eq. 8): the C [mm] with
/// e(z_level; W + C) − C = 0, up milling for the left wall, down milling for the right one (model's
/// axial depth; its engagement is replaced). Throws std::runtime_error if no root is bracketed.
double one_d_compensation(const deflection::DeflectionModel& model, deflection::WallSide side, double width,
                          double level_z, double tolerance = 1e-7, int max_iterations = 100);

struct DeflectionCompensationOptions {
  DeflectionScheme scheme = DeflectionScheme::integrated;
  ReferenceLevel level = ReferenceLevel::middle;
  double tolerance = 5e-4;  ///< ε on max |e| at the reference level [mm]
  double discount = 1.0;    ///< λ ∈ (0, 1]
  int max_iterations = 50;  ///< LIMIT (per point for sectional)
  int anderson_depth = 5;   ///< m of the accelerated scheme
  /// (n) 1 where the point's wall is part of the finished part (see wall_remains), 0 where a later
  /// pass cuts it away: such a point keeps C = 0 (as programmed) and its error does not count
  /// against the tolerance. Empty: every point counts.
  Eigen::VectorXi active;
  PathOptions path{};
  void validate() const;
};

struct DeflectionCompensationResult {
  bool converged = false;
  std::string message;            ///< why it stopped (point and reason when it failed)
  DeflectionScheme scheme = DeflectionScheme::integrated;
  int iterations = 0;             ///< scheme iterations (sectional: largest per point)
  std::int64_t path_evaluations = 0;   ///< full-path model evaluations (Z-map sweeps)
  std::int64_t point_evaluations = 0;  ///< single-point deflection evaluations, all included
  int worst_index = -1;           ///< point of the largest |e| at the end
  VectorXd offsets;               ///< (n) C_i [mm]
  Points3 positions;              ///< (n, 3) compensated tip positions [mm]
  Points2 normals;                ///< (n, 2) wall normals used
  std::vector<double> history;    ///< max |e| at the reference level per evaluation [mm]
  PathWallErrors before, after;   ///< nominal and compensated evaluations
};

/// Compensate the path `nominal` (n, 3) over `stock`. Throws std::invalid_argument for bad input
/// (including a path that never touches the stock); a non-converging scheme returns converged = false
/// with the best iterate (the smallest max |e| at the reference level over the active points).
/// Never worse: an active point whose |e| at the reference level ends above its uncompensated |e|
/// has its offset halved (at most six times, then zeroed) and the path evaluated again, so the
/// result is never worse than the program as written at any sample.
DeflectionCompensationResult compensate_deflection(const deflection::DeflectionModel& model,
                                                   const cutter::Cutter& cutter, const stock::ZMap& stock,
                                                   const Eigen::Ref<const Points3>& nominal,
                                                   const DeflectionCompensationOptions& options);

/// Which walls remain at the end of a program: wall point k touches the wall at `wall` row k (XY of
/// the contact of the tool's side with the wall, z its bottom) up to the height top[k]; it is cut
/// away when a cutting move j ≥ first_later[k] of `path` (tool tips (m, 3); move j joins rows j − 1
/// and j, cutting[j] ≠ 0 when it is a feed move; cutting[0] is ignored) passes closer than
/// radius − clearance to it in XY with its tip below top[k]. Returns (n) 1 where the wall remains.
/// Cost: a grid of the moves, so each wall point visits only the moves within reach.
Eigen::VectorXi wall_remains(const Eigen::Ref<const Points3>& wall, const Eigen::Ref<const VectorXd>& top,
                             const Eigen::Ref<const Eigen::VectorXi>& first_later,
                             const Eigen::Ref<const Points3>& path, const Eigen::Ref<const Eigen::VectorXi>& cutting,
                             double radius, double clearance);

/// A program's points measured against a drawing's contour (tool-centre polylines in the same order):
/// for each point the signed distance C along the drawing's wall normal (+ towards the wall), the
/// unit normal n there (so that foot + C·n is the point) and the arc length s of the foot along the
/// drawing [mm]. Each foot is searched from the previous one forwards over the arc length the point
/// has moved plus `window` [mm], so a pocket whose passes lie side by side is followed pass by pass.
struct DrawingOffsets {
  VectorXd offsets;  ///< (n) C [mm]
  Points2 normals;   ///< (n, 2) n
  VectorXd s;        ///< (n) arc length of the foot along the drawing [mm]
  VectorXd foot_distance;  ///< (n) |point − foot| [mm] (equals |C| unless the foot is a corner)
};
DrawingOffsets drawing_offsets(const Eigen::Ref<const Points3>& points, const Eigen::Ref<const Points3>& drawing,
                               deflection::WallSide side, double window = 2.0);

}  // namespace netshape::compensation

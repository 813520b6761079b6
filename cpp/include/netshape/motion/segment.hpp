#pragma once
/// \file segment.hpp
/// A piece of path as the planner sees it: a (trimmed) line, a (trimmed) arc, or a cubic Bézier
/// corner blend, parameterised by arc length s ∈ [0, length()].

#include <array>
#include <cstdint>

#include "netshape/core/types.hpp"
#include "netshape/toolpath/block.hpp"

namespace netshape::motion {

enum class SegmentKind : std::uint8_t { line = 0, arc = 1, blend = 2 };

/// Path segment. Lines and arcs keep the programmed block and a trimmed window
/// [trim_start, full_length − trim_end] of it (blends eat into their ends; the planner also cuts arcs
/// and blends into several windows); blends are cubic Béziers.
struct Segment {
  SegmentKind kind = SegmentKind::line;
  toolpath::Block block;           ///< line / arc: the programmed block
  std::array<Vec3, 4> ctrl{};      ///< blend: Bézier control points P0..P3 [mm]
  std::array<double, 17> table{};  ///< blend: arc length at u = i/16 [mm]
  double full_length = 0.0;        ///< line / arc: untrimmed length; blend: length [mm]
  double trim_start = 0.0;         ///< [mm] removed at the start
  double trim_end = 0.0;           ///< [mm] removed at the end
  double curvature = 0.0;          ///< largest curvature on the segment [1/mm]
  double curvature_rate = 0.0;     ///< largest |dκ/ds| [1/mm^2] (blends; 0 for lines and arcs)
  long source = -1;                ///< index of the program block (blend: the block before it)

  static Segment line(const toolpath::Block& b, long source);
  static Segment arc(const toolpath::Block& b, long source);
  /// Cubic Bézier with control points p0..p3 [mm]. When `tangent` / `curvature_vector` are given,
  /// they receive the unit tangent and the curvature vector [1/mm] at the table nodes u = i/16.
  static Segment blend(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3, long source,
                       std::array<Vec3, 17>* tangent = nullptr, std::array<Vec3, 17>* curvature_vector = nullptr);

  /// Length after trimming [mm].
  double length() const noexcept { return full_length - trim_start - trim_end; }
  /// Point at arc length s from the (trimmed) start [mm].
  Vec3 point_at(double s) const noexcept;
  /// Unit tangent at arc length s.
  Vec3 tangent_at(double s) const noexcept;
  /// Axes that move on this segment (|component| > 1e-12 anywhere): used for "Acc" of Lee & Lee.
  Vec3 moving_axes() const noexcept;
  /// Points of distance_to_piece's first pass over [s0, s1]: the piece at 65 evenly spaced arc lengths.
  using PiecePolyline = std::array<Vec3, 65>;
  /// Fill `out` with those points (arcs and blends; lines need none).
  void piece_polyline(double s0, double s1, PiecePolyline& out) const noexcept;
  /// Distance from p to the untrimmed programmed piece between arc lengths [s0, s1] [mm]. `coarse`:
  /// the piece_polyline of the same window, when the caller measures several points against it.
  /// `enough`: the caller only asks whether the distance is ≤ enough; the search stops at the first
  /// chord that close (it returns that chord's distance, then not always the smallest one).
  double distance_to_piece(const Vec3& p, double s0, double s1, const PiecePolyline* coarse = nullptr,
                           double enough = -1.0) const noexcept;
  /// Blend: the Bézier parameter u ∈ [0, 1] at arc length s from the untrimmed start [mm].
  double bezier_u(double s) const noexcept;
};

/// Blend `s` with its arc-length table filled: sets its largest curvature, largest |dκ/ds| between
/// neighbouring table nodes and its length, from the curvature at the 17 table nodes [1/mm].
/// `symmetric`: the second half of the table and of k_at mirrors the first (only it is scanned).
void finish_blend(Segment& s, const double (&k_at)[17], bool symmetric = false) noexcept;

/// The unit tangents and curvature vectors [1/mm] at the table nodes u = i/16 that Segment::blend
/// gives for the control points c (the same values), without the arc-length table.
void bezier_node_frames(const std::array<Vec3, 4>& c, std::array<Vec3, 17>& tangent,
                        std::array<Vec3, 17>& curvature_vector) noexcept;

/// Bézier point and first two derivatives with respect to u.
Vec3 bezier_point(const std::array<Vec3, 4>& c, double u) noexcept;
Vec3 bezier_d1(const std::array<Vec3, 4>& c, double u) noexcept;
Vec3 bezier_d2(const std::array<Vec3, 4>& c, double u) noexcept;

}  // namespace netshape::motion

#pragma once
/// \file engagement.hpp
/// Which cutter elements are in material at a cutter position (Kim et al. §3.2, docs/conventions.md §2).
///
/// Cutting frame at the tip (docs/conventions.md §2): X_c = horizontal unit feed direction, Z_c = +Z
/// (tool axis, tip → spindle), Y_c = Z_c × X_c (the left of the feed). The immersion angle φ runs clockwise
/// from +Y_c seen from the spindle (looking down −Z), the direction the cutter turns (M3):
///
///                    +Y_c  (φ = 0)
///                      |
///      φ = 3π/2  ------+------>  +X_c = feed   (φ = π/2)
///                      |
///                    −Y_c  (φ = π)
///
///     direction(φ) = sin φ · X_c + cos φ · Y_c
///     element(φ, z) = tip + z·Ẑ + r(z)·direction(φ),   r(z) = cutter.radius_at(z)
///
/// So up milling (φ_st = 0 … φ_ex = acos(1 − a_e/R)) has the material on the +Y_c (left) side,
/// down milling (φ_st = π − acos(1 − a_e/R) … π) on the −Y_c (right) side, and φ ∈ (0, π) is the
/// front half. An element is engaged when its point is in material (ZMap::is_material, pillar
/// model). Query the Z-map BEFORE sweeping the move that ends at `tip`: the material that move
/// removes is the material in front of the edges.

#include "netshape/core/types.hpp"
#include "netshape/cutter/cutter.hpp"
#include "netshape/stock/zmap.hpp"

namespace netshape::stock {

/// (k, m) boolean mask, row-major (NumPy bool).
using MaskR = Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// Unit cutting-frame axes for a feed direction (any 3-D vector with a horizontal part; the
/// horizontal part is used). Throws std::invalid_argument for a vertical or non-finite direction.
void cutting_frame(const Vec3& feed_direction, Vec3& x_c, Vec3& y_c);

/// Point of the cutter element at immersion φ [rad] and height z above the tip [mm].
Vec3 element_point(const cutter::Cutter& cutter, const Vec3& tip, const Vec3& feed_direction, double phi,
                   double z);

/// Engagement mask (k, m): entry (a, b) is true if the element at height z[a] [mm] above the tip and
/// angle phi[b] [rad] lies in material. Heights above the flute length are never engaged.
MaskR engaged_elements(const ZMap& zmap, const cutter::Cutter& cutter, const Vec3& tip,
                       const Vec3& feed_direction, const Eigen::Ref<const VectorXd>& phi,
                       const Eigen::Ref<const VectorXd>& z);
/// Same, into a preallocated (k, m) mask (resized only if its shape differs).
void engaged_elements_into(const ZMap& zmap, const cutter::Cutter& cutter, const Vec3& tip,
                           const Vec3& feed_direction, const Eigen::Ref<const VectorXd>& phi,
                           const Eigen::Ref<const VectorXd>& z, MaskR& out);

/// Radial and axial immersion read from the Z-map.
struct Immersion {
  bool engaged = false;      ///< any material touches the cutter's side within the flute length
  double phi_st = 0.0;       ///< start angle of the engaged arc [rad], in (−π, π]
  double phi_ex = 0.0;       ///< exit angle [rad], phi_st ≤ phi_ex < phi_st + 2π
  double axial_depth = 0.0;  ///< largest height of material above the tip on the engaged arc [mm]
  double radial_depth = 0.0; ///< R·(cos φ_st − cos φ_ex): the width of the engaged arc across the
                             ///< feed; equals a_e for up, down and slot milling [mm]
};

/// Options of `immersion`.
struct ImmersionOptions {
  int angles = 720;              ///< angular scan resolution (then each edge is bisected to 1e-9 rad)
  double probe_height = 1e-6;    ///< height above the tip [mm] at which radial engagement is read
  void validate() const;
};

/// Radial immersion (φ_st, φ_ex) and axial depth of the cutter at `tip` moving along
/// `feed_direction`, from the Z-map: the engaged arc at `probe_height` above the tip at the
/// nominal radius (the arc that remains after removing the largest material-free gap), and the
/// material height above the tip along it (pillar heights, capped at the flute length). Meant for
/// flat end mills (the side is a cylinder); other cutters use their nominal radius.
Immersion immersion(const ZMap& zmap, const cutter::Cutter& cutter, const Vec3& tip, const Vec3& feed_direction,
                    const ImmersionOptions& options = {});

}  // namespace netshape::stock

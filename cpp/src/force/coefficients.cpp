#include "netshape/force/coefficients.hpp"

#include <cmath>
#include <stdexcept>

#include "netshape/core/error.hpp"
#include "netshape/core/types.hpp"

namespace netshape::force {

void LinearEdgeCoefficients::validate() const {
  NETSHAPE_CHECK_FINITE("ktc", ktc);
  NETSHAPE_CHECK_FINITE("krc", krc);
  NETSHAPE_CHECK_FINITE("kac", kac);
  NETSHAPE_CHECK_FINITE("kte", kte);
  NETSHAPE_CHECK_FINITE("kre", kre);
  NETSHAPE_CHECK_FINITE("kae", kae);
}

void KlineDevorCoefficients::validate() const {
  NETSHAPE_CHECK_FINITE("kt", kt);
  NETSHAPE_CHECK(kt > 0.0, "kt", kt, "must be positive [N/mm^2]");
  NETSHAPE_CHECK_FINITE("kr", kr);
}

void BallEndCoefficients::validate() const {
  static const char* an[] = {"a0", "a1", "a2", "a3"};
  static const char* bn[] = {"b0", "b1", "b2", "b3"};
  for (int i = 0; i < 4; ++i) {
    NETSHAPE_CHECK_FINITE(an[i], a[i]);
    NETSHAPE_CHECK_FINITE(bn[i], b[i]);
  }
  NETSHAPE_CHECK_FINITE("m_t", m_t);
  NETSHAPE_CHECK(m_t > 0.0 && m_t <= 2.0, "m_t", m_t, "must be in (0, 2]");
  NETSHAPE_CHECK_FINITE("m_r", m_r);
  NETSHAPE_CHECK(m_r > 0.0 && m_r <= 2.0, "m_r", m_r, "must be in (0, 2]");
}

BallEndCoefficientSet ball_end_coefficient_set(const std::string& name) {
  if (name == "kim_zas_ball12") {
    BallEndCoefficientSet s;
    s.name = name;
    s.coefficients.a = {321.7, 803.1, -1165.5, 550.7};
    s.coefficients.b = {104.1, 139.1, -213.1, 69.3};
    s.coefficients.m_t = 0.7053;
    s.coefficients.m_r = 0.4788;
    s.diameter = 12.0;
    s.flutes = 2;
    s.helix = deg2rad(30.0);
    s.source =
        "G. M. Kim, P. J. Cho, B. H. Kim, C. N. Chu, 'Cutting force prediction in the ball-end milling "
        "process of various cutting area using Z-map' §4.2 (docs/references.md): zinc alloy ZAS, 600 rpm";
    return s;
  }
  throw std::invalid_argument("coefficient_set = " + name + ": unknown ball-end coefficient set (known: kim_zas_ball12)");
}

LinearEdgeCoefficientSet linear_edge_coefficient_set(const std::string& name) {
  if (name == "leekunhwee_flat_slot") {
    LinearEdgeCoefficientSet s;
    s.name = name;
    s.coefficients = {958.8, 251.1, 146.4, 15.8, 19.4, 18.2};
    s.source =
        "reference regression of the leekunhwee-flat-slot DynoWare recordings (Jianhui Li's slot cuts, "
        "README of github.com/leekunhwee/ForceCalculation): 2-flute flat end mill, slot, a_p = 3 mm, 6000 rpm";
    return s;
  }
  throw std::invalid_argument("coefficient_set = " + name +
                              ": unknown linear edge coefficient set (known: leekunhwee_flat_slot)");
}

std::vector<std::string> ball_end_coefficient_set_names() { return {"kim_zas_ball12"}; }
std::vector<std::string> linear_edge_coefficient_set_names() { return {"leekunhwee_flat_slot"}; }

}  // namespace netshape::force

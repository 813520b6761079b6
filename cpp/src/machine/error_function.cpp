// Error components of a linear axis: construction, validation and evaluation (polynomial by Horner,
// table through table_interpolation.hpp).
#include "netshape/machine/error_function.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "netshape/core/error.hpp"
#include "netshape/machine/table_interpolation.hpp"

namespace netshape::machine {

ErrorFunction ErrorFunction::zero_function(std::string name) {
  ErrorFunction f;
  f.name = std::move(name);
  return f;
}

ErrorFunction ErrorFunction::polynomial(std::vector<double> coefficients, std::string name) {
  ErrorFunction f;
  f.kind = Kind::polynomial;
  f.coefficients = std::move(coefficients);
  f.name = std::move(name);
  f.validate();
  return f;
}

ErrorFunction ErrorFunction::table(std::vector<double> positions, std::vector<double> values,
                                   OutOfRange out_of_range, std::string name) {
  ErrorFunction f;
  f.kind = Kind::table;
  f.positions = std::move(positions);
  f.values = std::move(values);
  f.out_of_range = out_of_range;
  f.name = std::move(name);
  f.validate();
  return f;
}

void ErrorFunction::validate() const {
  const std::string who = name.empty() ? std::string("error component") : name;
  switch (kind) {
    case Kind::zero:
      return;
    case Kind::polynomial:
      for (std::size_t i = 0; i < coefficients.size(); ++i) {
        if (!std::isfinite(coefficients[i])) {
          const std::string field = who + " coefficient[" + std::to_string(i) + "]";
          netshape::detail::throw_invalid(field.c_str(), coefficients[i], "must be a finite number");
        }
      }
      return;
    case Kind::table: {
      if (positions.size() < 2) {
        const std::string field = who + " table points";
        netshape::detail::throw_invalid(field.c_str(), positions.size(), "a table needs at least 2 positions");
      }
      if (positions.size() != values.size()) {
        const std::string field = who + " table values";
        netshape::detail::throw_invalid(field.c_str(), values.size(), "must have as many values as positions");
      }
      for (std::size_t i = 0; i < positions.size(); ++i) {
        if (!std::isfinite(positions[i])) {
          const std::string field = who + " position[" + std::to_string(i) + "]";
          netshape::detail::throw_invalid(field.c_str(), positions[i], "must be a finite number [mm]");
        }
        if (!std::isfinite(values[i])) {
          const std::string field = who + " value[" + std::to_string(i) + "]";
          netshape::detail::throw_invalid(field.c_str(), values[i], "must be a finite number");
        }
        if (i > 0 && !(positions[i] > positions[i - 1])) {
          const std::string field = who + " position[" + std::to_string(i) + "]";
          netshape::detail::throw_invalid(field.c_str(), positions[i],
                                "table positions must be strictly increasing [mm]");
        }
      }
      return;
    }
  }
  throw std::invalid_argument(who + ": unknown kind");
}

double ErrorFunction::operator()(double q) const {
  switch (kind) {
    case Kind::zero:
      return 0.0;
    case Kind::polynomial: {
      double r = 0.0;
      for (auto it = coefficients.rbegin(); it != coefficients.rend(); ++it) r = r * q + *it;
      return r;
    }
    case Kind::table: {
      // positions are not scanned for equal spacing here (binary search); a CompiledMachine does that once
      const detail::TableGrid grid = detail::table_grid(positions, false);
      const detail::TableLookup at = detail::look_up<false>(grid, out_of_range, q);
      if (at.where == detail::TableLookup::Where::refused) {
        std::ostringstream os;
        os.precision(17);
        os << (name.empty() ? std::string("error component") : name) << " position = " << q
           << ": outside the table range [" << grid.lo << ", " << grid.hi
           << "] mm (out_of_range = \"error\"; use \"clamp\" or \"extrapolate\" to allow it)";
        throw std::invalid_argument(os.str());
      }
      return detail::table_value<false>(at, values.data(), grid.n, 1, 0, nullptr);
    }
  }
  return 0.0;
}

}  // namespace netshape::machine

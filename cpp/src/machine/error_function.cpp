// Error components of a linear axis: polynomial or table with linear interpolation.
#include "netshape/machine/error_function.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "netshape/core/error.hpp"

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
          detail::throw_invalid(field.c_str(), coefficients[i], "must be a finite number");
        }
      }
      return;
    case Kind::table: {
      if (positions.size() < 2) {
        const std::string field = who + " table points";
        detail::throw_invalid(field.c_str(), positions.size(), "a table needs at least 2 positions");
      }
      if (positions.size() != values.size()) {
        const std::string field = who + " table values";
        detail::throw_invalid(field.c_str(), values.size(), "must have as many values as positions");
      }
      for (std::size_t i = 0; i < positions.size(); ++i) {
        if (!std::isfinite(positions[i])) {
          const std::string field = who + " position[" + std::to_string(i) + "]";
          detail::throw_invalid(field.c_str(), positions[i], "must be a finite number [mm]");
        }
        if (!std::isfinite(values[i])) {
          const std::string field = who + " value[" + std::to_string(i) + "]";
          detail::throw_invalid(field.c_str(), values[i], "must be a finite number");
        }
        if (i > 0 && !(positions[i] > positions[i - 1])) {
          const std::string field = who + " position[" + std::to_string(i) + "]";
          detail::throw_invalid(field.c_str(), positions[i],
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
      const std::size_t n = positions.size();
      const double lo = positions.front(), hi = positions.back();
      std::size_t i;  // segment [i, i+1]
      if (q < lo || q > hi || !std::isfinite(q)) {
        if (out_of_range == OutOfRange::error || !std::isfinite(q)) {
          std::ostringstream os;
          os.precision(17);
          os << (name.empty() ? std::string("error component") : name) << " position = " << q
             << ": outside the table range [" << lo << ", " << hi
             << "] mm (out_of_range = \"error\"; use \"clamp\" or \"extrapolate\" to allow it)";
          throw std::invalid_argument(os.str());
        }
        if (out_of_range == OutOfRange::clamp) return q < lo ? values.front() : values.back();
        i = q < lo ? 0 : n - 2;
      } else {
        i = static_cast<std::size_t>(std::upper_bound(positions.begin(), positions.end(), q) -
                                     positions.begin());
        i = i == 0 ? 0 : std::min(i - 1, n - 2);
      }
      const double t = (q - positions[i]) / (positions[i + 1] - positions[i]);
      return values[i] + t * (values[i + 1] - values[i]);
    }
  }
  return 0.0;
}

}  // namespace netshape::machine

#include "contact_model/ContactParameters.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace spacetree::contact_model {

double ContactParameters::require(const std::string& name, const char* who, bool positive) const {
  const auto it = values_.find(name);
  if (it == values_.end())
    throw std::invalid_argument(std::string(who) + ": coefficient " + name + " missing");
  const double v = it->second;
  if (!std::isfinite(v) || v < 0.0 || (positive && v == 0.0)) {
    std::ostringstream msg;
    msg << who << ": coefficient " << name << " = " << v << " must be a finite number "
        << (positive ? "> 0" : ">= 0");
    throw std::invalid_argument(msg.str());
  }
  return v;
}

}  // namespace spacetree::contact_model

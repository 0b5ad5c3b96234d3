#include "costmap_layers/core/input_error.hpp"

#include <sstream>

namespace costmap_layers
{
std::string valueText(double value)
{
  std::ostringstream s;
  s << value;
  return s.str();
}
}  // namespace costmap_layers

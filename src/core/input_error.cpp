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

std::string shownText(const std::string& text, std::size_t max)
{
  if (text.size() <= max) return text;
  return text.substr(0, max) + "... (" + std::to_string(text.size()) + " characters)";
}
}  // namespace costmap_layers

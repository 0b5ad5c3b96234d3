#include "costmap_layers/core/config/input_error.hpp"

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

std::string rosNameProblem(const std::string& name, bool allow_private)
{
  if (name.empty()) return "is empty, not a ROS name";
  const auto letter = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); };
  for (std::size_t k = 0; k < name.size(); ++k)
  {
    const char c = name[k];
    const bool ok = k == 0 ? letter(c) || c == '/' || (allow_private && c == '~')
                           : letter(c) || (c >= '0' && c <= '9') || c == '_' || c == '/';
    if (ok) continue;
    const bool printable = c > ' ' && c < 127;
    std::string shown;
    for (const char d : shownText(name, 200))
      shown += d >= ' ' && d < 127 ? d : '?';
    return "'" + shown + "' is not a ROS name: " +
           (printable ? "'" + std::string(1, c) + "'"
                      : std::string("character code ") + std::to_string(static_cast<unsigned char>(c))) +
           " at position " + std::to_string(k) + " (a letter, '/'" + (allow_private ? " or '~'" : "") +
           " first, then letters, digits, '_' and '/')";
  }
  return "";
}
}  // namespace costmap_layers

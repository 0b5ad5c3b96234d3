#include "costmap_layers/core/grid/footprint.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "costmap_layers/core/config/input_error.hpp"
#include "costmap_layers/core/rules/limits.hpp"
#include "costmap_layers/core/config/param_reader.hpp"

namespace costmap_layers
{
Footprint makeFootprintFromRadius(double radius)
{
  constexpr int N = 16;
  Footprint points;
  points.reserve(N);
  for (int i = 0; i < N; ++i)
  {
    const double angle = i * 2.0 * M_PI / N;
    points.emplace_back(radius * std::cos(angle), radius * std::sin(angle));
  }
  return points;
}

void padFootprint(Footprint& footprint, double padding)
{
  for (auto& p : footprint)
  {
    p.x() += (p.x() > 0.0 ? padding : (p.x() < 0.0 ? -padding : 0.0));
    p.y() += (p.y() > 0.0 ? padding : (p.y() < 0.0 ? -padding : 0.0));
  }
}

namespace
{
double distanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b)
{
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}
}  // namespace

void calculateMinAndMaxDistances(const Footprint& footprint, double& min_dist, double& max_dist)
{
  min_dist = std::numeric_limits<double>::max();
  max_dist = 0.0;
  if (footprint.size() <= 2)
  {
    min_dist = 0.0;
    for (const auto& p : footprint)
      max_dist = std::max(max_dist, p.norm());
    return;
  }
  const Eigen::Vector2d origin(0.0, 0.0);
  for (std::size_t i = 0; i < footprint.size(); ++i)
  {
    const auto& a = footprint[i];
    const auto& b = footprint[(i + 1) % footprint.size()];
    min_dist = std::min(min_dist, distanceToSegment(origin, a, b));
    max_dist = std::max(max_dist, a.norm());
  }
}

Footprint parseFootprintString(const std::string& text)
{
  // Accept exactly nested brackets of numbers: [[x, y], [x, y], ...].
  auto fail = [&text](const std::string& why)
  { throw std::invalid_argument("footprint \"" + shownText(text) + "\": " + why); };
  std::vector<double> numbers;
  std::vector<int> group_sizes;
  int depth = 0;
  int in_group = 0;
  std::size_t i = 0;
  while (i < text.size())
  {
    const char c = text[i];
    if (std::isspace(static_cast<unsigned char>(c)) || c == ',')
    {
      ++i;
      continue;
    }
    if (c == '[')
    {
      if (++depth > 2) fail("too many nested brackets");
      in_group = 0;
      ++i;
      continue;
    }
    if (c == ']')
    {
      if (depth == 2) group_sizes.push_back(in_group);
      if (--depth < 0) fail("unbalanced brackets");
      ++i;
      continue;
    }
    if (depth != 2) fail("numbers must stand inside [x, y] pairs");
    // strtod in place: a copy of the rest of the text per number would make a long string quadratic.
    const char* start = text.c_str() + i;
    char* end = nullptr;
    const double v = std::strtod(start, &end);
    const auto used = static_cast<std::size_t>(end - start);
    if (used == 0) fail("cannot read a number at position " + std::to_string(i));
    // strtod also reads hexadecimal ("0x10" = 16), inf and nan; costmap_2d reads decimal only.
    const std::string token = text.substr(i, used);
    if (token.find_first_not_of("0123456789+-.eE") != std::string::npos)
      fail("'" + shownText(token) + "' at position " + std::to_string(i) + " is not a decimal number");
    if (!std::isfinite(v)) fail("values must be finite");
    numbers.push_back(v);
    ++in_group;
    i += used;
  }
  if (depth != 0) fail("unbalanced brackets");
  for (int n : group_sizes)
  {
    if (n != 2) fail("each point needs exactly two numbers");
  }
  if (group_sizes.size() < 3) fail("a footprint needs at least 3 points");
  Footprint fp;
  for (std::size_t k = 0; k + 1 < numbers.size(); k += 2)
    fp.emplace_back(numbers[k], numbers[k + 1]);
  return fp;
}

Footprint transformFootprint(double x, double y, double yaw, const Footprint& footprint)
{
  const double c = std::cos(yaw), s = std::sin(yaw);
  Footprint out;
  out.reserve(footprint.size());
  for (const auto& p : footprint)
    out.emplace_back(x + c * p.x() - s * p.y(), y + s * p.x() + c * p.y());
  return out;
}

std::string footprintProblem(const Footprint& footprint)
{
  if (footprint.size() < 3) return "a footprint needs at least 3 points (got " + std::to_string(footprint.size()) + ")";
  for (std::size_t k = 0; k < footprint.size(); ++k)
  {
    const Eigen::Vector2d& v = footprint[k];
    // A vertex is a length from the robot's centre: finite, and within kMaxDistance as robot_radius.
    const bool finite = std::isfinite(v.x()) && std::isfinite(v.y());
    if (!finite || std::fabs(v.x()) > limits::kMaxDistance || std::fabs(v.y()) > limits::kMaxDistance)
    {
      std::ostringstream what;
      what << "vertex " << k << " (" << v.x() << ", " << v.y() << ") "
           << (finite ? "is farther than " + std::to_string(limits::kMaxDistance) + " m from the robot's centre"
                      : std::string("is not finite"));
      return what.str();
    }
  }
  return {};
}

Footprint FootprintConfig::padded() const
{
  Footprint fp = footprint.empty() ? makeFootprintFromRadius(robot_radius) : footprint;
  padFootprint(fp, footprint_padding);
  return fp;
}

namespace
{
/// The `footprint` parameter into cfg.footprint (left empty for costmap_2d's "[]", which means: use
/// robot_radius); params.fail() for anything else that is not a valid polygon.
void parseFootprintValue(const ParamValue& value, const ParamReader& params, FootprintConfig& cfg)
{
  try
  {
    if (value.type() == ParamValue::Type::String)
    {
      // "[]" is costmap_2d's way of saying "no polygon, use robot_radius".
      std::string compact;
      for (char c : value.asString())
        if (!std::isspace(static_cast<unsigned char>(c))) compact += c;
      if (compact != "[]" && !compact.empty()) cfg.footprint = parseFootprintString(value.asString());
    }
    else
    {
      const auto& points = value.asList();
      if (points.empty()) return;
      if (points.size() < 3) throw std::invalid_argument("a footprint needs at least 3 points");
      for (const auto& p : points)
      {
        const auto& xy = p.asList();
        if (xy.size() != 2) throw std::invalid_argument("each point needs exactly two numbers");
        const double x = xy[0].asDouble(), y = xy[1].asDouble();
        if (!std::isfinite(x) || !std::isfinite(y)) throw std::invalid_argument("values must be finite");
        cfg.footprint.emplace_back(x, y);
      }
    }
    if (!cfg.footprint.empty())
    {
      const std::string problem = footprintProblem(cfg.footprint);
      if (!problem.empty()) throw std::invalid_argument(problem);
    }
  }
  catch (const std::invalid_argument& e)
  {
    params.fail("footprint", std::string("is not a valid polygon: ") + e.what());
  }
}
}  // namespace

FootprintConfig parseFootprintConfig(const ParamReader& params)
{
  FootprintConfig cfg;
  cfg.robot_radius = params.getDouble("robot_radius", cfg.robot_radius, 0.0, limits::kMaxDistance);
  // costmap_2d takes any padding; a negative one shrinks the footprint.
  cfg.footprint_padding =
      params.getDouble("footprint_padding", cfg.footprint_padding, -limits::kMaxDistance, limits::kMaxDistance);
  params.declare("footprint", "[[x, y], ...] in the robot frame [m], or that text",
                 "none: the circle of robot_radius");
  const ParamValue* fp = params.raw("footprint");
  if (fp != nullptr && !fp->isNull()) parseFootprintValue(*fp, params, cfg);
  // A shrink as large as a vertex's distance from the robot's axes would move that vertex across
  // them (costmap_2d's padFootprint would mirror it): refused, for a polygon and for the circle of
  // robot_radius alike. A coordinate within 1e-9 of the radius is on an axis (cos(pi / 2) is 6e-17, not
  // 0, in makeFootprintFromRadius): padFootprint moves it by at most the padding, along the axis.
  if (cfg.footprint_padding < 0.0)
  {
    const Footprint base = cfg.footprint.empty() ? makeFootprintFromRadius(cfg.robot_radius) : cfg.footprint;
    double reach = 0.0;
    for (const auto& p : base)
      reach = std::max(reach, p.norm());
    const double on_axis = 1e-9 * reach;
    for (const auto& p : base)
      if ((std::abs(p.x()) > on_axis && std::abs(p.x()) <= -cfg.footprint_padding) ||
          (std::abs(p.y()) > on_axis && std::abs(p.y()) <= -cfg.footprint_padding))
      {
        std::ostringstream what;
        what << "shrinks the footprint by more than its vertex (" << p.x() << ", " << p.y()
             << ") is away from the robot's axes: that vertex would cross them";
        params.fail("footprint_padding", what.str());
      }
  }
  return cfg;
}
}  // namespace costmap_layers

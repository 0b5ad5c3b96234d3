#include "costmap_layers/core/config/param_reader.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include "costmap_layers/core/config/input_error.hpp"

namespace costmap_layers
{
void ParamReader::fail(const std::string& name, const std::string& what) const
{
  const ParamValue* v = ns_.find(name);
  std::ostringstream msg;
  msg << owner_ << ": parameter '" << name << "' " << what;
  if (v != nullptr) msg << " (got " << v->toString() << ")";
  throw std::invalid_argument(msg.str());
}

namespace
{
thread_local ParamSpecLog* g_spec_log = nullptr;
}

ParamSpecLog::ParamSpecLog() : previous_(g_spec_log)
{
  g_spec_log = this;
}
ParamSpecLog::~ParamSpecLog()
{
  g_spec_log = previous_;
}
ParamSpecLog* ParamSpecLog::current()
{
  return g_spec_log;
}

void ParamReader::note(ParamSpec spec) const
{
  if (ParamSpecLog* log = ParamSpecLog::current()) log->entries().push_back({owner_, spec});
  if (record_ != nullptr) record_->push_back(std::move(spec));
}

void ParamReader::declare(const std::string& name, const std::string& what, const std::string& default_text) const
{
  if (ParamSpecLog* log = ParamSpecLog::current())
  {
    ParamSpec spec;
    spec.name = name;
    spec.default_value = ParamValue::makeString(default_text);
    spec.role = what;
    log->entries().push_back({owner_, std::move(spec)});
  }
}

bool ParamReader::getBool(const std::string& name, bool def) const
{
  const ParamValue* v = ns_.find(name);
  bool value = def;
  if (v == nullptr)
    value = def;
  else if (v->type() == ParamValue::Type::Bool)
    value = v->asBool();
  // rosparam stores 0/1 for some older configs: accept those two integers, nothing else.
  else if (v->type() == ParamValue::Type::Int && (v->asInt() == 0 || v->asInt() == 1))
    value = v->asInt() == 1;
  else
    fail(name, "must be a boolean");
  note({name, ParamValue::Type::Bool, ParamValue::makeBool(def), ParamValue::makeBool(value), 0, 1, {}, {}});
  return value;
}

int ParamReader::getInt(const std::string& name, int def, int min, int max) const
{
  const ParamValue* v = ns_.find(name);
  const auto noted = [&](int value)
  {
    note({name,
          ParamValue::Type::Int,
          ParamValue::makeInt(def),
          ParamValue::makeInt(value),
          double(min),
          double(max),
          {},
          {}});
    return value;
  };
  if (v == nullptr) return noted(def);
  int64_t value = 0;
  if (v->type() == ParamValue::Type::Int)
    value = v->asInt();
  else if (v->type() == ParamValue::Type::Double && std::isfinite(v->asDouble()) &&
           std::floor(v->asDouble()) == v->asDouble() && std::fabs(v->asDouble()) < 1e15)
    value = static_cast<int64_t>(v->asDouble());
  else
    fail(name, "must be an integer");
  if (value < min || value > max) fail(name, "must be in [" + std::to_string(min) + ", " + std::to_string(max) + "]");
  return noted(static_cast<int>(value));
}

double ParamReader::getDouble(const std::string& name, double def, double min, double max) const
{
  const ParamValue* v = ns_.find(name);
  const auto noted = [&](double value)
  {
    note(
        {name, ParamValue::Type::Double, ParamValue::makeDouble(def), ParamValue::makeDouble(value), min, max, {}, {}});
    return value;
  };
  if (v == nullptr) return noted(def);
  if (!v->isNumber())
  {
    // rosparam (PyYAML, YAML 1.1) reads 5e-2, 1e3 and -.5 as strings: say how to write them.
    if (v->type() == ParamValue::Type::String && !v->asString().empty())
    {
      const std::string& text = v->asString();
      char* end = nullptr;
      std::strtod(text.c_str(), &end);
      const bool plain = text.find_first_not_of("0123456789+-.eE") == std::string::npos;
      if (plain && end != nullptr && *end == '\0')
        fail(name,
             "must be a number; rosparam (YAML 1.1) reads this as a string: write a float with a dot and, "
             "for an exponent, its sign (5.0e-2, 1.0e+3, -0.5)");
    }
    fail(name, "must be a number");
  }
  const double value = v->asDouble();
  if (!std::isfinite(value)) fail(name, "must be finite");
  if (value < min || value > max)
  {
    std::ostringstream range;
    range << "must be in [" << min << ", " << max << "]";
    fail(name, range.str());
  }
  return noted(value);
}

std::string ParamReader::getString(const std::string& name, const std::string& def) const
{
  const ParamValue* v = ns_.find(name);
  if (v != nullptr && v->type() != ParamValue::Type::String) fail(name, "must be a string");
  const std::string value = v != nullptr ? v->asString() : def;
  note({name, ParamValue::Type::String, ParamValue::makeString(def), ParamValue::makeString(value), 0, 0, {}, {}});
  return value;
}

void ParamReader::markRole(const char* role) const
{
  if (record_ != nullptr) record_->back().role = role;
  if (ParamSpecLog* log = ParamSpecLog::current()) log->entries().back().spec.role = role;
}

std::string ParamReader::getTopic(const std::string& name, const std::string& def, bool allow_empty) const
{
  const std::string value = getString(name, def);
  markRole("topic");
  if (value.empty() && allow_empty) return value;
  const std::string problem = rosNameProblem(value);
  if (!problem.empty()) fail(name, "must be a topic name: " + problem);
  return value;
}

std::string ParamReader::getFrameId(const std::string& name, const std::string& def, bool allow_empty) const
{
  const std::string value = getString(name, def);
  markRole("frame id");
  if (value.empty() && allow_empty) return value;
  const std::string problem = frameIdProblem(value);
  if (!problem.empty()) fail(name, "must be a frame id: the frame id " + problem);
  return value;
}

std::string ParamReader::getChoice(const std::string& name, const std::string& def,
                                   const std::vector<std::string>& choices) const
{
  const std::string value = getString(name, def);
  for (const auto& c : choices)
  {
    if (c == value)
    {
      if (record_ != nullptr) record_->back().choices = choices;
      if (ParamSpecLog* log = ParamSpecLog::current()) log->entries().back().spec.choices = choices;
      return value;
    }
  }
  std::string list;
  for (const auto& c : choices)
    list += (list.empty() ? "" : ", ") + c;
  fail(name, "must be one of: " + list);
}
}  // namespace costmap_layers

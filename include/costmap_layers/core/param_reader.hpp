// Typed, validated reads from one parameter namespace. Each config struct has one parse function
// built on this, so every parameter name is written once, next to its default and its limits.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "costmap_layers/core/param_value.hpp"

namespace costmap_layers
{
class ParamReader
{
public:
  /// @param ns     the namespace (a Map, or Null for "nothing set")
  /// @param owner  who reads, for error messages (e.g. "gradient_layer_1")
  ParamReader(const ParamValue& ns, std::string owner) : ns_(ns), owner_(std::move(owner)) {}

  bool has(const std::string& name) const { return ns_.find(name) != nullptr; }
  const ParamValue* raw(const std::string& name) const { return ns_.find(name); }
  const ParamValue& ns() const { return ns_; }
  const std::string& owner() const { return owner_; }

  /// Each getter returns the default when the name is absent and throws std::invalid_argument
  /// ("owner: parameter 'name' ...: value") when the value has the wrong type or is out of range.
  bool getBool(const std::string& name, bool def) const;
  int getInt(const std::string& name, int def, int min = std::numeric_limits<int>::min(),
             int max = std::numeric_limits<int>::max()) const;
  /// Rejects NaN and infinities as well as values outside [min, max].
  double getDouble(const std::string& name, double def, double min = std::numeric_limits<double>::lowest(),
                   double max = std::numeric_limits<double>::max()) const;
  std::string getString(const std::string& name, const std::string& def) const;
  /// Accepts one of the given choices only.
  std::string getChoice(const std::string& name, const std::string& def, const std::vector<std::string>& choices) const;

  /// Throws "owner: parameter 'name' <what> (value)".
  [[noreturn]] void fail(const std::string& name, const std::string& what) const;

private:
  const ParamValue& ns_;
  std::string owner_;
};
}  // namespace costmap_layers

// Creates layers by pluginlib type name (e.g. "costmap_layers/GradientLayer").
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "costmap_layers/core/costmap/layer.hpp"

namespace costmap_layers_ros
{
class PluginFactory
{
public:
  PluginFactory();
  ~PluginFactory();
  /// Creates a layer of `type`, or of the class a costmap_2d / Nav2 type name stands for
  /// (costmap_layers::resolvePluginType()). Throws std::runtime_error naming the type and listing the
  /// available types when it is unknown or cannot be loaded.
  std::shared_ptr<costmap_layers::Layer> create(const std::string& type);
  std::vector<std::string> availableTypes() const;
  /// The <description> of a type in the plugin description file.
  std::string description(const std::string& type) const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};
}  // namespace costmap_layers_ros

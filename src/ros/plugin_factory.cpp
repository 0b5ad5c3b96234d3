#include "costmap_layers/ros/plugin_factory.hpp"

#include <pluginlib/class_loader.hpp>
#include <stdexcept>

#include "costmap_layers/core/config/config_compat.hpp"

namespace costmap_layers_ros
{
struct PluginFactory::Impl
{
  pluginlib::ClassLoader<costmap_layers::Layer> loader{"costmap_layers", "costmap_layers::Layer"};
};

PluginFactory::PluginFactory() : impl_(std::make_unique<Impl>()) {}

// The loader must outlive every layer it created: the owner destroys layers first.
PluginFactory::~PluginFactory() = default;

std::vector<std::string> PluginFactory::availableTypes() const
{
  return impl_->loader.getDeclaredClasses();
}

std::string PluginFactory::description(const std::string& type) const
{
  return impl_->loader.getClassDescription(type);
}

std::shared_ptr<costmap_layers::Layer> PluginFactory::create(const std::string& written_type)
{
  // costmap_2d's and Nav2's names for the layers this package re-implements load its own classes.
  const std::string type = costmap_layers::resolvePluginType(written_type);
  std::string list;
  for (const auto& t : availableTypes())
    list += (list.empty() ? "" : ", ") + t;
  if (!impl_->loader.isClassAvailable(type))
    throw std::runtime_error("unknown plugin type '" + written_type + "'; available types: " + list +
                             " (and the costmap_2d / Nav2 names of these, see the README)");
  try
  {
    return impl_->loader.createSharedInstance(type);
  }
  catch (const pluginlib::PluginlibException& e)
  {
    throw std::runtime_error("plugin type '" + type + "' failed to load: " + e.what() + "; available types: " + list);
  }
}
}  // namespace costmap_layers_ros

#include "costmap_layers/ros/plugin_factory.hpp"

#include <pluginlib/class_loader.hpp>
#include <stdexcept>

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

std::shared_ptr<costmap_layers::Layer> PluginFactory::create(const std::string& type)
{
  std::string list;
  for (const auto& t : availableTypes())
    list += (list.empty() ? "" : ", ") + t;
  if (!impl_->loader.isClassAvailable(type))
    throw std::runtime_error("unknown plugin type '" + type + "'; available types: " + list);
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

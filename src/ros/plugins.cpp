// Every pluginlib export of the package, in one file built into its own library.
#include <pluginlib/class_list_macros.hpp>

#include "costmap_layers/core/layers/asymmetric_inflation_layer.hpp"
#include "costmap_layers/core/filters/binary_filter.hpp"
#include "costmap_layers/core/layers/denoise_layer.hpp"
#include "costmap_layers/core/layers/gradient_layer.hpp"
#include "costmap_layers/core/layers/inflation_layer.hpp"
#include "costmap_layers/core/filters/keepout_filter.hpp"
#include "costmap_layers/core/filters/lanes_filter.hpp"
#include "costmap_layers/core/layers/obstacle_layer.hpp"
#include "costmap_layers/core/layers/plugin_container_layer.hpp"
#include "costmap_layers/core/layers/range_sensor_layer.hpp"
#include "costmap_layers/core/filters/speed_filter.hpp"
#include "costmap_layers/core/layers/static_layer.hpp"
#include "costmap_layers/core/layers/voxel_layer.hpp"
#include "costmap_layers/core/filters/zone_parameter_filter.hpp"

PLUGINLIB_EXPORT_CLASS(costmap_layers::GradientLayer, costmap_layers::Layer)
PLUGINLIB_EXPORT_CLASS(costmap_layers::KeepoutFilter, costmap_layers::Layer)
PLUGINLIB_EXPORT_CLASS(costmap_layers::StaticLayer, costmap_layers::Layer)
PLUGINLIB_EXPORT_CLASS(costmap_layers::InflationLayer, costmap_layers::Layer)
PLUGINLIB_EXPORT_CLASS(costmap_layers::SpeedFilter, costmap_layers::Layer)
PLUGINLIB_EXPORT_CLASS(costmap_layers::LanesFilter, costmap_layers::Layer)
PLUGINLIB_EXPORT_CLASS(costmap_layers::ObstacleLayer, costmap_layers::Layer)
PLUGINLIB_EXPORT_CLASS(costmap_layers::VoxelLayer, costmap_layers::Layer)
PLUGINLIB_EXPORT_CLASS(costmap_layers::RangeSensorLayer, costmap_layers::Layer)
PLUGINLIB_EXPORT_CLASS(costmap_layers::ZoneParameterFilter, costmap_layers::Layer)
PLUGINLIB_EXPORT_CLASS(costmap_layers::BinaryFilter, costmap_layers::Layer)
PLUGINLIB_EXPORT_CLASS(costmap_layers::DenoiseLayer, costmap_layers::Layer)
PLUGINLIB_EXPORT_CLASS(costmap_layers::AsymmetricInflationLayer, costmap_layers::Layer)
PLUGINLIB_EXPORT_CLASS(costmap_layers::PluginContainerLayer, costmap_layers::Layer)

// Every pluginlib export of the package, in one file built into its own library.
#include <pluginlib/class_list_macros.hpp>

#include "costmap_layers/core/gradient_layer.hpp"
#include "costmap_layers/core/inflation_layer.hpp"
#include "costmap_layers/core/keepout_filter.hpp"
#include "costmap_layers/core/static_layer.hpp"

PLUGINLIB_EXPORT_CLASS(costmap_layers::GradientLayer, costmap_layers::Layer)
PLUGINLIB_EXPORT_CLASS(costmap_layers::KeepoutFilter, costmap_layers::Layer)
PLUGINLIB_EXPORT_CLASS(costmap_layers::StaticLayer, costmap_layers::Layer)
PLUGINLIB_EXPORT_CLASS(costmap_layers::InflationLayer, costmap_layers::Layer)

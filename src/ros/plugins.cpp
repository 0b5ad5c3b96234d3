// Every pluginlib export of the package, in one file built into its own library.
#include <pluginlib/class_list_macros.hpp>

#include "costmap_layers/core/gradient_layer.hpp"
#include "costmap_layers/core/keepout_filter.hpp"

PLUGINLIB_EXPORT_CLASS(costmap_layers::GradientLayer, costmap_layers::Layer)
PLUGINLIB_EXPORT_CLASS(costmap_layers::KeepoutFilter, costmap_layers::Layer)

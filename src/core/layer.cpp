#include "costmap_layers/core/layer.hpp"

#include "costmap_layers/core/layered_costmap.hpp"
#include "costmap_layers/core/param_reader.hpp"

namespace costmap_layers
{
void Layer::initialize(LayeredCostmap* parent, const std::string& name, std::shared_ptr<LayerContext> context)
{
  layered_costmap_ = parent;
  name_ = name;
  context_ = std::move(context);
  enabled_ = ParamReader(context_->params(), name_).getBool("enabled", true);
  onInitialize();
  initialized_ = true;
}

void Layer::reconfigure(const ParamValue& params)
{
  enabled_ = ParamReader(params, name_).getBool("enabled", true);
}

std::vector<ParamSpec> Layer::tunableParameters(const ParamValue& params) const
{
  return recordParameters(params, name_, [](const ParamReader& r) { r.getBool("enabled", true); });
}

const std::vector<Eigen::Vector2d>& Layer::getFootprint() const
{
  static const std::vector<Eigen::Vector2d> empty;
  return layered_costmap_ != nullptr ? layered_costmap_->getFootprint() : empty;
}
}  // namespace costmap_layers

#include "costmap_layers/core/observation_buffer.hpp"

#include <utility>

namespace costmap_layers
{
ObservationBuffer::ObservationBuffer(std::string name, const ObservationBufferConfig& config, uint64_t now_ns)
    : name_(std::move(name)), config_(config), last_updated_ns_(now_ns)
{
}

void ObservationBuffer::add(std::shared_ptr<const Observation> observation, uint64_t now_ns)
{
  if (!observation) return;
  std::lock_guard<std::mutex> lock(mutex_);
  observations_.push_back(std::move(observation));
  last_updated_ns_ = now_ns;
  purgeLocked(now_ns);
}

void ObservationBuffer::purgeLocked(uint64_t now_ns)
{
  if (observations_.empty()) return;
  if (config_.observation_persistence <= 0.0)
  {
    while (observations_.size() > 1)
      observations_.pop_front();
    return;
  }
  const double keep_ns = config_.observation_persistence * 1e9;
  while (!observations_.empty())
  {
    const uint64_t stamp = observations_.front()->stamp_ns;
    // A stamp in the future (clock skew) counts as fresh.
    const double age_ns = stamp >= now_ns ? 0.0 : static_cast<double>(now_ns - stamp);
    if (age_ns <= keep_ns) break;
    observations_.pop_front();
  }
}

void ObservationBuffer::getObservations(std::vector<std::shared_ptr<const Observation>>& out, uint64_t now_ns,
                                        double robot_x, double robot_y)
{
  std::lock_guard<std::mutex> lock(mutex_);
  purgeLocked(now_ns);
  if (config_.observation_keep_distance > 0.0)
  {
    const double max_d2 = config_.observation_keep_distance * config_.observation_keep_distance;
    for (auto it = observations_.begin(); it != observations_.end();)
    {
      const double dx = (*it)->origin_x - robot_x, dy = (*it)->origin_y - robot_y;
      if (dx * dx + dy * dy > max_d2)
        it = observations_.erase(it);
      else
        ++it;
    }
  }
  out.insert(out.end(), observations_.begin(), observations_.end());
}

bool ObservationBuffer::isCurrent(uint64_t now_ns) const
{
  if (config_.expected_update_rate <= 0.0) return true;
  return secondsSinceUpdate(now_ns) <= config_.expected_update_rate;
}

double ObservationBuffer::secondsSinceUpdate(uint64_t now_ns) const
{
  std::lock_guard<std::mutex> lock(mutex_);
  if (now_ns <= last_updated_ns_) return 0.0;
  return static_cast<double>(now_ns - last_updated_ns_) * 1e-9;
}

void ObservationBuffer::resetLastUpdated(uint64_t now_ns)
{
  std::lock_guard<std::mutex> lock(mutex_);
  last_updated_ns_ = now_ns;
}

void ObservationBuffer::clear()
{
  std::lock_guard<std::mutex> lock(mutex_);
  observations_.clear();
}

std::size_t ObservationBuffer::size() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return observations_.size();
}
}  // namespace costmap_layers

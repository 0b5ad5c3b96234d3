#include "costmap_layers/core/layers/observation_buffer.hpp"

#include <algorithm>
#include <utility>

namespace costmap_layers
{
ObservationBuffer::ObservationBuffer(std::string name, const ObservationBufferConfig& config, uint64_t now_ns)
    : name_(std::move(name)), config_(config), last_updated_ns_(now_ns)
{
  clock_.jumpedBack(now_ns);
}

void ObservationBuffer::noteTimeLocked(uint64_t now_ns) const
{
  const uint64_t before = clock_.latest();
  if (!clock_.jumpedBack(now_ns)) return;
  if (jump_)
  {
    jump_->to_ns = now_ns;
    jump_->dropped += observations_.size();
  }
  else
  {
    jump_ = ClockJump{before, now_ns, observations_.size()};
  }
  observations_.clear();
  last_updated_ns_ = now_ns;
}

std::shared_ptr<ObservationPool> ObservationPool::make()
{
  std::shared_ptr<ObservationPool> pool(new ObservationPool());
  pool->self_ = pool;
  return pool;
}

std::shared_ptr<Observation> ObservationPool::take()
{
  std::unique_ptr<Observation> o;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!free_.empty())
    {
      o = std::move(free_.back());
      free_.pop_back();
    }
  }
  if (o)
  {
    // As new, the capacity of its vectors kept.
    std::vector<Point3f> points = std::move(o->points), clear_only = std::move(o->clear_only);
    points.clear();
    clear_only.clear();
    *o = Observation{};
    o->points = std::move(points);
    o->clear_only = std::move(clear_only);
  }
  else
  {
    o = std::make_unique<Observation>();
  }
  std::weak_ptr<ObservationPool> pool = self_;
  return std::shared_ptr<Observation>(o.release(),
                                      [pool](Observation* released)
                                      {
                                        if (auto p = pool.lock())
                                          p->giveBack(released);
                                        else
                                          delete released;
                                      });
}

void ObservationPool::giveBack(Observation* observation)
{
  std::unique_ptr<Observation> o(observation);
  std::lock_guard<std::mutex> lock(mutex_);
  if (free_.size() < kMaxFree) free_.push_back(std::move(o));
}

bool olderThanPersistence(uint64_t stamp_ns, uint64_t now_ns, double observation_persistence)
{
  if (!(observation_persistence > 0.0)) return false;
  // Stamped a little ahead (within the tolerance) counts as age 0: it expires that much later.
  const double age_ns = stamp_ns >= now_ns ? 0.0 : static_cast<double>(now_ns - stamp_ns);
  return age_ns > observation_persistence * 1e9;
}

bool ObservationBuffer::add(std::shared_ptr<const Observation> observation, uint64_t now_ns)
{
  if (!observation) return false;
  std::lock_guard<std::mutex> lock(mutex_);
  noteTimeLocked(now_ns);
  if (isAheadOfNow(observation->stamp_ns, now_ns))
  {
    purgeLocked(now_ns);
    return false;
  }
  observations_.push_back(std::move(observation));
  last_updated_ns_ = now_ns;
  purgeLocked(now_ns);
  while (observations_.size() > kMaxObservations)
  {
    observations_.pop_front();
    ++dropped_;
  }
  return true;
}

void ObservationBuffer::purgeLocked(uint64_t now_ns)
{
  // Every entry is checked, not only the front ones: the buffer is in arrival order, and a reading can
  // arrive after a newer one.
  const bool keep_newest_only = config_.observation_persistence <= 0.0;
  auto stale = [&](const std::shared_ptr<const Observation>& o)
  {
    const uint64_t stamp = o->stamp_ns;
    if (isAheadOfNow(stamp, now_ns)) return true;  // from another time line, or a sender's bad clock
    return !keep_newest_only && olderThanPersistence(stamp, now_ns, config_.observation_persistence);
  };
  observations_.erase(std::remove_if(observations_.begin(), observations_.end(), stale), observations_.end());
  if (keep_newest_only)
  {
    while (observations_.size() > 1)
      observations_.pop_front();
  }
}

void ObservationBuffer::getObservations(std::vector<std::shared_ptr<const Observation>>& out, uint64_t now_ns,
                                        double robot_x, double robot_y)
{
  std::lock_guard<std::mutex> lock(mutex_);
  noteTimeLocked(now_ns);
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
  noteTimeLocked(now_ns);
  if (now_ns <= last_updated_ns_) return 0.0;  // a step back within the tolerance
  return static_cast<double>(now_ns - last_updated_ns_) * 1e-9;
}

void ObservationBuffer::resetLastUpdated(uint64_t now_ns)
{
  std::lock_guard<std::mutex> lock(mutex_);
  noteTimeLocked(now_ns);
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

std::optional<ObservationBuffer::ClockJump> ObservationBuffer::takeClockJump()
{
  std::lock_guard<std::mutex> lock(mutex_);
  std::optional<ClockJump> j;
  j.swap(jump_);
  return j;
}
std::size_t ObservationBuffer::takeDropped()
{
  std::lock_guard<std::mutex> lock(mutex_);
  return std::exchange(dropped_, 0);
}
}  // namespace costmap_layers

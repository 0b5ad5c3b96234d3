#include "costmap_layers/core/filters/speed_window.hpp"

namespace costmap_layers
{
void OdometrySpeedWindow::add(uint64_t received_ns, uint64_t stamp_ns, double linear_x)
{
  samples_.push_back({received_ns, stamp_ns, linear_x});
  while (samples_.size() > 1 &&
         (samples_.size() > kMaxSamples || samples_.front().received_ns + kWindowNs < received_ns))
    samples_.pop_front();
}

OdometrySpeedWindow::Mean OdometrySpeedWindow::mean() const
{
  Mean m;
  if (samples_.empty()) return m;
  m.newest_received_ns = samples_.back().received_ns;
  double sum = 0.0;
  for (const Sample& s : samples_)
    if (s.received_ns + kWindowNs >= m.newest_received_ns)
    {
      sum += s.linear_x;
      ++m.samples;
    }
  m.linear_x = sum / static_cast<double>(m.samples);
  return m;
}
}  // namespace costmap_layers

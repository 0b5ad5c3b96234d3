// What a layer can say about itself at a glance, ROS-free: a level, one line, and key/value facts
// (what it received and when, what it waits for). The ROS node turns each into one
// diagnostic_msgs/DiagnosticStatus on /diagnostics; a test or a tool can read it directly.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace costmap_layers
{
/// The levels of diagnostic_msgs/DiagnosticStatus, in the same order (OK < WARN < ERROR).
enum class StatusLevel : uint8_t
{
  Ok = 0,
  Warn = 1,
  Error = 2
};

struct LayerStatus
{
  StatusLevel level = StatusLevel::Ok;
  std::string message;  ///< one line: what is wrong, or what is in force
  std::vector<std::pair<std::string, std::string>> values;

  /// Adds a fact.
  void add(std::string key, std::string value) { values.emplace_back(std::move(key), std::move(value)); }
  /// Raises the level to at least `at_least`. The message of the worst problem wins; a problem as bad as
  /// the one already said is appended ("; ").
  void raise(StatusLevel at_least, const std::string& why);
  /// The value of a key ("" when absent).
  std::string value(const std::string& key) const;
};

/// "3.25 s ago" for an age in [s]; "never" for a negative age.
std::string describeAge(double seconds);
/// Seconds from then_ns to now_ns (0 when then_ns is later: a clock that jumped back).
double secondsBetween(uint64_t then_ns, uint64_t now_ns);
}  // namespace costmap_layers

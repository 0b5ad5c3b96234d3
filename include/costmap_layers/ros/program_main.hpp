// How every program of this package starts and stops, so that each says why it stopped.
//
// roscpp shuts the node down when the last NodeHandle that started it is destroyed, and its shutdown
// also shuts rosconsole down: a start-up error thrown while a program's NodeHandles unwind used to end
// the program with exit code 1 and no line anywhere (zone_server with a zone file that does not load).
// runProgram() starts the node itself, so that it lives until main returns, runs the program's body
// and turns any exception into one FATAL line, on stderr and on /rosout, and exit code 1.
#pragma once

#include <functional>
#include <string>

namespace costmap_layers_ros
{
/// ros::init(argc, argv, default_name, init_options), ros::start(), then body(); returns body's code.
/// An exception from body (a parameter, a file, a topic name roscpp refuses) is reported by
/// reportFatal() and the program returns 1.
int runProgram(int argc, char** argv, const std::string& default_name, const std::function<int()>& body,
               uint32_t init_options = 0);

/// Logs "<node>: <what> [<program>/startup]" once (<program>: runProgram's default_name, the stable key
/// whatever __name:= says; the node's name outside runProgram) at FATAL level, on stderr and on /rosout. /rosout only
/// delivers to a subscriber that is already connected (a program that fails in its first milliseconds
/// would lose the line), so it waits up to 2 s of wall time for rosout's subscription first, and a
/// moment after the line for it to leave. Returns 1, the code programs exit with.
int reportFatal(const std::string& what);
}  // namespace costmap_layers_ros

// The set-up lines of a run on stderr, so that a long set-up (a large grid, a
// Gmsh mesh at a small element size, the first factorisation's analysis) is
// not taken for a hang: a phase says what it does when it begins, and its size
// and time when it ends, on one line:
//   ipstep: loading scene ball_impact_3d ... 12,345 nodes, 61,234 elements in 3.2 s
// A phase's line appears once the phase has run `delay` seconds (a short one
// prints nothing); a negative delay turns the lines off.
//   SetupProgress progress("ipstep", 0.5);
//   progress.Begin("loading scene " + name);
//   ... LoadScene ...
//   progress.End(Thousands(scene.num_nodes()) + " nodes");
#pragma once

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace ipstep {

class SetupProgress {
 public:
  SetupProgress(std::string program, double delay_seconds);
  ~SetupProgress();
  SetupProgress(const SetupProgress&) = delete;
  SetupProgress& operator=(const SetupProgress&) = delete;

  // Starts a phase (ending the one before, without a result).
  void Begin(const std::string& what);
  // Ends the phase; its line, if shown, gets " <result> in <t> s".
  void End(const std::string& result);

 private:
  void Show();  // with mutex_ held
  void Watch();

  const std::string program_;
  const double delay_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::string phase_;    // empty: none running
  long generation_ = 0;  // phases begun
  std::chrono::steady_clock::time_point started_;
  bool shown_ = false;  // the running phase's line is on stderr
  bool stop_ = false;
  std::thread watcher_;  // with a positive delay: shows a phase still running after it
};

// 12345 as "12,345".
std::string Thousands(long long value);

}  // namespace ipstep

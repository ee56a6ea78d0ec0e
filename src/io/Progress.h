// Copyright (C) 2026 fsai developers
#pragma once

#include <chrono>
#include <string>

namespace fsai::io
{
/// Progress line with ETA for long loops, printed on rank 0 at most every
/// `interval_s` seconds (and at the end):
///   "[ 42%] step 420/1000  t = 4.200e-02 s  elapsed 1m12s  ETA 1m39s  ..."
class Progress
{
public:
  /// @param[in] label Loop name shown first
  /// @param[in] total Number of steps (or end time, if update() is given t)
  /// @param[in] start Where this process starts (a restarted run: its
  ///   checkpoint's step); the ETA extrapolates the rate since then
  Progress(std::string label, double total, double interval_s = 5.0,
           double start = 0.0);

  /// Report that `done` of `total` is complete; `extra` is appended
  /// (e.g. iteration counts). Returns true if a line was printed.
  bool update(double done, const std::string& extra = "");

  /// Format seconds as "1h02m", "3m07s" or "12.3s"
  static std::string format_duration(double seconds);

  /// Estimated remaining seconds after `done` of `total`, `elapsed`
  /// seconds after starting at `start`
  static double eta(double done, double total, double elapsed,
                    double start = 0.0);

private:
  std::string _label;
  double _total;
  double _interval;
  double _start_done;
  std::chrono::steady_clock::time_point _start, _last;
  bool _printed = false;
};
} // namespace fsai::io

// Copyright (C) 2026 fsai developers
#include "Progress.h"
#include "../common/log.h"
#include <cmath>

using clock_type = std::chrono::steady_clock;

//-----------------------------------------------------------------------------
fsai::io::Progress::Progress(std::string label, double total, double interval_s,
                             double start)
    : _label(std::move(label)), _total(total), _interval(interval_s),
      _start_done(start), _start(clock_type::now()), _last(_start)
{
}
//-----------------------------------------------------------------------------
double fsai::io::Progress::eta(double done, double total, double elapsed,
                               double start)
{
  if (done <= start)
    return NAN;
  return elapsed * (total - done) / (done - start);
}
//-----------------------------------------------------------------------------
std::string fsai::io::Progress::format_duration(double s)
{
  if (!std::isfinite(s))
    return "?";
  if (s >= 3600)
    return fmt::format("{}h{:02d}m", int(s / 3600),
                       int(std::fmod(s, 3600) / 60));
  if (s >= 60)
    return fmt::format("{}m{:02d}s", int(s / 60), int(std::fmod(s, 60)));
  return fmt::format("{:.1f}s", s);
}
//-----------------------------------------------------------------------------
bool fsai::io::Progress::update(double done, const std::string& extra)
{
  auto now = clock_type::now();
  const bool last = done >= _total;
  if (!last and _printed
      and std::chrono::duration<double>(now - _last).count() < _interval)
  {
    return false;
  }
  _last = now;
  _printed = true;
  const double elapsed = std::chrono::duration<double>(now - _start).count();
  log::info("[{:3.0f}%] {} {:.6g}/{:.6g}  elapsed {}  ETA {}{}{}",
            100.0 * done / _total, _label, done, _total,
            format_duration(elapsed),
            format_duration(eta(done, _total, elapsed, _start_done)),
            extra.empty() ? "" : "  ", extra);
  return true;
}
//-----------------------------------------------------------------------------

// Copyright (C) 2026 fsai developers
#include "RunLoop.h"
#include "../common/log.h"
#include "RunSummary.h"
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <stdexcept>

//-----------------------------------------------------------------------------
fsai::io::RunLoop::RunLoop(MPI_Comm comm, const std::string& dir,
                           const nlohmann::json& params,
                           const RestartOptions& options)
    : _comm(comm), _dir(dir), _options(options), _checkpoint(comm, dir, params)
{
  if (restarting())
  {
    _checkpoint.read();
    _unconverged = _checkpoint.meta().value("coupling_unconverged_steps", 0);
  }
}
//-----------------------------------------------------------------------------
double fsai::io::RunLoop::restart_time() const
{
  return restarting() ? _checkpoint.meta().at("t").get<double>()
                      : std::numeric_limits<double>::quiet_NaN();
}
//-----------------------------------------------------------------------------
std::size_t fsai::io::RunLoop::rows_kept() const
{
  return restarting() ? std::size_t(first_step()) : std::string::npos;
}
//-----------------------------------------------------------------------------
std::vector<std::vector<double>>
fsai::io::RunLoop::open_series(const std::string& path,
                               const std::vector<std::string>& columns,
                               RunSummary& summary)
{
  if (!restarting())
  {
    _series = std::make_unique<CsvWriter>(_comm, path, columns);
    return {};
  }
  _series = std::make_unique<CsvWriter>(_comm, path, columns,
                                        std::size_t(first_step()));
  fsai::log::info("restart from step {} (t = {:.6g} s) of {}", first_step(),
                  restart_time(), _dir);
  summary.set("restarted_from_step", first_step());
  return _series->kept_rows();
}
//-----------------------------------------------------------------------------
double fsai::io::RunLoop::run(long n, const RunHooks& hooks)
{
  const long k0 = first_step();
  Progress progress("step", double(n), 5.0, double(k0));
  const auto start = std::chrono::steady_clock::now();
  for (long k = k0 + 1; k <= n; ++k)
  {
    StepReport r;
    try
    {
      r = hooks.step(k);
    }
    catch (const std::exception& e)
    {
      // A failed step (coupling not converged with on_failure = error, an
      // inverted cell, a solver failure): the last good fields are written
      // for inspection before the error ends the run
      const std::string path = _dir + "/last_good.xdmf";
      const auto t_good
          = hooks.last_good ? hooks.last_good(path) : std::optional<double>{};
      if (!t_good)
        throw;
      throw std::runtime_error(fmt::format(
          "{} [step {} failed; the last good state (step {}, t = {:.6g} s) "
          "is in {}{}]",
          e.what(), k, k - 1, *t_good, path,
          _checkpoint.last_checkpoint_note()));
    }
    _unconverged += !r.converged;
    if (_options.checkpoint_due(k))
    {
      nlohmann::json scalars{{"coupling_unconverged_steps", _unconverged}};
      std::optional<RankState> fields;
      hooks.save(scalars, fields);
      _checkpoint.write(k, r.t, scalars, fields ? &*fields : nullptr);
    }
    _options.kill_if_requested(k);
    progress.update(double(k), hooks.progress ? hooks.progress() : "");
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
      .count();
}

// Copyright (C) 2026 fsai developers
#include "Checkpointer.h"
#include "../common/Parameters.h"
#include "../common/errors.h"
#include "../common/log.h"
#include "../common/timer.h"
#include "field_state.h"
#include <csignal>
#include <fmt/format.h>

void fsai::io::RestartOptions::bind(fsai::common::Parameters& p)
{
  p.add("checkpoint-every", checkpoint_every,
        "write DIR/checkpoint.json (FE scenes: and the fields, one file per "
        "rank) every N steps (0: never)");
  p.add("restart", restart,
        "continue the run in this folder from its checkpoint (same "
        "parameters, any number of ranks; --duration may be longer)");
  p.add("debug.kill_at_step", kill_at_step,
        "testing: kill this process with SIGKILL after step N");
}

void fsai::io::RestartOptions::validate() const
{
  fsai::require(checkpoint_every >= 0, "--checkpoint-every", ">= 0",
                checkpoint_every);
}

void fsai::io::RestartOptions::kill_if_requested(long k) const
{
  if (kill_at_step == k)
    std::raise(SIGKILL);
}

fsai::io::Checkpointer::Checkpointer(MPI_Comm comm, std::string dir,
                                     nlohmann::json parameters)
    : _comm(comm), _dir(std::move(dir)), _parameters(std::move(parameters))
{
}

void fsai::io::Checkpointer::read()
{
  _meta = read_checkpoint(_comm, _dir + "/checkpoint.json");
  const auto diff = compare_parameters(_meta.at("parameters"), _parameters);
  if (!diff.changed.empty())
  {
    throw InputError("restart: parameter " + diff.changed.front()
                     + " differs from the checkpointed run");
  }
  // A checkpoint written before a parameter existed ran as if it had its
  // default: the restart says which values it assumes rather than refusing
  // every checkpoint older than the code
  for (const auto& [path, value] : diff.added)
    log::warn("restart: parameter {} is not in the checkpoint (written by an "
              "older version); using {}",
              path, value.dump());
  for (const auto& path : diff.removed)
    log::warn("restart: the checkpoint's parameter {} is no longer known; "
              "ignored",
              path);
  _stem = _meta.value("fields", std::string());
  if (!_stem.empty())
    _fields = read_all_rank_states(_comm, _dir + "/" + _stem,
                                   _meta.at("mpi_size").get<int>());
}

void fsai::io::Checkpointer::write(long step, double t,
                                   const nlohmann::json& scalars,
                                   const RankState* fields)
{
  common::ScopedTimer timer("io: checkpoint");
  int size = 1;
  MPI_Comm_size(_comm, &size);
  nlohmann::json meta = scalars;
  meta["step"] = step;
  meta["t"] = t;
  meta["mpi_size"] = size;
  meta["parameters"] = _parameters;
  const std::string previous = _stem;
  if (fields)
  {
    _stem = fmt::format("checkpoint_{}", step);
    write_rank_state(_comm, _dir + "/" + _stem, *fields);
    meta["fields"] = _stem;
  }
  write_checkpoint(_comm, _dir + "/checkpoint.json", meta);
  if (!previous.empty() and previous != _stem)
    remove_rank_state(_comm, _dir + "/" + previous);
}

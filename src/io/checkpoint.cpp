// Copyright (C) 2026 fsai developers
#include "checkpoint.h"
#include "../common/errors.h"
#include <cstdio>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace
{
// Broadcast rank 0's error message; throw E on every rank if it is not empty
template <typename E>
void collective_error(MPI_Comm comm, std::string error)
{
  int n = int(error.size());
  MPI_Bcast(&n, 1, MPI_INT, 0, comm);
  if (n == 0)
    return;
  error.resize(n);
  MPI_Bcast(error.data(), n, MPI_CHAR, 0, comm);
  throw E(error);
}
} // namespace

void fsai::io::write_checkpoint(MPI_Comm comm, const std::string& path,
                                const nlohmann::json& data)
{
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string error;
  if (rank == 0)
  {
    const std::string tmp = path + ".tmp";
    const std::string text = data.dump(1);
    std::FILE* f = std::fopen(tmp.c_str(), "w");
    bool ok = f != nullptr;
    if (ok)
    {
      ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
      ok = std::fflush(f) == 0 and ok;
      ok = ::fsync(fileno(f)) == 0 and ok;
      ok = std::fclose(f) == 0 and ok;
    }
    if (!ok or std::rename(tmp.c_str(), path.c_str()) != 0)
    {
      std::remove(tmp.c_str());
      error = "cannot write the checkpoint '" + path
              + "' (disk full or not writable); the previous one is kept";
    }
  }
  collective_error<std::runtime_error>(comm, error);
}

nlohmann::json fsai::io::read_checkpoint(MPI_Comm comm, const std::string& path)
{
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string text, error;
  if (rank == 0)
  {
    std::ifstream in(path);
    if (!in)
      error = "restart: no checkpoint '" + path + "'";
    else
    {
      std::stringstream ss;
      ss << in.rdbuf();
      text = ss.str();
      if (!nlohmann::json::accept(text))
        error = "restart: checkpoint '" + path + "' is not valid JSON";
    }
  }
  collective_error<InputError>(comm, error);
  int n = int(text.size());
  MPI_Bcast(&n, 1, MPI_INT, 0, comm);
  text.resize(n);
  MPI_Bcast(text.data(), n, MPI_CHAR, 0, comm);
  return nlohmann::json::parse(text);
}

std::string fsai::io::first_changed_parameter(nlohmann::json saved,
                                              nlohmann::json current)
{
  for (auto* j : {&saved, &current})
    for (const char* key :
         {"output", "restart", "checkpoint-every", "duration", "debug"})
      j->erase(key);
  const auto diff = nlohmann::json::diff(saved, current);
  if (diff.empty())
    return "";
  return diff[0].value("path", std::string("?"));
}

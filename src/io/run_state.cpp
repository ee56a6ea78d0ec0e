// Copyright (C) 2026 fsai developers
#include "run_state.h"
#include "../common/errors.h"
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace
{
// Throw E on every rank if any rank has an error (the lowest rank's message)
template <typename E>
void any_rank_error(MPI_Comm comm, const std::string& error)
{
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const int mine = error.empty() ? size : rank;
  int first = size;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == size)
    return;
  int n = rank == first ? int(error.size()) : 0;
  MPI_Bcast(&n, 1, MPI_INT, first, comm);
  std::string msg = rank == first ? error : std::string(n, ' ');
  MPI_Bcast(msg.data(), n, MPI_CHAR, first, comm);
  throw E(msg);
}

std::string rank_file(MPI_Comm comm, const std::string& stem)
{
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  return stem + ".r" + std::to_string(rank) + ".bin";
}

// File layout: "fsai-state 1\n", the entry count, then per entry the
// name's length, the name, the array's length and the doubles (native
// byte order: a checkpoint is read back on the machine class it was
// written on)
constexpr char magic[] = "fsai-state 1\n";

// Write `path` through a temporary file: `body` writes it, then it is
// flushed, synced and renamed over `path`; false (and no temporary left)
// if any of that fails — `path` then still holds its previous content
template <typename F>
bool write_atomically(const std::string& path, F&& body)
{
  const std::string tmp = path + ".tmp";
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  bool ok = f != nullptr;
  if (ok)
  {
    ok = body(f);
    ok = std::fflush(f) == 0 and ok;
    ok = ::fsync(fileno(f)) == 0 and ok;
    ok = std::fclose(f) == 0 and ok;
  }
  if (!ok or std::rename(tmp.c_str(), path.c_str()) != 0)
  {
    std::remove(tmp.c_str());
    return false;
  }
  return true;
}
} // namespace

void fsai::io::write_rank_state(MPI_Comm comm, const std::string& stem,
                                const RankState& state)
{
  const std::string path = rank_file(comm, stem);
  const bool ok = write_atomically(
      path,
      [&](std::FILE* f)
      {
        bool good = true;
        auto put = [&](const void* data, std::size_t bytes)
        { good = good and std::fwrite(data, 1, bytes, f) == bytes; };
        put(magic, sizeof(magic) - 1);
        const std::uint64_t n = state.size();
        put(&n, sizeof(n));
        for (const auto& [name, v] : state)
        {
          const std::uint64_t len = name.size(), size = v.size();
          put(&len, sizeof(len));
          put(name.data(), len);
          put(&size, sizeof(size));
          put(v.data(), size * sizeof(double));
        }
        return good;
      });
  std::string error;
  if (!ok)
  {
    error = "cannot write the checkpoint state '" + path
            + "' (disk full or not writable); the previous checkpoint is kept";
  }
  any_rank_error<std::runtime_error>(comm, error);
}

fsai::io::RankState fsai::io::read_rank_state_file(MPI_Comm comm,
                                                   const std::string& path)
{
  RankState state;
  std::string error;
  std::ifstream in(path, std::ios::binary);
  auto get = [&](void* data, std::size_t bytes)
  { return bool(in.read(static_cast<char*>(data), std::streamsize(bytes))); };
  std::string head(sizeof(magic) - 1, ' ');
  std::uint64_t n = 0;
  if (!in)
    error = "restart: no checkpoint state '" + path + "'";
  else if (!get(head.data(), head.size()) or head != magic
           or !get(&n, sizeof(n)))
    error = "restart: '" + path + "' is not an fsai checkpoint state";
  for (std::uint64_t i = 0; error.empty() and i < n; ++i)
  {
    std::uint64_t len = 0, size = 0;
    std::string name;
    bool ok = get(&len, sizeof(len)) and len < 4096;
    if (ok)
    {
      name.resize(len);
      ok = get(name.data(), len) and get(&size, sizeof(size))
           and size < (std::uint64_t(1) << 40);
    }
    std::vector<double> v;
    if (ok)
    {
      v.resize(size);
      ok = get(v.data(), size * sizeof(double));
    }
    if (!ok)
      error = "restart: checkpoint state '" + path + "' is truncated";
    else
      state[name] = std::move(v);
  }
  any_rank_error<InputError>(comm, error);
  return state;
}

void fsai::io::remove_rank_state(MPI_Comm comm, const std::string& stem)
{
  std::remove(rank_file(comm, stem).c_str());
}

const std::vector<double>& fsai::io::state_entry(const RankState& state,
                                                 const std::string& name,
                                                 std::size_t size)
{
  auto it = state.find(name);
  if (it == state.end())
    throw InputError("restart: the checkpoint has no '" + name + "'");
  if (size != std::size_t(-1) and it->second.size() != size)
  {
    throw InputError("restart: checkpoint entry '" + name + "' has "
                     + std::to_string(it->second.size()) + " values, the run "
                     + std::to_string(size) + " (another mesh)");
  }
  return it->second;
}

void fsai::io::throw_if_any_rank(MPI_Comm comm, const std::string& error)
{
  any_rank_error<InputError>(comm, error);
}

void fsai::io::write_checkpoint(MPI_Comm comm, const std::string& path,
                                const nlohmann::json& data)
{
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string error;
  if (rank == 0)
  {
    const std::string text = data.dump(1);
    if (!write_atomically(path,
                          [&](std::FILE* f) {
                            return std::fwrite(text.data(), 1, text.size(), f)
                                   == text.size();
                          }))
    {
      error = "cannot write the checkpoint '" + path
              + "' (disk full or not writable); the previous one is kept";
    }
  }
  any_rank_error<std::runtime_error>(comm, error);
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
  any_rank_error<InputError>(comm, error);
  int n = int(text.size());
  MPI_Bcast(&n, 1, MPI_INT, 0, comm);
  text.resize(n);
  MPI_Bcast(text.data(), n, MPI_CHAR, 0, comm);
  return nlohmann::json::parse(text);
}

fsai::io::ParameterChanges fsai::io::compare_parameters(nlohmann::json saved,
                                                        nlohmann::json current)
{
  for (auto* j : {&saved, &current})
    for (const char* key : {"output", "restart", "checkpoint-every", "duration",
                            "write_every", "debug"})
      j->erase(key);
  ParameterChanges out;
  for (const auto& op : nlohmann::json::diff(saved, current))
  {
    const std::string path = op.value("path", std::string("?"));
    const std::string kind = op.value("op", std::string());
    if (kind == "add")
      out.added.push_back({path, op.value("value", nlohmann::json())});
    else if (kind == "remove")
      out.removed.push_back(path);
    else
      out.changed.push_back(path);
  }
  return out;
}

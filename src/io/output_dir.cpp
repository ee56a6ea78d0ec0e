// Copyright (C) 2026 fsai developers
#include "output_dir.h"
#include "../common/errors.h"
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

//-----------------------------------------------------------------------------
void fsai::io::prepare_output_dir(MPI_Comm comm, const std::string& dir)
{
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string error;
  if (rank == 0)
  {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec)
      error = ec.message();
    else
    {
      // Creating the folder can succeed on a read-only parent that exists;
      // probe with a file
      const fs::path probe = fs::path(dir) / ".fsai_write_test";
      std::ofstream f(probe);
      if (!f)
        error = "cannot create files";
      f.close();
      fs::remove(probe, ec);
    }
  }
  int failed = error.empty() ? 0 : 1;
  MPI_Bcast(&failed, 1, MPI_INT, 0, comm);
  if (failed)
  {
    throw InputError("output folder '" + dir + "' is not writable"
                     + (error.empty() ? "" : ": " + error));
  }
}
//-----------------------------------------------------------------------------
void fsai::io::ensure_parent_dir(const std::string& path)
{
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty())
  {
    std::error_code ec;
    fs::create_directories(parent, ec);
  }
}
//-----------------------------------------------------------------------------

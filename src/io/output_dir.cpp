// Copyright (C) 2026 fsai developers
#include "output_dir.h"
#include "../common/errors.h"
#include "../common/log.h"
#include <cstdlib>
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
//-----------------------------------------------------------------------------
void fsai::io::draw_chart(MPI_Comm comm, const std::string& script,
                          const std::string& dir)
{
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank != 0)
    return;
  const std::string cmd = std::string(FSAI_PYTHON) + " " + FSAI_SCRIPTS_DIR
                          + "/" + script + " " + dir + " > /dev/null 2>&1";
  if (std::system(cmd.c_str()) != 0)
    fsai::log::warn("could not draw the chart of {} ({})", dir, cmd);
}

// Copyright (C) 2026 fsai developers
#include "TimeSeriesWriter.h"
#include "../common/errors.h"
#include "../common/timer.h"
#include "output_dir.h"
#include "run_state.h"
#include <cmath>
#include <cstdio>
#include <dolfinx/io/XDMFFile.h>
#include <filesystem>
#include <hdf5.h>
#include <limits>
#include <pugixml.hpp>
#include <stdexcept>

//-----------------------------------------------------------------------------
fsai::io::TimeSeriesWriter::TimeSeriesWriter(const std::string& path,
                                             std::vector<Field> fields,
                                             double continue_after)
    : _path(path), _fields(std::move(fields))
{
  if (_fields.empty())
    throw std::runtime_error("TimeSeriesWriter '" + path + "': no fields");
  auto mesh = _fields.front()->function_space()->mesh();
  for (const Field& f : _fields)
  {
    if (f->function_space()->mesh() != mesh)
      throw std::runtime_error("TimeSeriesWriter '" + path
                               + "': fields live on different meshes");
  }
  if (!std::isnan(continue_after))
  {
    // A restart of a run that wrote no series (--write_every 0 then) starts
    // one at the restart; rank 0 decides, so that all ranks agree
    int rank = 0, exists = 0;
    MPI_Comm_rank(mesh->comm(), &rank);
    if (rank == 0)
      exists = std::filesystem::exists(path);
    MPI_Bcast(&exists, 1, MPI_INT, 0, mesh->comm());
    if (!exists)
      continue_after = std::numeric_limits<double>::quiet_NaN();
  }
  if (std::isnan(continue_after))
  {
    ensure_parent_dir(path);
    dolfinx::io::XDMFFile file(mesh->comm(), path, "w");
    file.write_mesh(*mesh);
  }
  else
    truncate_time_series(mesh->comm(), path, continue_after);
}
//-----------------------------------------------------------------------------
void fsai::io::TimeSeriesWriter::write(double t)
{
  common::ScopedTimer timer("io: xdmf");
  // Open, append, close: the HDF5 file is complete on disk after each step
  dolfinx::io::XDMFFile file(_fields.front()->function_space()->mesh()->comm(),
                             _path, "a");
  for (const Field& f : _fields)
    file.write_function(*f, t);
  file.close();
  ++_steps;
}
//-----------------------------------------------------------------------------
int fsai::io::truncate_time_series(MPI_Comm comm, const std::string& path,
                                   double t)
{
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string error;
  int removed = 0;
  if (rank == 0)
  {
    pugi::xml_document doc;
    std::vector<std::string> datasets;
    if (!doc.load_file(path.c_str()))
      error = "restart: cannot read the XDMF series '" + path + "'";
    else
    {
      // Temporal collections hold one Grid per written time; its DataItems
      // name their datasets as "file.h5:/Function/<name>/<time>"
      const double tol = 1e-9 * std::max(std::abs(t), 1e-300);
      for (auto col :
           doc.select_nodes("/Xdmf/Domain/Grid[@GridType='Collection']"))
      {
        std::vector<pugi::xml_node> late;
        for (auto grid : col.node().children("Grid"))
        {
          const double tg = grid.child("Time").attribute("Value").as_double();
          if (tg > t + tol)
            late.push_back(grid);
        }
        for (auto grid : late)
        {
          for (auto item : grid.select_nodes(".//DataItem"))
          {
            const std::string text = item.node().child_value();
            const auto colon = text.find(':');
            if (colon != std::string::npos)
              datasets.push_back(text.substr(colon + 1));
          }
          col.node().remove_child(grid);
          ++removed;
        }
      }
      const std::string tmp = path + ".tmp";
      if (!doc.save_file(tmp.c_str(), "  ")
          or std::rename(tmp.c_str(), path.c_str()) != 0)
        error = "restart: cannot rewrite the XDMF series '" + path + "'";
    }
    if (error.empty() and !datasets.empty())
    {
      // The datasets of the removed steps: a rewrite at the same time
      // would otherwise fail (HDF5 does not overwrite a dataset)
      const std::string h5 = path.substr(0, path.rfind('.')) + ".h5";
      const hid_t f = H5Fopen(h5.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
      if (f < 0)
        error = "restart: cannot open '" + h5 + "'";
      else
      {
        for (const auto& d : datasets)
          if (H5Lexists(f, d.c_str(), H5P_DEFAULT) > 0)
            H5Ldelete(f, d.c_str(), H5P_DEFAULT);
        H5Fclose(f);
      }
    }
  }
  MPI_Bcast(&removed, 1, MPI_INT, 0, comm);
  throw_if_any_rank(comm, error);
  return removed;
}
//-----------------------------------------------------------------------------

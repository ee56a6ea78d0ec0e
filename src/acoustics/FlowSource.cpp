// Copyright (C) 2026 fsai developers
#include "FlowSource.h"
#include <algorithm>
#include <cmath>
#include <common/errors.h>
#include <common/mpi_gather.h>
#include <dolfinx/mesh/Mesh.h>

using fsai::common::allgather;

//-----------------------------------------------------------------------------
fsai::acoustics::FlowSource::FlowSource(MPI_Comm comm,
                                        const dolfinx::fem::FunctionSpace& Vf,
                                        std::span<const double> X_ref,
                                        const dolfinx::fem::FunctionSpace& Va)
    : _comm(comm)
{
  const auto imap = Vf.dofmap()->index_map;
  fsai::require(Vf.dofmap()->index_map_bs() == 2
                    and Va.dofmap()->index_map_bs() == 2,
                "flow/acoustic velocity spaces", "2D vector spaces", 0);
  const std::int32_t n_owned = imap->size_local();

  // 1. Reference coordinates of all flow blocks (global order: ranks own
  // consecutive ranges) and the flow triangles as global block triplets
  std::vector<double> X_loc(2 * n_owned);
  for (std::int32_t i = 0; i < n_owned; ++i)
  {
    X_loc[2 * i] = X_ref[3 * i];
    X_loc[2 * i + 1] = X_ref[3 * i + 1];
  }
  const std::vector<double> X = allgather(comm, X_loc);
  const auto& topology = Vf.mesh()->topology();
  const std::int32_t n_cells = topology.index_map(2)->size_local();
  std::vector<std::int32_t> local(3 * n_cells);
  for (std::int32_t c = 0; c < n_cells; ++c)
  {
    auto d = Vf.dofmap()->cell_dofs(c);
    fsai::require(d.size() == 3, "flow velocity space", "P1 on triangles",
                  d.size());
    std::copy(d.begin(), d.end(), local.begin() + 3 * c);
  }
  std::vector<std::int64_t> global(local.size());
  imap->local_to_global(local, global);
  const std::vector<std::int64_t> tri = allgather(comm, global);
  const std::size_t n_tri = tri.size() / 3;

  // 2. Bucket grid over the triangles' bounding boxes
  double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
  for (std::size_t k = 0; k < X.size(); k += 2)
  {
    xmin = std::min(xmin, X[k]), xmax = std::max(xmax, X[k]);
    ymin = std::min(ymin, X[k + 1]), ymax = std::max(ymax, X[k + 1]);
  }
  const int nb = std::max(1, int(std::sqrt(double(n_tri)) / 2));
  const double bx = (xmax - xmin) / nb, by = (ymax - ymin) / nb;
  auto bucket = [&](double x, double y)
  {
    const int i = std::clamp(int((x - xmin) / bx), 0, nb - 1);
    const int j = std::clamp(int((y - ymin) / by), 0, nb - 1);
    return i * nb + j;
  };
  std::vector<std::vector<std::int32_t>> buckets(nb * nb);
  for (std::size_t t = 0; t < n_tri; ++t)
  {
    double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
    for (int v = 0; v < 3; ++v)
    {
      const double* p = &X[2 * tri[3 * t + v]];
      x0 = std::min(x0, p[0]), x1 = std::max(x1, p[0]);
      y0 = std::min(y0, p[1]), y1 = std::max(y1, p[1]);
    }
    const int i0 = std::clamp(int((x0 - xmin) / bx), 0, nb - 1),
              i1 = std::clamp(int((x1 - xmin) / bx), 0, nb - 1),
              j0 = std::clamp(int((y0 - ymin) / by), 0, nb - 1),
              j1 = std::clamp(int((y1 - ymin) / by), 0, nb - 1);
    for (int i = i0; i <= i1; ++i)
      for (int j = j0; j <= j1; ++j)
        buckets[i * nb + j].push_back(std::int32_t(t));
  }

  // 3. Each acoustic block: the triangle that contains it (barycentric
  // coordinates ≥ −tol: the two meshes discretise the fold's spline
  // differently, so a node on the acoustic fold boundary may lie a hair
  // outside the flow mesh; its weights are clipped and renormalised)
  const std::vector<double> Y = Va.tabulate_dof_coordinates(false);
  const std::int32_t n_a = Va.dofmap()->index_map->size_local()
                           + Va.dofmap()->index_map->num_ghosts();
  const double tol = 0.05;
  for (std::int32_t b = 0; b < n_a; ++b)
  {
    const double x = Y[3 * b], y = Y[3 * b + 1];
    if (x < xmin - bx or x > xmax + bx or y < ymin - by or y > ymax + by)
      continue;
    double best = -1e300;
    Node node{b, {}, {}};
    for (std::int32_t t : buckets[bucket(x, y)])
    {
      const double* a = &X[2 * tri[3 * t]];
      const double* p = &X[2 * tri[3 * t + 1]];
      const double* q = &X[2 * tri[3 * t + 2]];
      const double det
          = (p[0] - a[0]) * (q[1] - a[1]) - (q[0] - a[0]) * (p[1] - a[1]);
      const double l1
          = ((x - a[0]) * (q[1] - a[1]) - (q[0] - a[0]) * (y - a[1])) / det;
      const double l2
          = ((p[0] - a[0]) * (y - a[1]) - (x - a[0]) * (p[1] - a[1])) / det;
      const std::array<double, 3> l = {1 - l1 - l2, l1, l2};
      const double m = std::min({l[0], l[1], l[2]});
      if (m > best)
      {
        best = m;
        node.weight = l;
        for (int v = 0; v < 3; ++v)
          node.flow[v] = tri[3 * t + v];
      }
    }
    if (best < -tol)
      continue;
    double s = 0;
    for (auto& w : node.weight)
      s += (w = std::max(w, 0.0));
    for (auto& w : node.weight)
      w /= s;
    _nodes.push_back(node);
  }

  int size = 1;
  MPI_Comm_size(comm, &size);
  _counts.resize(size);
  _offsets.assign(size + 1, 0);
  const int n_val = 2 * n_owned;
  MPI_Allgather(&n_val, 1, MPI_INT, _counts.data(), 1, MPI_INT, comm);
  for (int r = 0; r < size; ++r)
    _offsets[r + 1] = _offsets[r] + _counts[r];
  _v_global.resize(_offsets[size]);
}
//-----------------------------------------------------------------------------
void fsai::acoustics::FlowSource::transfer(
    const dolfinx::fem::Function<double>& v_f,
    dolfinx::fem::Function<double>& v_a)
{
  const auto v = v_f.x()->array();
  int rank = 0;
  MPI_Comm_rank(_comm, &rank);
  MPI_Allgatherv(v.data(), _counts[rank], MPI_DOUBLE, _v_global.data(),
                 _counts.data(), _offsets.data(), MPI_DOUBLE, _comm);
  auto out = v_a.x()->mutable_array();
  std::fill(out.begin(), out.end(), 0.0);
  for (const Node& n : _nodes)
  {
    for (int c = 0; c < 2; ++c)
    {
      double s = 0;
      for (int v3 = 0; v3 < 3; ++v3)
        s += n.weight[v3] * _v_global[2 * n.flow[v3] + c];
      out[2 * n.block + c] = s;
    }
  }
}

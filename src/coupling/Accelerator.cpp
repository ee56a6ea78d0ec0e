// Copyright (C) 2026 fsai developers
#include "Accelerator.h"
#include "../common/Parameters.h"
#include "../common/errors.h"
#include <cmath>
#include <limits>
#include <numeric>

//-----------------------------------------------------------------------------
void fsai::coupling::AcceleratorParameters::bind(fsai::common::Parameters& p)
{
  p.add_choice("coupling.method", method, {"constant", "aitken", "iqn-ils"},
               "coupling accelerator");
  p.add("coupling.omega", omega,
        "constant relaxation factor; first factor of aitken and iqn-ils");
  p.add("coupling.reuse", reuse, "iqn-ils: past time steps reused");
  p.add("coupling.filter", filter, "iqn-ils: QR1 filter epsilon");
}
//-----------------------------------------------------------------------------
void fsai::coupling::AcceleratorParameters::validate() const
{
  fsai::require(method == "constant" or method == "aitken"
                    or method == "iqn-ils",
                "--coupling.method", "constant, aitken or iqn-ils", method);
  fsai::require(omega > 0 and omega <= 2, "--coupling.omega", "in (0, 2]",
                omega);
  fsai::require(reuse >= 0 and reuse <= 100, "--coupling.reuse", "in [0, 100]",
                reuse);
  fsai::require(filter >= 0 and filter < 1, "--coupling.filter", "in [0, 1)",
                filter);
}
//-----------------------------------------------------------------------------
double fsai::coupling::norm(MPI_Comm comm, std::span<const double> v)
{
  double s = std::inner_product(v.begin(), v.end(), v.begin(), 0.0);
  MPI_Allreduce(MPI_IN_PLACE, &s, 1, MPI_DOUBLE, MPI_SUM, comm);
  return std::sqrt(s);
}
//-----------------------------------------------------------------------------
namespace
{
using vec = std::vector<double>;

double dot(MPI_Comm comm, std::span<const double> a, std::span<const double> b)
{
  double s = std::inner_product(a.begin(), a.end(), b.begin(), 0.0);
  MPI_Allreduce(MPI_IN_PLACE, &s, 1, MPI_DOUBLE, MPI_SUM, comm);
  return s;
}

vec residual(std::span<const double> x, std::span<const double> Hx)
{
  vec r(x.size());
  for (std::size_t i = 0; i < x.size(); ++i)
    r[i] = Hx[i] - x[i];
  return r;
}

class Constant : public fsai::coupling::Accelerator
{
public:
  explicit Constant(double omega) : _omega(omega) {}
  void new_step() override {}
  void update(std::span<const double> x, std::span<const double> Hx,
              std::span<double> x_next) override
  {
    for (std::size_t i = 0; i < x.size(); ++i)
      x_next[i] = x[i] + _omega * (Hx[i] - x[i]);
  }
  double last_omega() const override { return _omega; }

private:
  double _omega;
};

class Aitken : public fsai::coupling::Accelerator
{
public:
  Aitken(MPI_Comm comm, double omega0) : _comm(comm), _omega0(omega0) {}
  void new_step() override
  {
    _r_prev.clear();
    _have_prev = false;
  }
  void update(std::span<const double> x, std::span<const double> Hx,
              std::span<double> x_next) override
  {
    vec r = residual(x, Hx);
    // A flag, not _r_prev.empty(): ranks without interface unknowns must
    // join the same collective dots
    if (!_have_prev)
      _omega = _omega0;
    else
    {
      vec dr(r.size());
      for (std::size_t i = 0; i < r.size(); ++i)
        dr[i] = r[i] - _r_prev[i];
      const double dd = dot(_comm, dr, dr);
      if (dd > 0)
        _omega = -_omega * dot(_comm, _r_prev, dr) / dd;
    }
    for (std::size_t i = 0; i < x.size(); ++i)
      x_next[i] = x[i] + _omega * r[i];
    _r_prev = std::move(r);
    _have_prev = true;
  }
  double last_omega() const override { return _omega; }

private:
  MPI_Comm _comm;
  double _omega0, _omega = 0;
  vec _r_prev;
  bool _have_prev = false;
};

class IQNILS : public fsai::coupling::Accelerator
{
public:
  IQNILS(MPI_Comm comm, const fsai::coupling::AcceleratorParameters& p)
      : _comm(comm), _p(p)
  {
  }
  void new_step() override
  {
    if (!_step.empty())
      _history.push_front(std::move(_step));
    _step.clear();
    while (int(_history.size()) > _p.reuse)
      _history.pop_back();
    _r_prev.clear();
    _have_prev = false;
  }
  void update(std::span<const double> x, std::span<const double> Hx,
              std::span<double> x_next) override
  {
    vec r = residual(x, Hx);
    // A flag, not _r_prev.empty(): a rank without interface unknowns must
    // still build the same columns (every norm and dot is collective)
    if (_have_prev)
    {
      Column c{vec(r.size()), vec(r.size())};
      for (std::size_t i = 0; i < r.size(); ++i)
      {
        c.dr[i] = r[i] - _r_prev[i];
        c.dx[i] = Hx[i] - _Hx_prev[i];
      }
      _step.insert(_step.begin(), std::move(c)); // newest first
    }
    _r_prev = r;
    _Hx_prev.assign(Hx.begin(), Hx.end());
    _have_prev = true;

    // Columns: this step's, then the reused steps', newest first
    std::vector<const Column*> cols;
    for (auto& c : _step)
      cols.push_back(&c);
    for (auto& s : _history)
      for (auto& c : s)
        cols.push_back(&c);

    // QR of V by modified Gram–Schmidt, dropping (nearly) dependent
    // columns (QR1 filter)
    std::vector<vec> Q;
    std::vector<std::vector<double>> R; // R[j] = column j of R (size j+1)
    std::vector<const Column*> kept;
    for (const Column* c : cols)
    {
      vec v = c->dr;
      const double n0 = fsai::coupling::norm(_comm, v);
      std::vector<double> rj;
      for (auto& q : Q)
      {
        const double h = dot(_comm, q, v);
        for (std::size_t i = 0; i < v.size(); ++i)
          v[i] -= h * q[i];
        rj.push_back(h);
      }
      const double n = fsai::coupling::norm(_comm, v);
      if (n0 == 0 or n < _p.filter * n0)
        continue;
      for (double& vi : v)
        vi /= n;
      rj.push_back(n);
      Q.push_back(std::move(v));
      R.push_back(std::move(rj));
      kept.push_back(c);
    }

    if (kept.empty())
    {
      _omega = _p.omega;
      for (std::size_t i = 0; i < x.size(); ++i)
        x_next[i] = x[i] + _p.omega * r[i];
      return;
    }
    // R c = −Qᵀ r, back substitution
    const std::size_t m = kept.size();
    std::vector<double> c(m);
    for (std::size_t j = 0; j < m; ++j)
      c[j] = -dot(_comm, Q[j], r);
    for (std::size_t j = m; j-- > 0;)
    {
      for (std::size_t k = j + 1; k < m; ++k)
        c[j] -= R[k][j] * c[k];
      c[j] /= R[j][j];
    }
    for (std::size_t i = 0; i < x.size(); ++i)
    {
      double w = 0;
      for (std::size_t j = 0; j < m; ++j)
        w += kept[j]->dx[i] * c[j];
      x_next[i] = Hx[i] + w;
    }
    _omega = std::numeric_limits<double>::quiet_NaN();
  }
  double last_omega() const override { return _omega; }
  void clear_history() override
  {
    _step.clear();
    _history.clear();
  }
  // The columns of the last step (moved into the reuse history by the next
  // new_step()) and of the reused steps: "iqn.counts" = columns per step
  // (last step first), "iqn.dr"/"iqn.dx" the columns one after the other
  void save(fsai::io::RankState& state,
            const std::string& prefix) const override
  {
    std::vector<double> counts{double(_step.size())}, dr, dx;
    auto add = [&](const std::vector<Column>& step)
    {
      for (const Column& c : step)
      {
        dr.insert(dr.end(), c.dr.begin(), c.dr.end());
        dx.insert(dx.end(), c.dx.begin(), c.dx.end());
      }
    };
    add(_step);
    for (const auto& s : _history)
    {
      counts.push_back(double(s.size()));
      add(s);
    }
    state[prefix + "iqn.counts"] = counts;
    state[prefix + "iqn.dr"] = dr;
    state[prefix + "iqn.dx"] = dx;
  }
  void load(const fsai::io::RankState& state,
            const std::string& prefix) override
  {
    const auto& counts = fsai::io::state_entry(state, prefix + "iqn.counts");
    const auto& dr = fsai::io::state_entry(state, prefix + "iqn.dr");
    const auto& dx = fsai::io::state_entry(state, prefix + "iqn.dx");
    double ncols = 0;
    for (double c : counts)
      ncols += c;
    if (counts.empty() or dr.size() != dx.size()
        or (ncols > 0 and dr.size() % std::size_t(ncols) != 0))
      throw fsai::InputError("restart: inconsistent IQN-ILS history");
    const std::size_t n = ncols > 0 ? dr.size() / std::size_t(ncols) : 0;
    std::size_t at = 0;
    auto take = [&](double count)
    {
      std::vector<Column> step;
      for (int j = 0; j < int(count); ++j, at += n)
        step.push_back({vec(dr.begin() + at, dr.begin() + at + n),
                        vec(dx.begin() + at, dx.begin() + at + n)});
      return step;
    };
    _step = take(counts[0]);
    _history.clear();
    for (std::size_t k = 1; k < counts.size(); ++k)
      _history.push_back(take(counts[k]));
  }

private:
  struct Column
  {
    vec dr, dx;
  };
  MPI_Comm _comm;
  fsai::coupling::AcceleratorParameters _p;
  std::vector<Column> _step;
  std::deque<std::vector<Column>> _history;
  vec _r_prev, _Hx_prev;
  bool _have_prev = false;
  double _omega = 0;
};
} // namespace
//-----------------------------------------------------------------------------
std::unique_ptr<fsai::coupling::Accelerator>
fsai::coupling::make_accelerator(MPI_Comm comm, const AcceleratorParameters& p)
{
  p.validate();
  if (p.method == "constant")
    return std::make_unique<Constant>(p.omega);
  if (p.method == "aitken")
    return std::make_unique<Aitken>(comm, p.omega);
  return std::make_unique<IQNILS>(comm, p);
}

// Copyright (C) 2026 fsai developers
#pragma once

#include <fmt/format.h>
#include <stdexcept>
#include <string>

namespace fsai
{
/// Bad input (command line, config file, parameter out of range, unreadable
/// data file). Thrown identically on every rank, because every rank reads the
/// same input; `run_main` prints it once and exits with status 2.
class InputError : public std::runtime_error
{
public:
  explicit InputError(const std::string& what) : std::runtime_error(what) {}
};

/// `--help` was requested: usage was printed, exit with status 0
class HelpRequested : public std::exception
{
};

/// Throw an InputError "<name>: must be <what> (got <value>)" unless `ok`
template <typename T>
void require(bool ok, const std::string& name, const std::string& what,
             const T& value)
{
  if (!ok)
  {
    throw InputError(fmt::format("{}: must be {} (got {})", name, what, value));
  }
}

/// Require value > 0
inline void require_positive(const std::string& name, double value)
{
  require(value > 0.0, name, "> 0", value);
}

/// Require lo <= value <= hi
inline void require_range(const std::string& name, double value, double lo,
                          double hi)
{
  require(value >= lo and value <= hi, name, fmt::format("in [{}, {}]", lo, hi),
          value);
}
} // namespace fsai

// Copyright (C) 2026 fsai developers
// Runtime selection of an FFCx-generated object by (tdim, degree).
//
// Every forms/<name>.py is compiled once per cell type and degree; the
// generated header fsai_forms/<name>.h (cmake/ffcx_dispatch.py) exposes one
// accessor per form, e.g. `fsai::forms::poisson::a(tdim, degree)`, built on
// `select` below, so solver code is written once for 2D and 3D.
#pragma once

#include <initializer_list>
#include <stdexcept>
#include <string>

namespace fsai::forms
{
/// One compiled variant of a generated object
template <typename T>
struct Variant
{
  int tdim;
  int degree;
  T object;
};

/// Pick the variant compiled for (tdim, degree)
/// @throws std::runtime_error naming the form file and the object when that
/// variant was not compiled
template <typename T>
T select(const char* file, const char* name, int tdim, int degree,
         std::initializer_list<Variant<T>> variants)
{
  std::string available;
  for (const Variant<T>& v : variants)
  {
    if (v.tdim == tdim and v.degree == degree)
      return v.object;
    available += " (tdim " + std::to_string(v.tdim) + ", P"
                 + std::to_string(v.degree) + ")";
  }
  throw std::runtime_error(
      "forms/" + std::string(file) + ".py: '" + std::string(name)
      + "' not compiled for tdim " + std::to_string(tdim) + ", P"
      + std::to_string(degree) + "; available:" + available);
}
} // namespace fsai::forms

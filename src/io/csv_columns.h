// Copyright (C) 2026 fsai developers
#pragma once

#include <string>
#include <vector>

namespace fsai::io
{
/// The named columns of a CSV table with a header line (e.g. a run's
/// series.csv), one vector per name in the order asked. Throws InputError
/// naming the file when it cannot be read, a column is missing, or a field
/// is not a number.
std::vector<std::vector<double>>
read_csv_columns(const std::string& path,
                 const std::vector<std::string>& names);
} // namespace fsai::io

// Copyright (C) 2026 fsai developers
#include "Parameters.h"
#include "Runtime.h"
#include "errors.h"
#include "log.h"
#include <cstdio>
#include <filesystem>
#include <regex>
#include <sstream>
#include <toml.hpp>

namespace
{
/// Collapse a multi-line library message (toml11 draws source excerpts) into
/// one line
std::string one_line(const std::string& text)
{
  std::istringstream in(text);
  std::string line, out;
  while (std::getline(in, line))
  {
    auto b = line.find_first_not_of(" \t|");
    if (b == std::string::npos)
      continue;
    line = line.substr(b);
    if (line.rfind("[error] ", 0) == 0)
      line = line.substr(8);
    out += (out.empty() ? "" : " ") + line;
  }
  return out;
}

/// Text form of a TOML scalar, as it would be typed on the command line
std::string scalar_text(const toml::value& v, const std::string& where)
{
  switch (v.type())
  {
  case toml::value_t::boolean:
    return v.as_boolean() ? "true" : "false";
  case toml::value_t::integer:
    return std::to_string(v.as_integer());
  case toml::value_t::floating:
  {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%.17g", v.as_floating());
    return buf;
  }
  case toml::value_t::string:
    return v.as_string().str;
  default:
    throw fsai::InputError(where + ": unsupported value type");
  }
}

/// Convert tokens into T with CLI11's own conversion (the same rules as on
/// the command line)
template <typename T>
bool convert(const std::vector<std::string>& tokens, T& value)
{
  if constexpr (std::is_same_v<T, std::vector<double>>)
  {
    std::vector<double> out(tokens.size());
    for (std::size_t i = 0; i < tokens.size(); ++i)
      if (!CLI::detail::lexical_cast(tokens[i], out[i]))
        return false;
    value = out;
    return true;
  }
  else
  {
    if (tokens.size() != 1)
      return false;
    if constexpr (std::is_same_v<T, std::string>)
    {
      value = tokens[0];
      return true;
    }
    else
      return CLI::detail::lexical_cast(tokens[0], value);
  }
}
} // namespace

//-----------------------------------------------------------------------------
fsai::common::Parameters::Parameters(const std::string& program,
                                     const std::string& description)
    : _app(description, program)
{
  _app.add_option("--config", _config_file,
                  "TOML file with parameters ([section] key = value); "
                  "command-line values take precedence")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  _app.get_formatter()->column_width(36);
  _app.footer("Parameters can also be set in the --config file as "
              "[section] key = value.\nPETSc options for the solvers "
              "(e.g. -poisson_ksp_type gmres -poisson_ksp_monitor) pass "
              "through and override the code's defaults.");
}
//-----------------------------------------------------------------------------
fsai::common::Parameters::~Parameters() = default;
//-----------------------------------------------------------------------------
void fsai::common::Parameters::bind(
    const std::string& key, CLI::Option* option,
    std::function<bool(const std::vector<std::string>&)> assign,
    std::function<nlohmann::json()> to_json)
{
  for (const Entry& e : _entries)
    if (e.key == key)
      throw std::logic_error("Parameter '" + key + "' bound twice");
  _entries.push_back({key, option, std::move(assign), std::move(to_json)});
}
//-----------------------------------------------------------------------------
template <typename T>
void fsai::common::Parameters::add(const std::string& key, T& value,
                                   const std::string& help)
{
  CLI::Option* opt;
  if constexpr (std::is_same_v<T, bool>)
    opt = _app.add_flag("--" + key, value, help);
  else
    opt = _app.add_option("--" + key, value, help)->capture_default_str();
  if constexpr (std::is_same_v<T, std::vector<double>>)
    opt->delimiter(',');
  else
    opt->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  bind(
      key, opt,
      [&value](const std::vector<std::string>& t) { return convert(t, value); },
      [&value]() { return nlohmann::json(value); });
}
//-----------------------------------------------------------------------------
void fsai::common::Parameters::add_choice(
    const std::string& key, std::string& value,
    const std::vector<std::string>& choices, const std::string& help)
{
  CLI::Option* opt = _app.add_option("--" + key, value, help)
                         ->capture_default_str()
                         ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast)
                         ->check(CLI::IsMember(choices));
  bind(
      key, opt,
      [&value, choices](const std::vector<std::string>& t)
      {
        if (t.size() != 1
            or std::find(choices.begin(), choices.end(), t[0]) == choices.end())
        {
          return false;
        }
        value = t[0];
        return true;
      },
      [&value]() { return nlohmann::json(value); });
}
//-----------------------------------------------------------------------------
void fsai::common::Parameters::parse(const std::vector<std::string>& args)
{
  // CLI11 takes the arguments in reverse order
  std::vector<std::string> rev(args.rbegin(), args.rend());
  try
  {
    _app.parse(rev);
  }
  catch (const CLI::CallForHelp&)
  {
    if (log::rank() == 0)
      std::cout << _app.help() << std::flush;
    throw HelpRequested();
  }
  catch (const CLI::ParseError& e)
  {
    throw InputError(one_line(e.what()) + " (see --help)");
  }
  start_deferred_libraries();

  if (!_config_file.empty())
    apply_toml(_config_file);
}
//-----------------------------------------------------------------------------
void fsai::common::Parameters::apply_toml(const std::string& path)
{
  if (!std::filesystem::is_regular_file(path))
    throw InputError("config file '" + path + "' not found");

  toml::value data;
  try
  {
    data = toml::parse(path);
  }
  catch (const std::exception& e)
  {
    throw InputError("config file '" + path + "': " + one_line(e.what()));
  }

  // Walk nested tables; leaves are "a.b.key"
  std::function<void(const toml::value&, const std::string&)> walk;
  walk = [&](const toml::value& table, const std::string& prefix)
  {
    for (const auto& [k, v] : table.as_table())
    {
      const std::string key = prefix.empty() ? k : prefix + "." + k;
      const std::string where = path + ": " + key;
      if (key.rfind("petsc.", 0) == 0)
      {
        // PETSc options: defaults that the command line still overrides
        set_option_default(key.substr(6), scalar_text(v, where));
        continue;
      }
      if (v.is_table())
      {
        walk(v, key);
        continue;
      }
      const Entry* it = find(key);
      if (!it)
        throw InputError(where + ": unknown parameter (see --help)");
      if (it->option->count() > 0)
        continue; // The command line wins

      std::vector<std::string> tokens;
      if (v.is_array())
      {
        for (const toml::value& x : v.as_array())
          tokens.push_back(scalar_text(x, where));
      }
      else
        tokens.push_back(scalar_text(v, where));
      if (!it->assign(tokens))
      {
        throw InputError(where + ": invalid value '" + one_line(toml::format(v))
                         + "'");
      }
      _from_toml.insert(key);
    }
  };
  walk(data, "");
}
//-----------------------------------------------------------------------------
const fsai::common::Parameters::Entry*
fsai::common::Parameters::find(const std::string& key) const
{
  auto it = std::find_if(_entries.begin(), _entries.end(),
                         [&key](const Entry& e) { return e.key == key; });
  return it == _entries.end() ? nullptr : &*it;
}
//-----------------------------------------------------------------------------
bool fsai::common::Parameters::given(const std::string& key) const
{
  const Entry* it = find(key);
  if (!it)
    throw std::logic_error("Parameters::given: no parameter '" + key + "'");
  return it->option->count() > 0 or _from_toml.count(key) > 0;
}
//-----------------------------------------------------------------------------
void fsai::common::Parameters::preset(const std::string& key,
                                      const std::string& text) const
{
  if (given(key)) // (throws for an unknown key)
    return;
  if (!find(key)->assign({text}))
    throw std::logic_error("Parameters::preset: '" + text
                           + "' is not a value of '" + key + "'");
}
//-----------------------------------------------------------------------------
nlohmann::json fsai::common::Parameters::to_json() const
{
  nlohmann::json out = nlohmann::json::object();
  for (const Entry& e : _entries)
    out[nlohmann::json::json_pointer(
        "/" + std::regex_replace(e.key, std::regex("\\."), "/"))]
        = e.to_json();
  return out;
}
//-----------------------------------------------------------------------------
void fsai::common::Parameters::print() const
{
  log::info("Parameters in effect:");
  for (const Entry& e : _entries)
    log::info("  {:<28} = {}", e.key, e.to_json().dump());
}
//-----------------------------------------------------------------------------
// Explicit instantiations: the supported parameter types
template void fsai::common::Parameters::add(const std::string&, bool&,
                                            const std::string&);
template void fsai::common::Parameters::add(const std::string&, int&,
                                            const std::string&);
template void fsai::common::Parameters::add(const std::string&, double&,
                                            const std::string&);
template void fsai::common::Parameters::add(const std::string&, std::string&,
                                            const std::string&);
template void fsai::common::Parameters::add(const std::string&,
                                            std::vector<double>&,
                                            const std::string&);
//-----------------------------------------------------------------------------

// Copyright (C) 2026 fsai developers
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

namespace fsai::common
{
/// Typed run-time parameters: each module keeps its values in a plain
/// struct with defaults and binds the members here under "section.key"
/// (`FluidParameters::bind(Parameters&)`, say). Values then come from, in
/// increasing precedence:
///   1. the struct's defaults,
///   2. the TOML file given by `--config FILE` ([section] key = value),
///   3. the command line (`--section.key value`).
/// A TOML table [petsc] holds PETSc options (without the dash) that become
/// defaults which PETSc options on the command line still override.
///
/// Unknown keys (command line or TOML), wrong types and unreadable files
/// raise InputError with a one-line message.
class Parameters
{
public:
  /// @param[in] program Program name shown in usage
  /// @param[in] description One-line description for --help
  Parameters(const std::string& program, const std::string& description);
  ~Parameters();

  /// Bind a value; `key` is "section.key" (or "key" for program-level
  /// values such as "output"). Supported: bool, int, double, std::string,
  /// std::vector<double>.
  template <typename T>
  void add(const std::string& key, T& value, const std::string& help);

  /// Bind a value that must be one of `choices`
  void add_choice(const std::string& key, std::string& value,
                  const std::vector<std::string>& choices,
                  const std::string& help);

  /// Parse the application arguments (Runtime::app_args()) and the config
  /// file. Throws HelpRequested after printing usage for -h/--help.
  void parse(const std::vector<std::string>& args);

  /// Whether `key` was given on the command line or in the config file
  /// (a scene may then choose its own default for it)
  bool given(const std::string& key) const;

  /// `value`, bound under `key`, set to `preset` unless the key was given:
  /// a scene's own default for an option shared with other scenes
  template <typename T, typename U>
  void set_unless_given(const std::string& key, T& value, const U& preset) const
  {
    if (!given(key))
      value = preset;
  }

  /// The value bound under `key` set from `text`, as it would be typed on
  /// the command line, unless the key was given: a scene's presets kept as
  /// one table of text that its --help can print as well
  void preset(const std::string& key, const std::string& text) const;

  /// Path given by --config ("" if none)
  const std::string& config_file() const { return _config_file; }

  /// Parameters in effect, nested by section, for the run summary
  nlohmann::json to_json() const;

  /// Print the parameters in effect (rank 0)
  void print() const;

private:
  struct Entry
  {
    std::string key;
    CLI::Option* option;
    /// Assign from text tokens (a TOML scalar is one token, an array one
    /// per element); false if they do not convert
    std::function<bool(const std::vector<std::string>&)> assign;
    std::function<nlohmann::json()> to_json;
  };

  void bind(const std::string& key, CLI::Option* option,
            std::function<bool(const std::vector<std::string>&)> assign,
            std::function<nlohmann::json()> to_json);
  void apply_toml(const std::string& path);
  /// The entry bound under `key` (nullptr if none)
  const Entry* find(const std::string& key) const;

  CLI::App _app;
  std::string _config_file;
  std::vector<Entry> _entries;
  std::set<std::string> _from_toml; ///< keys the config file assigned
};
} // namespace fsai::common

// Copyright (C) 2026 fsai developers
// Parameters: defaults < TOML < command line; clear errors for bad input
#include "catch.h"
#include <common/Parameters.h>
#include <common/Runtime.h>
#include <common/errors.h>
#include <fstream>
#include <petscsys.h>

namespace
{
struct Demo
{
  double h = 0.1;
  int n = 4;
  bool flag = false;
  std::string model = "planar";
  std::vector<double> xs = {1.0, 2.0};

  void bind(fsai::common::Parameters& p)
  {
    p.add("mesh.h", h, "mesh size");
    p.add("mesh.n", n, "count");
    p.add("run.flag", flag, "a flag");
    p.add_choice("run.model", model, {"planar", "axisym"}, "model");
    p.add("run.xs", xs, "list");
  }
};

/// Write `text` to a file `name` in a scratch folder (per rank)
std::string write_file(const fsai::test::TempDir& dir, const std::string& name,
                       const std::string& text)
{
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  std::string path = dir / (std::to_string(rank) + "_" + name);
  std::ofstream(path) << text;
  return path;
}

/// Parse args into a fresh Demo
Demo parse(const std::vector<std::string>& args)
{
  Demo d;
  fsai::common::Parameters p("test", "test");
  d.bind(p);
  p.parse(args);
  return d;
}
} // namespace

TEST_CASE("Parameters keep defaults without input", "[common]")
{
  Demo d = parse({});
  CHECK(d.h == 0.1);
  CHECK(d.n == 4);
  CHECK(!d.flag);
  CHECK(d.model == "planar");
}

TEST_CASE("Command line overrides TOML, TOML overrides defaults", "[common]")
{
  fsai::test::TempDir dir;
  std::string cfg = write_file(dir, "a.toml",
                               "[mesh]\nh = 0.5\nn = 7\n"
                               "[run]\nmodel = \"axisym\"\n"
                               "xs = [3, 4.5]\nflag = true\n");
  Demo d = parse({"--config", cfg, "--mesh.h", "0.25"});
  CHECK(d.h == 0.25);         // Command line
  CHECK(d.n == 7);            // TOML
  CHECK(d.model == "axisym"); // TOML
  CHECK(d.flag);
  REQUIRE(d.xs.size() == 2);
  CHECK(d.xs[0] == 3.0);
  CHECK(d.xs[1] == 4.5);

  // An integer in TOML is accepted for a floating-point parameter
  std::string cfg2 = write_file(dir, "b.toml", "mesh.h = 2\n");
  CHECK(parse({"--config", cfg2}).h == 2.0);
}

TEST_CASE("Parameters tell which keys were given", "[common]")
{
  fsai::test::TempDir dir;
  std::string cfg = write_file(dir, "g.toml", "[mesh]\nn = 4\n");
  Demo d;
  fsai::common::Parameters p("test", "test");
  d.bind(p);
  p.parse({"--config", cfg, "--run.model", "planar"});
  CHECK(p.given("mesh.n"));    // TOML, even with the default's value
  CHECK(p.given("run.model")); // command line, the same
  CHECK(!p.given("mesh.h"));
  CHECK(!p.given("run.flag"));
  CHECK_THROWS(p.given("mesh.nope"));
}

TEST_CASE("A scene's presets set what was not given", "[common]")
{
  Demo d;
  fsai::common::Parameters p("test", "test");
  d.bind(p);
  p.parse({"--mesh.h", "0.3"});
  p.preset("mesh.h", "0.7"); // given: kept
  p.preset("mesh.n", "9");
  p.preset("run.flag", "true");
  p.preset("run.model", "axisym");
  CHECK(d.h == 0.3);
  CHECK(d.n == 9);
  CHECK(d.flag);
  CHECK(d.model == "axisym");
  // A preset that is not a value of its key is a programming error
  CHECK_THROWS_AS(p.preset("run.model", "spherical"), std::logic_error);
  CHECK_THROWS_AS(p.preset("mesh.n", "many"), std::logic_error);
  CHECK_THROWS_AS(p.preset("mesh.nope", "1"), std::logic_error);
  CHECK(d.model == "axisym");
}

TEST_CASE("Bad input raises one-line InputError", "[common]")
{
  fsai::test::TempDir dir;
  using Catch::Matchers::Contains;
  auto message = [](const std::vector<std::string>& args)
  {
    try
    {
      parse(args);
    }
    catch (const fsai::InputError& e)
    {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  auto one_line
      = [](const std::string& s) { return s.find('\n') == std::string::npos; };

  std::string m = message({"--nonsense"});
  CHECK_THAT(m, Contains("--nonsense"));
  CHECK(one_line(m));

  m = message({"--mesh.h", "abc"});
  CHECK_THAT(m, Contains("mesh.h"));
  CHECK(one_line(m));

  m = message({"--run.model", "cylindrical"});
  CHECK_THAT(m, Contains("cylindrical"));

  m = message({"--config", "/nonexistent/fsai.toml"});
  CHECK_THAT(m, Contains("not found"));

  m = message({"--config", write_file(dir, "c.toml", "[mesh]\nh 0.1\n")});
  CHECK_THAT(m, Contains("c.toml"));
  CHECK(one_line(m));

  m = message({"--config", write_file(dir, "d.toml", "[mesh]\nhh = 0.1\n")});
  CHECK_THAT(m, Contains("mesh.hh") && Contains("unknown"));

  m = message({"--config", write_file(dir, "e.toml", "[mesh]\nh = \"big\"\n")});
  CHECK_THAT(m, Contains("mesh.h") && Contains("invalid"));

  m = message({"--config", write_file(dir, "f.toml", "run.model = \"x\"\n")});
  CHECK_THAT(m, Contains("run.model"));
}

TEST_CASE("Range checks name the parameter and the value", "[common]")
{
  using Catch::Matchers::Contains;
  CHECK_THROWS_WITH(fsai::require_positive("--mesh.h", -0.1),
                    Contains("--mesh.h") && Contains("> 0")
                        && Contains("-0.1"));
  CHECK_NOTHROW(fsai::require_range("nu", 0.3, 0.0, 0.5));
  CHECK_THROWS_AS(fsai::require_range("nu", 0.5001, 0.0, 0.5),
                  fsai::InputError);
}

TEST_CASE("PETSc options are split from application arguments", "[common]")
{
  auto [app, petsc] = fsai::common::Runtime::split_arguments(
      {"--output", "out", "-fluid_ksp_type", "gmres", "-ksp_view",
       "-fluid_ksp_rtol", "-1e-8", "--mesh.h", "-0.5", "-h"});
  CHECK(
      app
      == std::vector<std::string>{"--output", "out", "--mesh.h", "-0.5", "-h"});
  CHECK(petsc
        == std::vector<std::string>{"-fluid_ksp_type", "gmres", "-ksp_view",
                                    "-fluid_ksp_rtol", "-1e-8"});
}

TEST_CASE("Code defaults do not overwrite PETSc options already set",
          "[common]")
{
  fsai::test::TempDir dir;
  PetscOptionsSetValue(nullptr, "-fsai_test_ksp_type", "gmres");
  fsai::common::set_option_default("fsai_test_ksp_type", "cg");
  fsai::common::set_option_default("fsai_test_pc_type", "jacobi");
  char value[64];
  PetscBool set = PETSC_FALSE;
  PetscOptionsGetString(nullptr, nullptr, "-fsai_test_ksp_type", value,
                        sizeof(value), &set);
  CHECK(std::string(value) == "gmres");
  PetscOptionsGetString(nullptr, nullptr, "-fsai_test_pc_type", value,
                        sizeof(value), &set);
  CHECK(std::string(value) == "jacobi");

  // A [petsc] table in the config file sets defaults too
  std::string cfg = write_file(dir, "g.toml",
                               "[petsc]\nfsai_test_pc_type = \"ilu\"\n"
                               "fsai_test2_ksp_rtol = 1e-9\n");
  parse({"--config", cfg});
  PetscOptionsGetString(nullptr, nullptr, "-fsai_test_pc_type", value,
                        sizeof(value), &set);
  CHECK(std::string(value) == "jacobi"); // Already set: kept
  PetscReal rtol = 0;
  PetscOptionsGetReal(nullptr, nullptr, "-fsai_test2_ksp_rtol", &rtol, &set);
  CHECK(set);
  CHECK(rtol == Approx(1e-9));
}

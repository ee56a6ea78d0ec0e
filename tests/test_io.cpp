// Copyright (C) 2026 fsai developers
#include "catch.h"
#include <cmath>
#include <common/periodic.h>
#include <dolfinx/fem/utils.h>
#include <dolfinx/mesh/generation.h>
#include <filesystem>
#include <fsai_forms/poisson.h>
#include <fstream>
#include <io/CsvWriter.h>
#include <io/Progress.h>
#include <io/RunSummary.h>
#include <io/TimeSeriesWriter.h>
#include <io/run_state.h>
#include <nlohmann/json.hpp>
#include <sstream>

TEST_CASE("CsvWriter writes a header and round-trip exact rows", "[io]")
{
  fsai::test::TempDir dir;
  const std::string path = dir / "series.csv";
  {
    fsai::io::CsvWriter csv(MPI_COMM_SELF, path, {"t_s", "q_m3s"});
    csv.row({0.1, 1.0 / 3.0});
    csv.row({0.2, -2.5e-7});
    CHECK_THROWS_AS(csv.row({1.0}), std::logic_error);
  }
  std::ifstream in(path);
  std::string header, r1, r2;
  std::getline(in, header);
  std::getline(in, r1);
  std::getline(in, r2);
  CHECK(header == "t_s,q_m3s");
  CHECK(std::stod(r1.substr(r1.find(',') + 1)) == 1.0 / 3.0);
  CHECK(r2 == "0.20000000000000001,-2.4999999999999999e-07");
}

TEST_CASE("RunSummary writes parameters, results and wall time", "[io]")
{
  fsai::test::TempDir dir;
  const std::string path = dir / "summary.json";
  fsai::io::RunSummary s(MPI_COMM_SELF, "fsai_test");
  s.set_parameters({{"mesh", {{"h", 0.1}}}});
  s.set("f0_hz", 117.5);
  s.set("formants_hz", std::vector<double>{300, 870});
  s.write(path);
  nlohmann::json j = nlohmann::json::parse(std::ifstream(path));
  CHECK(j["program"] == "fsai_test");
  CHECK(j["f0_hz"] == 117.5);
  CHECK(j["formants_hz"][1] == 870);
  CHECK(j["parameters"]["mesh"]["h"] == 0.1);
  CHECK(j["wall_s"].get<double>() >= 0.0);
  CHECK(j.contains("timings"));
}

TEST_CASE("Progress estimates time left linearly", "[io]")
{
  CHECK(fsai::io::Progress::eta(25, 100, 10.0) == Approx(30.0));
  CHECK(std::isnan(fsai::io::Progress::eta(0, 100, 1.0)));
  // A restart from step 60: 5 steps in 10 s leave 35 steps, 70 s
  CHECK(fsai::io::Progress::eta(65, 100, 10.0, 60) == Approx(70.0));
  CHECK(std::isnan(fsai::io::Progress::eta(60, 100, 1.0, 60)));
  CHECK(fsai::io::Progress::format_duration(12.34) == "12.3s");
  CHECK(fsai::io::Progress::format_duration(187) == "3m07s");
  CHECK(fsai::io::Progress::format_duration(3720) == "1h02m");
}

TEST_CASE("TimeSeriesWriter writes the mesh once and one entry per step",
          "[io][mpi]")
{
  auto mesh
      = std::make_shared<dolfinx::mesh::Mesh>(dolfinx::mesh::create_rectangle(
          MPI_COMM_WORLD, {{{0.0, 0.0}, {1.0, 1.0}}}, {4, 4},
          dolfinx::mesh::CellType::triangle,
          dolfinx::mesh::GhostMode::shared_facet));
  auto V = std::make_shared<dolfinx::fem::FunctionSpace>(
      dolfinx::fem::create_functionspace(
          fsai::forms::poisson::functionspace_a(2, 1), "u", mesh));
  auto u = std::make_shared<dolfinx::fem::Function<double>>(V);
  u->name = "pressure";

  fsai::test::TempDir dir;
  const std::string path = dir / "series.xdmf";
  {
    fsai::io::TimeSeriesWriter writer(path, {u});
    for (double t : {0.0, 0.5, 1.0})
    {
      u->x()->set(t);
      writer.write(t);
    }
    CHECK(writer.steps() == 3);
  }
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  const std::string xml = text.str();
  auto count = [&xml](const std::string& what)
  {
    std::size_t n = 0;
    for (auto p = xml.find(what); p != std::string::npos;
         p = xml.find(what, p + 1))
      ++n;
    return n;
  };
  CHECK(count("<Time Value=") == 3);
  CHECK(count("<Attribute Name=\"pressure\"") == 3);
  CHECK(count("<Geometry") == 1); // Mesh written once

  // A restart of a run that wrote no series starts one
  const std::string fresh = dir / "restarted.xdmf";
  {
    fsai::io::TimeSeriesWriter writer(fresh, {u}, 0.5);
    writer.write(0.75);
  }
  std::ifstream in2(fresh);
  std::stringstream text2;
  text2 << in2.rdbuf();
  CHECK(text2.str().find("<Time Value=\"0.75\"") != std::string::npos);
}

TEST_CASE("periodic_stats: mean, amplitude, frequency of a sampled sine",
          "[io]")
{
  // v = 0.3 + 2 sin(2π 1.7 t) + a decaying start-up, sampled at 200 Hz on
  // [0, 10] s; statistics over t ≥ 6 s where the transient is < 1e-9
  std::vector<double> t, v;
  for (int k = 0; k <= 2000; ++k)
  {
    t.push_back(0.005 * k);
    v.push_back(0.3 + 2 * std::sin(2 * M_PI * 1.7 * t.back())
                + 5 * std::exp(-4 * t.back()));
  }
  auto s = fsai::common::periodic_stats(t, v, 6.0);
  CHECK(s.mean == Approx(0.3).margin(2e-3));
  CHECK(s.amplitude == Approx(2.0).epsilon(2e-3));
  CHECK(s.frequency == Approx(1.7).epsilon(1e-3));
  CHECK(s.crossings >= 6);
  // Too short a window: no frequency, no exception
  auto s1 = fsai::common::periodic_stats(t, v, 9.9);
  CHECK(s1.frequency == 0.0);
  CHECK_THROWS(fsai::common::periodic_stats(t, {1.0}, 0.0));
}

TEST_CASE("CsvWriter and checkpoints report a full disk", "[io]")
{
  // /dev/full accepts the open and fails every write with ENOSPC
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  REQUIRE(std::filesystem::exists("/dev/full")); // Linux
  if (rank == 0)
  {
    CHECK_THROWS_WITH(
        fsai::io::CsvWriter(MPI_COMM_SELF, "/dev/full", {"t_s", "x"}),
        Catch::Matchers::Contains("disk full"));
  }
  // A torn checkpoint must not replace a good one
  const std::string dir = "test_io_checkpoint_" + std::to_string(rank);
  std::filesystem::create_directories(dir);
  fsai::io::write_checkpoint(MPI_COMM_SELF, dir + "/ck.json", {{"step", 1}});
  CHECK(fsai::io::read_checkpoint(MPI_COMM_SELF, dir + "/ck.json")["step"]
        == 1);
  CHECK_THROWS_WITH(fsai::io::read_checkpoint(MPI_COMM_SELF, dir + "/none"),
                    Catch::Matchers::Contains("no checkpoint"));
}

TEST_CASE("Restart parameters: changed values refuse, new ones are reported",
          "[io]")
{
  const nlohmann::json saved = {{"dt", 1e-5},
                                {"output", "a"},
                                {"duration", 0.1},
                                {"fe", {{"h_gap", 3.5e-5}, {"old", 1}}}};
  nlohmann::json current = saved;
  current["output"] = "b";     // may differ
  current["duration"] = 0.2;   // may differ (a longer run)
  current["write_every"] = 10; // may differ (output only)
  current["fe"].erase("old");  // removed from the code since
  current["fe"]["new"] = true; // added to the code since
  current["fluid"] = {{"x", 2}};
  auto d = fsai::io::compare_parameters(saved, current);
  CHECK(d.changed.empty());
  REQUIRE(d.added.size() == 2);
  CHECK(d.added[0].first == "/fe/new");
  CHECK(d.added[0].second == true);
  CHECK(d.added[1].first == "/fluid");
  REQUIRE(d.removed.size() == 1);
  CHECK(d.removed[0] == "/fe/old");
  current["dt"] = 2e-5;
  d = fsai::io::compare_parameters(saved, current);
  REQUIRE(d.changed.size() == 1);
  CHECK(d.changed[0] == "/dt");
}

// SPDX-License-Identifier: Apache-2.0
// Campaign files (sil/campaign.hpp): expansion order, stable run ids (a pure function of the
// run's own values), [replicates] (seed suffix, `when` from the overrides or the base
// scenario, stagnant runs not replicated) and every rejection of a bad table.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "campaign.hpp"

using uvms::sil::Campaign;
using uvms::sil::CampaignError;
using uvms::sil::CampaignRun;
using uvms::sil::IdPart;
using uvms::sil::ParseCampaign;
using uvms::sil::ReplicateSuffix;
namespace fs = std::filesystem;

namespace {

// A scratch directory with two base scenarios: one that enables unsteady flow, one silent on it.
fs::path Scratch() {
  static const fs::path dir = [] {
    std::string tmpl = (fs::temp_directory_path() / "uvms-campaign-XXXXXX").string();
    const fs::path d = mkdtemp(tmpl.data());
    std::ofstream(d / "unsteady.toml") << "[control]\ncase = \"IV\"\n"
                                          "[environment.unsteady_flow]\nenabled = true\n";
    std::ofstream(d / "silent.toml") << "[control]\ncase = \"IV\"\n";
    std::ofstream(d / "notbool.toml") << "[environment.unsteady_flow]\nenabled = \"yes\"\n";
    return d;
  }();
  return dir;
}

Campaign Parse(const std::string &text, const std::vector<std::string> &sets = {}) {
  return ParseCampaign(text, (Scratch() / "c.toml").string(), sets);
}

std::string ErrorOf(const std::string &text, const std::vector<std::string> &sets = {}) {
  try {
    Parse(text, sets);
  } catch (const CampaignError &e) {
    return e.what();
  }
  return "";
}

std::vector<std::string> Ids(const Campaign &c) {
  std::vector<std::string> ids;
  for (const CampaignRun &r : c.runs) ids.push_back(r.id);
  return ids;
}

const CampaignRun &Find(const Campaign &c, const std::string &id) {
  for (const CampaignRun &r : c.runs)
    if (r.id == id) return r;
  FAIL("no run " << id);
  throw 0;
}

const std::string kFlowSweep =
    "base = \"silent.toml\"\n"
    "[[sweep]]\n\"control.case\" = [\"IV\", \"VII\"]\n"
    "[[sweep]]\nlabels = [\"stagnant\", \"unsteady\"]\n"
    "\"environment.unsteady_flow.enabled\" = [false, true]\n";

const std::string kSeeds =
    "[replicates]\nkey = \"run.seed\"\nvalues = [1, 2, 3]\n"
    "when = \"environment.unsteady_flow.enabled\"\n";

}  // namespace

TEST_CASE("run ids are the axis labels, in Cartesian order, without an index") {
  const Campaign c = Parse("base = \"silent.toml\"\n"
                           "[[sweep]]\n\"control.case\" = [\"IV\", \"VII\"]\n"
                           "[[sweep]]\n\"payload.mass_kg\" = [0.0, 5.0]\n");
  CHECK(Ids(c) == std::vector<std::string>{"IV_0.0", "IV_5.0", "VII_0.0", "VII_5.0"});
  CHECK(Find(c, "VII_0.0").overrides ==
        std::vector<std::string>{"control.case=\"VII\"", "payload.mass_kg=0.0"});
  CHECK(Ids(Parse("base = \"silent.toml\"\n")) == std::vector<std::string>{"run"});
}

TEST_CASE("adding a sweep value renames no run and changes no other run's overrides") {
  const std::string head = "base = \"silent.toml\"\n[set]\n\"run.duration_s\" = 1.5\n[[sweep]]\n";
  const Campaign before = Parse(head + "\"payload.mass_kg\" = [0.0, 5.0]\n");
  const Campaign after = Parse(head + "\"payload.mass_kg\" = [0.0, 2.0, 5.0]\n");
  REQUIRE(after.runs.size() == 3);
  for (const CampaignRun &r : before.runs) CHECK(Find(after, r.id).overrides == r.overrides);
}

TEST_CASE("ids are sanitised for file names") {
  CHECK(IdPart("a b/c") == "a_b_c");
  CHECK(IdPart("\"IV\"") == "IV");
  CHECK(IdPart("[1, 0, 0]") == "1_0_0");
  CHECK(IdPart("../x") == "x");
  CHECK(IdPart(".hidden") == "hidden");
  CHECK(IdPart("-1.5") == "-1.5");  // negative values stay distinct
  CHECK(IdPart("") == "v");
  CHECK(IdPart("///") == "v");
  CHECK(ReplicateSuffix(7) == "s7");
  CHECK(ReplicateSuffix(120) == "s120");
}

TEST_CASE("two runs with the same id are an error naming both") {
  const std::string e = ErrorOf("base = \"silent.toml\"\n[[sweep]]\nlabels = [\"a b\", \"a_b\"]\n"
                                "\"payload.mass_kg\" = [1.0, 2.0]\n");
  CHECK_THAT(e, Catch::Contains("c.toml") && Catch::Contains("\"a_b\"") &&
                    Catch::Contains("payload.mass_kg = 1.0") &&
                    Catch::Contains("payload.mass_kg = 2.0"));
}

TEST_CASE("replicates: only runs whose `when` is true, with an unpadded seed suffix") {
  const Campaign c = Parse(kFlowSweep + kSeeds);
  CHECK(Ids(c) == std::vector<std::string>{"IV_stagnant", "IV_unsteady_s1", "IV_unsteady_s2",
                                           "IV_unsteady_s3", "VII_stagnant", "VII_unsteady_s1",
                                           "VII_unsteady_s2", "VII_unsteady_s3"});
  const CampaignRun &stagnant = Find(c, "VII_stagnant");
  CHECK_FALSE(stagnant.replicate.has_value());
  for (const std::string &o : stagnant.overrides) CHECK(o.rfind("run.seed", 0) != 0);
  const CampaignRun &r = Find(c, "VII_unsteady_s2");
  REQUIRE(r.replicate.has_value());
  CHECK(*r.replicate == 2);
  CHECK(r.overrides.back() == "run.seed=2");
  CHECK(r.swept.back() == std::make_pair(std::string("run.seed"), std::string("2")));
  CHECK(c.replicates.values == std::vector<std::int64_t>{1, 2, 3});
}

TEST_CASE("replicates: first and count; a seed past 99 renames no other run") {
  const std::string rep = "[replicates]\nkey = \"run.seed\"\nfirst = 99\ncount = 2\n";
  const Campaign c = Parse("base = \"silent.toml\"\n" + rep);
  CHECK(Ids(c) == std::vector<std::string>{"s99", "s100"});
  const Campaign one =
      Parse("base = \"silent.toml\"\n[replicates]\nkey = \"run.seed\"\nvalues = [4]\n");
  CHECK(Ids(one) == std::vector<std::string>{"s4"});
}

TEST_CASE("replicates: adding a seed keeps every other run's id and overrides") {
  const Campaign before = Parse(kFlowSweep + kSeeds);
  std::string more = kFlowSweep + kSeeds;
  more.replace(more.find("[1, 2, 3]"), 9, "[1, 2, 3, 4]");
  const Campaign after = Parse(more);
  CHECK(after.runs.size() == before.runs.size() + 2);
  for (const CampaignRun &r : before.runs) CHECK(Find(after, r.id).overrides == r.overrides);
}

TEST_CASE("replicates: `when` falls back to the base scenario, and the last override wins") {
  const std::string rep = "[replicates]\nkey = \"run.seed\"\nvalues = [1, 2]\n"
                          "when = \"environment.unsteady_flow.enabled\"\n";
  CHECK(Parse("base = \"unsteady.toml\"\n" + rep).runs.size() == 2);
  CHECK(Parse("base = \"unsteady.toml\"\n" + rep,
              {"environment.unsteady_flow.enabled=false"}).runs.size() == 1);
  // A sweep value comes after the extra --set, so it wins.
  CHECK(Parse(kFlowSweep + rep, {"environment.unsteady_flow.enabled=false"}).runs.size() == 6);
  // An override of the enclosing table counts too.
  CHECK(Parse("base = \"silent.toml\"\n" + rep,
              {"environment.unsteady_flow={ enabled = true }"}).runs.size() == 2);
  CHECK_THAT(ErrorOf("base = \"silent.toml\"\n" + rep),
             Catch::Contains("replicates.when") && Catch::Contains("set neither") &&
                 Catch::Contains("silent.toml"));
  CHECK_THAT(ErrorOf("base = \"notbool.toml\"\n" + rep),
             Catch::Contains("\"yes\"") && Catch::Contains("expected a boolean"));
}

TEST_CASE("replicates: bad tables are rejected with file, line and key") {
  const std::string base = "base = \"silent.toml\"\n[replicates]\n";  // [replicates] is line 2
  struct Bad {
    std::string table, where, key, what;
  };
  const std::vector<Bad> bad = {
      {"key = \"run.seed\"\nvalues = [1]\nseeds = 3\n", "c.toml:5", "replicates.seeds",
       "unknown key"},
      {"key = \"run.seed\"\nvalues = []\n", "c.toml:4", "replicates.values", "non-empty"},
      {"key = \"run.seed\"\nvalues = [1, 2.5]\n", "c.toml:4", "replicates.values", "got 2.5"},
      {"key = \"run.seed\"\nvalues = [1, \"2\"]\n", "c.toml:4", "replicates.values", "integer"},
      {"key = \"run.seed\"\nvalues = [1, -2]\n", "c.toml:4", "replicates.values", ">= 0"},
      {"key = \"run.seed\"\nvalues = [1, 2, 1]\n", "c.toml:4", "replicates.values",
       "more than once"},
      {"key = \"run.seed\"\nvalues = 3\n", "c.toml:4", "replicates.values", "array"},
      {"key = \"run.seed\"\nvalues = [1]\nfirst = 1\ncount = 2\n", "c.toml:2",
       "replicates.values", "not both"},
      {"key = \"run.seed\"\nfirst = 1\n", "c.toml:2", "replicates", "missing count"},
      {"key = \"run.seed\"\nfirst = 1\ncount = 0\n", "c.toml:5", "replicates.count", ">= 1"},
      {"values = [1]\n", "c.toml:2", "replicates.key", "required"},
      {"key = \"run seed\"\nvalues = [1]\n", "c.toml:3", "replicates.key", "dotted"},
      {"key = \"run.seed\"\nvalues = [1]\nwhen = 3\n", "c.toml:5", "replicates.when", "dotted"},
  };
  for (const Bad &b : bad) {
    INFO(b.table);
    const std::string e = ErrorOf(base + b.table);
    CHECK_THAT(e, Catch::StartsWith((Scratch() / b.where).string() + ": key \"" + b.key + "\"") &&
                      Catch::Contains(b.what));
  }
  CHECK_THAT(ErrorOf("base = \"silent.toml\"\nreplicates = 3\n"),
             Catch::Contains("c.toml:2") && Catch::Contains("[replicates]"));
  CHECK_THAT(ErrorOf("base = \"silent.toml\"\n[[sweep]]\n\"run.seed\" = [1, 2]\n"
                     "[replicates]\nkey = \"run.seed\"\nvalues = [1]\n"),
             Catch::Contains("replicates.key") && Catch::Contains("also a [[sweep]] key"));
}

// ---- issue 15 items 5 and 6: input bounds and values that become --set lines ------------------

TEST_CASE("CampaignInputBoundsAreCheckedBeforeParsing") {
  std::string dotted = "a";
  for (int i = 0; i < 50000; ++i) dotted += ".a";
  CHECK_THAT(ErrorOf(dotted + " = 1\n"), Catch::Contains("c.toml:1: a dotted key of more than 32 parts"));
  CHECK_THAT(ErrorOf("a = " + std::string(5000, '[')), Catch::Contains("nesting deeper than 32"));
  CHECK_THROWS_WITH(uvms::sil::LoadCampaign("/dev/urandom"), Catch::Contains("not a regular file"));
  CHECK_THROWS_WITH(uvms::sil::LoadCampaign(Scratch().string()), Catch::Contains("not a regular file (a directory"));
}

TEST_CASE("CampaignSetValuesWithLineBreaksAreRejected") {
  CHECK_THAT(ErrorOf("base = \"silent.toml\"\n[set]\n\"run.name\" = \"a\\nrun.tick_s = 1e-300\"\n"),
             Catch::Contains("key \"run.name\": a string value with a line break"));
  CHECK_THAT(ErrorOf("base = \"silent.toml\"\n[[sweep]]\n\"run.name\" = [\"a\", \"b\\r\"]\n"),
             Catch::Contains("line break"));
}

// SPDX-License-Identifier: Apache-2.0
// Campaign files (sil/campaign/campaign.hpp): expansion order, stable run ids (a pure function of the
// run's own values), [replicates] (seed suffix, `when` from the overrides or the base
// scenario, stagnant runs not replicated) and every rejection of a bad table.
#include <catch2/catch.hpp>

#include <chrono>
#include <cstddef>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

#include "campaign/campaign.hpp"
#include "run/provenance.hpp"

using uvms::sil::Campaign;
using uvms::sil::CampaignError;
using uvms::sil::CampaignIdentity;
using uvms::sil::CampaignRun;
using uvms::sil::IdPart;
using uvms::sil::ParseCampaign;
using uvms::sil::ReplicateSuffix;
using uvms::sil::RunSession;
namespace fs = std::filesystem;

namespace {

// A scratch directory with two base scenarios: one that enables unsteady flow, one silent on it.
// Removed when the test process exits.
struct ScratchDir {
  fs::path path;
  ScratchDir() {
    std::string tmpl = (fs::temp_directory_path() / "uvms-campaign-XXXXXX").string();
    path = mkdtemp(tmpl.data());
    std::ofstream(path / "unsteady.toml") << "[control]\ncase = \"IV\"\n"
                                             "[environment.unsteady_flow]\nenabled = true\n";
    std::ofstream(path / "silent.toml") << "[control]\ncase = \"IV\"\n";
    std::ofstream(path / "notbool.toml") << "[environment.unsteady_flow]\nenabled = \"yes\"\n";
  }
  ~ScratchDir() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
};

fs::path Scratch() {
  static const ScratchDir dir;
  return dir.path;
}

Campaign Parse(const std::string &text, const std::vector<std::string> &sets = {},
               std::size_t max_runs = uvms::sil::kDefaultMaxRuns) {
  return ParseCampaign(text, (Scratch() / "c.toml").string(), sets, max_runs);
}

std::string ErrorOf(const std::string &text, const std::vector<std::string> &sets = {},
                    std::size_t max_runs = uvms::sil::kDefaultMaxRuns) {
  try {
    Parse(text, sets, max_runs);
  } catch (const CampaignError &e) {
    return e.what();
  }
  return "";
}

// A campaign of `n` [[sweep]] axes of two values each: 2^n runs.
std::string BinaryAxes(int n) {
  std::string text = "base = \"silent.toml\"\n";
  for (int i = 0; i < n; ++i) text += "[[sweep]]\n\"p.k" + std::to_string(i) + "\" = [0, 1]\n";
  return text;
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

TEST_CASE("replicates: first and count, and a seed past 99 renames no other run") {
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

// ---- issue 18: campaign integrity (run-count limit, one axis per key, identity) ---------------

TEST_CASE("a run count past size_t is an overflow error, raised before any run is built") {
  REQUIRE(sizeof(std::size_t) == 8);  // the counts below are 2^64
  const auto start = std::chrono::steady_clock::now();
  const std::string e = ErrorOf(BinaryAxes(64));  // 2^64 runs: wrapped to 0 before issue 18
  const double elapsed_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  CHECK_THAT(e, Catch::StartsWith((Scratch() / "c.toml").string() + ": ") &&
                    Catch::Contains("18,446,744,073,709,551,616 runs or more (overflow)") &&
                    Catch::Contains("64 [[sweep]] axes"));
  CHECK(elapsed_s < 5.0);  // no work proportional to the count
  // 2^63 combinations fit; twice as many replicated runs do not.
  CHECK_THAT(ErrorOf(BinaryAxes(63) + "[replicates]\nkey = \"run.seed\"\nvalues = [1, 2]\n"),
             Catch::Contains("18,446,744,073,709,551,616 runs or more (overflow)") &&
                 Catch::Contains("63 [[sweep]] axes and 2 replicate values"));
}

TEST_CASE("a run count over --max-runs is an error naming the count and the limit") {
  const auto start = std::chrono::steady_clock::now();
  const std::string e = ErrorOf(BinaryAxes(40));  // 2^40 runs: exhausted memory before issue 18
  const double elapsed_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  CHECK_THAT(e, Catch::Contains("the campaign expands to 1,099,511,627,776 runs, over the limit "
                                "of 1,000,000 (--max-runs N raises it)"));
  CHECK(elapsed_s < 5.0);
  CHECK(uvms::sil::kDefaultMaxRuns == 1000000);
}

TEST_CASE("a campaign exactly at --max-runs is accepted and one run more is refused") {
  // 2 x 2 x 3 axis values = 12 runs.
  const std::string axes = "base = \"silent.toml\"\n[[sweep]]\n\"a.x\" = [0, 1]\n"
                           "[[sweep]]\n\"a.y\" = [0, 1]\n[[sweep]]\n\"a.z\" = [0, 1, 2]\n";
  CHECK(Parse(axes, {}, 12).runs.size() == 12);
  CHECK_THAT(ErrorOf(axes, {}, 11),
             Catch::EndsWith(": the campaign expands to 12 runs, over the limit of 11 "
                             "(--max-runs N raises it)"));
  // 2 x 2 combinations x 3 replicates = 12 runs.
  const std::string replicated = "base = \"silent.toml\"\n[[sweep]]\n\"a.x\" = [0, 1]\n"
                                 "[[sweep]]\n\"a.y\" = [0, 1]\n"
                                 "[replicates]\nkey = \"run.seed\"\nvalues = [1, 2, 3]\n";
  CHECK(Parse(replicated, {}, 12).runs.size() == 12);
  CHECK_THAT(ErrorOf(replicated, {}, 11), Catch::Contains("12 runs, over the limit of 11"));
  // Conditional replicates: 2 stagnant runs + 2 x 3 unsteady ones = 8 runs.
  CHECK(Parse(kFlowSweep + kSeeds, {}, 8).runs.size() == 8);
  CHECK_THAT(ErrorOf(kFlowSweep + kSeeds, {}, 7), Catch::Contains("8 runs, over the limit of 7"));
  // More combinations than the limit: refused before `when` is evaluated for any of them.
  CHECK_THAT(ErrorOf(kFlowSweep + kSeeds, {}, 3),
             Catch::Contains("4 runs or more, over the limit of 3"));
}

TEST_CASE("a run limit of zero is refused") {
  CHECK_THAT(ErrorOf("base = \"silent.toml\"\n", {}, 0),
             Catch::Contains("(--max-runs) is 0 (expected at least 1)"));
}

TEST_CASE("a key on two axes is refused, naming both lines") {
  const std::string text = "base = \"silent.toml\"\n"                         // line 1
                           "[[sweep]]\n\"payload.mass_kg\" = [0.0, 5.0]\n"    // lines 2, 3
                           "[[sweep]]\n\"control.case\" = [\"IV\"]\n"         // lines 4, 5
                           "[[sweep]]\n\"payload.mass_kg\" = [1.0]\n";        // lines 6, 7
  CHECK_THAT(ErrorOf(text),
             Catch::StartsWith((Scratch() / "c.toml").string() +
                               ":7: key \"payload.mass_kg\": on two [[sweep]] axes, lines 3 and "
                               "7") &&
                 Catch::Contains("one [[sweep]]"));
}

TEST_CASE("keys are compared as --set applies them: blanks trimmed, then a dotted key") {
  // Two axes whose keys differ only by blanks set the same key once --set trims it.
  const std::string two_axes = "base = \"silent.toml\"\n"                       // line 1
                               "[[sweep]]\n\"control.case\" = [\"IV\", \"VII\"]\n"  // 2, 3
                               "[[sweep]]\n\" control.case \" = [\"II\"]\n";       // 4, 5
  CHECK_THAT(ErrorOf(two_axes), Catch::Contains(":5: key \"control.case\": on two [[sweep]] "
                                                "axes, lines 3 and 5"));
  // The replicate key against an axis key spelled with a tab.
  const std::string rep = "base = \"silent.toml\"\n"
                          "[[sweep]]\n\"run.seed\t\" = [1, 2]\n"
                          "[replicates]\nkey = \"run.seed\"\nvalues = [1]\n";
  CHECK_THAT(ErrorOf(rep), Catch::Contains("\"run.seed\" is also a [[sweep]] key on line 3"));
  // [set] twice under two spellings.
  CHECK_THAT(ErrorOf("base = \"silent.toml\"\n[set]\n\"run.seed\" = 1\n\" run.seed\" = 2\n"),
             Catch::Contains("set twice"));
  // Not a dotted key at all: refused by name, wherever it is.
  CHECK_THAT(ErrorOf("base = \"silent.toml\"\n[[sweep]]\n\"control..case\" = [\"IV\"]\n"),
             Catch::Contains("sweep key \"control..case\": not a dotted scenario key"));
  CHECK_THAT(ErrorOf("base = \"silent.toml\"\n[set]\n\"run seed\" = 1\n"),
             Catch::Contains("[set] key \"run seed\": not a dotted scenario key"));
  // The normalized key is what the runs get.
  const Campaign c = Parse("base = \"silent.toml\"\n[set]\n\" run.duration_s\" = 1.0\n"
                           "[[sweep]]\n\"control.case \" = [\"IV\"]\n"
                           "[replicates]\nkey = \" run.seed\"\nvalues = [3]\n");
  REQUIRE(c.runs.size() == 1);
  CHECK(c.runs[0].overrides ==
        std::vector<std::string>{"run.duration_s=1.0", "control.case=\"IV\"", "run.seed=3"});
}

TEST_CASE("a table value on an axis is refused, naming its key and line") {
  // (So no axis can set a table while another sets a key inside it.)
  const std::string text = "base = \"silent.toml\"\n"                                  // 1
                           "[[sweep]]\n\"environment.unsteady_flow.enabled\" = [true]\n"  // 2, 3
                           "[[sweep]]\n\"environment.unsteady_flow\" = [{enabled = false}]\n";
  CHECK_THAT(ErrorOf(text), Catch::Contains("line 5: key \"environment.unsteady_flow\": a table "
                                            "value (expected a value"));
}

TEST_CASE("the replicate key on an axis is refused, naming both lines") {
  const std::string text = "base = \"silent.toml\"\n"                      // line 1
                           "[[sweep]]\n\"run.seed\" = [1, 2]\n"             // lines 2, 3
                           "[replicates]\nkey = \"run.seed\"\nvalues = [1]\n";  // lines 4-6
  CHECK_THAT(ErrorOf(text), Catch::StartsWith((Scratch() / "c.toml").string() +
                                              ":5: key \"replicates.key\": \"run.seed\" is also "
                                              "a [[sweep]] key on line 3"));
}

TEST_CASE("a key both in [set] and on an axis is allowed, and the axis value wins") {
  const Campaign c = Parse("base = \"silent.toml\"\n[set]\n\"payload.mass_kg\" = 9.0\n"
                           "[[sweep]]\n\"payload.mass_kg\" = [0.0, 5.0]\n");
  REQUIRE(c.runs.size() == 2);
  CHECK(Find(c, "5.0").overrides ==
        std::vector<std::string>{"payload.mass_kg=9.0", "payload.mass_kg=5.0"});
}

TEST_CASE("campaign identity is stable and changes with every input") {
  const std::string campaign = "base = \"b.toml\"\n", base = "[run]\nseed = 1\n";
  const std::vector<std::string> sets = {"run.seed=2", "run.duration_s=1.0"};
  const std::string id = CampaignIdentity(campaign, base, sets, "0.4.0");
  CHECK(id.size() == 64);
  CHECK(id.find_first_not_of("0123456789abcdef") == std::string::npos);
  CHECK(CampaignIdentity(campaign, base, sets, "0.4.0") == id);
  CHECK(CampaignIdentity(campaign + " ", base, sets, "0.4.0") != id);
  CHECK(CampaignIdentity(campaign, base + "\n", sets, "0.4.0") != id);
  CHECK(CampaignIdentity(campaign, base, {"run.seed=3", "run.duration_s=1.0"}, "0.4.0") != id);
  CHECK(CampaignIdentity(campaign, base, {"run.duration_s=1.0", "run.seed=2"}, "0.4.0") != id);
  CHECK(CampaignIdentity(campaign, base, {"run.seed=2"}, "0.4.0") != id);
  CHECK(CampaignIdentity(campaign, base, sets, "0.4.1") != id);
}

TEST_CASE("campaign identity parts are length-prefixed, so no boundary can move") {
  CHECK(CampaignIdentity("", "", {"ab", "c"}, "v") != CampaignIdentity("", "", {"a", "bc"}, "v"));
  CHECK(CampaignIdentity("ab", "c", {}, "v") != CampaignIdentity("a", "bc", {}, "v"));
  CHECK(CampaignIdentity("", "", {"x"}, "v") != CampaignIdentity("", "", {}, "xv"));
  CHECK(CampaignIdentity("", "", {""}, "v") != CampaignIdentity("", "", {}, "v"));
  // The layout documented in campaign.hpp, hashed by the one SHA-256 of provenance.hpp.
  CHECK(CampaignIdentity("a", "b", {"c"}, "v") == uvms::sil::Sha256Hex("1:a1:b1:c1:v"));
}

TEST_CASE("a run's session is a function of its inputs: 16 hex digits, as documented") {
  const std::string base = "[run]\nseed = 1\n";
  const std::vector<std::string> ov = {"control.case=\"IV\"", "payload.mass_kg=5.0"};
  const std::string s = RunSession(base, ov);
  CHECK(s.size() == 16);
  CHECK(s.find_first_not_of("0123456789abcdef") == std::string::npos);
  CHECK(RunSession(base, ov) == s);
  CHECK(RunSession(base + " ", ov) != s);
  CHECK(RunSession(base, {ov[1], ov[0]}) != s);
  CHECK(RunSession(base, {ov[0]}) != s);
  CHECK(RunSession("", {"ab", "c"}) != RunSession("", {"a", "bc"}));
  // The layout documented in campaign.hpp: the first 16 hex digits of the length-prefixed
  // stream's SHA-256, computed here by hand.
  const std::string domain = "uvms campaign run session";
  const std::string stream = std::to_string(domain.size()) + ":" + domain + "1:b3:o=1";
  CHECK(RunSession("b", {"o=1"}) == uvms::sil::Sha256Hex(stream).substr(0, 16));
}

TEST_CASE("a float value is written in its shortest round-trip form, still a float") {
  const Campaign c = Parse("base = \"silent.toml\"\n[[sweep]]\n"
                           "\"environment.unsteady_flow.amplitude_m_s\" = [0.05, 1e-5, 5.0, 0.1]\n");
  REQUIRE(c.runs.size() == 4);
  const std::vector<std::string> ids = {c.runs[0].id, c.runs[1].id, c.runs[2].id, c.runs[3].id};
  CHECK(ids == std::vector<std::string>{"0.05", "1e-05", "5.0", "0.1"});
  CHECK(c.runs[0].overrides.back() == "environment.unsteady_flow.amplitude_m_s=0.05");
  // Each text reads back to the same double (strtod, independent of the formatter).
  const double want[] = {0.05, 1e-5, 5.0, 0.1};
  for (size_t i = 0; i < 4; ++i) {
    const std::string &o = c.runs[i].overrides.back();
    CHECK(std::strtod(o.substr(o.find('=') + 1).c_str(), nullptr) == want[i]);
  }
}

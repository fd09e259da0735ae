// SPDX-License-Identifier: Apache-2.0
// fuzz_scenario: scenario files through the real parser entry point, uvms::sil::ParseScenario
// (sil/scenario/scenario.hpp), with --set overrides.
//
// Input: TOML text; when it contains NUL bytes, the text before the first NUL is the file and
// every further NUL-separated piece (at most kMaxOverrides) is one "section.key=value" --set
// string. A seed that is a plain scenario file therefore has no overrides.
//
// Properties: ParseScenario either returns a scenario or throws uvms::sil::ScenarioError (the
// designed outcome for bad input) whose message starts with the file name or "--set ". Any other exception, a crash, a sanitizer report, a leak or
// a hang (libFuzzer -timeout) is a finding. A scenario it returns is consistent: a positive,
// finite tick and duration, a tick count ≥ 1, a non-empty name, and ScenarioSummary of it works.
#include <cmath>
#include <exception>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_support.h"
#include "scenario/scenario.hpp"

namespace {
constexpr std::size_t kMaxOverrides = 4;
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  const std::string_view all(reinterpret_cast<const char *>(data), size);
  std::string_view text = all;
  std::vector<std::string> overrides;
  std::size_t nul = all.find('\0');
  if (nul != std::string_view::npos) {
    text = all.substr(0, nul);
    std::string_view rest = all.substr(nul + 1);
    while (overrides.size() < kMaxOverrides) {
      const std::size_t next = rest.find('\0');
      overrides.emplace_back(rest.substr(0, next));
      if (next == std::string_view::npos) break;
      rest = rest.substr(next + 1);
    }
  }
  try {
    const uvms::sil::Scenario s = uvms::sil::ParseScenario(text, "fuzz.toml", overrides);
    FUZZ_REQUIRE(std::isfinite(s.tick_s) && s.tick_s > 0, "tick_s %g", s.tick_s);
    FUZZ_REQUIRE(std::isfinite(s.duration_s) && s.duration_s >= s.tick_s,
                 "duration_s %g, tick_s %g", s.duration_s, s.tick_s);
    FUZZ_REQUIRE(uvms::sil::ScenarioTicks(s) >= 1, "%lld ticks",
                 static_cast<long long>(uvms::sil::ScenarioTicks(s)));
    FUZZ_REQUIRE(!s.name.empty(), "empty name");
    FUZZ_REQUIRE(!uvms::sil::ScenarioSummary(s).empty(), "empty summary");
  } catch (const uvms::sil::ScenarioError &e) {
    // Rejected: what bad input should get, with a message that names where (scenario.hpp).
    const std::string_view msg = e.what();
    FUZZ_REQUIRE(msg.rfind("fuzz.toml", 0) == 0 || msg.rfind("--set ", 0) == 0,
                 "error message names neither the file nor the --set: \"%s\"", e.what());
  } catch (const std::exception &e) {
    FUZZ_REQUIRE(false, "ParseScenario threw a non-ScenarioError exception: %s", e.what());
  } catch (...) {
    FUZZ_REQUIRE(false, "ParseScenario threw something that is not a std::exception");
  }
  return 0;
}

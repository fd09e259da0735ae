// SPDX-License-Identifier: Apache-2.0
// provenance.hpp: where a run's numbers come from, written into summary.json and a campaign's
// plan.json / results.json as the ordered object "provenance":
//
//   version               the project version (top-level CMakeLists.txt, project(... VERSION)),
//                         as the firmware library reports it (uvms_version(), uvms/version.h)
//   git_commit            the commit this binary was built from, "<sha>-dirty" when the source
//                         tree had uncommitted changes (tracked or untracked, not ignored) at
//                         build time, "unknown" outside a git checkout. Refreshed at every
//                         build (cmake/git_commit.cmake), not only at configure time.
//   build_preset          the configure preset (cache variable UVMS_BUILD_PRESET; "custom"
//                         when configured without a preset)
//   build_type            CMAKE_BUILD_TYPE ("none" when empty)
//   controller_precision  "double" or "float": the controller's uvms_real_t (the PIL image on
//                         the emulated Cortex-M4F is always "float")
// then, for a run:
//   scenario_sha256       SHA-256 (lowercase hex) of the scenario file's bytes as read
//   scenario_sets         the --set overrides, in order, joined with "\n" ("" when none)
// or, for a campaign:
//   campaign_sha256       SHA-256 of the campaign file's bytes
//   campaign_sets         the campaign's extra --set overrides joined with "\n"
//   scenario_sha256       SHA-256 of the base scenario file's bytes
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace uvms::sil {

/// Ordered key/value pairs (the order is the JSON object's).
using Provenance = std::vector<std::pair<std::string, std::string>>;

/// SHA-256 of `bytes` as 64 lowercase hex digits (OpenSSL libcrypto, EVP_sha256).
std::string Sha256Hex(std::string_view bytes);

/// The lines joined with "\n" (no trailing newline; "" for none).
std::string JoinLines(const std::vector<std::string> &lines);

/// version, git_commit, build_preset, build_type, controller_precision of this binary.
/// `pil_controller`: the controller is the Cortex-M4F image (single precision) rather than
/// this build's host controller.
Provenance BuildProvenance(bool pil_controller = false);

/// BuildProvenance, then scenario_sha256 of `scenario_bytes` and scenario_sets.
Provenance RunProvenance(std::string_view scenario_bytes, const std::vector<std::string> &sets,
                         bool pil_controller = false);

/// BuildProvenance, then campaign_sha256, campaign_sets and scenario_sha256 (base scenario).
Provenance CampaignProvenance(std::string_view campaign_bytes,
                              const std::vector<std::string> &campaign_sets,
                              std::string_view base_scenario_bytes);

}  // namespace uvms::sil

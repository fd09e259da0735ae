// SPDX-License-Identifier: Apache-2.0
// provenance.cpp: where a run's numbers come from (provenance.hpp).
#include "run/provenance.hpp"

#include <openssl/evp.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "uvms/types.h"
#include "uvms/version.h"
#include "uvms_git_commit.h"  // generated at build time: UVMS_GIT_COMMIT

// Set by sil/CMakeLists.txt at configure time.
#ifndef UVMS_BUILD_PRESET
#error "UVMS_BUILD_PRESET must be defined by the build (cache variable)"
#endif
#ifndef UVMS_BUILD_TYPE
#error "UVMS_BUILD_TYPE must be defined by the build (CMAKE_BUILD_TYPE)"
#endif

namespace uvms::sil {

std::string Sha256Hex(std::string_view bytes) {
  unsigned char md[EVP_MAX_MD_SIZE];
  unsigned int n = 0;
  if (EVP_Digest(bytes.data(), bytes.size(), md, &n, EVP_sha256(), nullptr) != 1 || n != 32)
    throw std::runtime_error("SHA-256 failed (OpenSSL EVP_Digest)");
  static const char kHex[] = "0123456789abcdef";
  std::string hex;
  hex.reserve(2 * n);
  for (unsigned int i = 0; i < n; ++i) {
    hex += kHex[md[i] >> 4];
    hex += kHex[md[i] & 0xF];
  }
  return hex;
}

std::string JoinLines(const std::vector<std::string> &lines) {
  std::string out;
  for (size_t i = 0; i < lines.size(); ++i) out += (i ? "\n" : "") + lines[i];
  return out;
}

Provenance BuildProvenance(bool pil_controller) {
  const bool single = pil_controller || sizeof(uvms_real_t) == sizeof(float);
  const std::string build_type = UVMS_BUILD_TYPE;
  return {{"version", uvms_version()},
          {"git_commit", UVMS_GIT_COMMIT},
          {"build_preset", UVMS_BUILD_PRESET},
          {"build_type", build_type.empty() ? "none" : build_type},
          {"controller_precision", single ? "float" : "double"}};
}

Provenance RunProvenance(std::string_view scenario_bytes, const std::vector<std::string> &sets,
                         bool pil_controller) {
  Provenance p = BuildProvenance(pil_controller);
  p.emplace_back("scenario_sha256", Sha256Hex(scenario_bytes));
  p.emplace_back("scenario_sets", JoinLines(sets));
  return p;
}

Provenance CampaignProvenance(std::string_view campaign_bytes,
                              const std::vector<std::string> &campaign_sets,
                              std::string_view base_scenario_bytes) {
  Provenance p = BuildProvenance();
  p.emplace_back("campaign_sha256", Sha256Hex(campaign_bytes));
  p.emplace_back("campaign_sets", JoinLines(campaign_sets));
  p.emplace_back("scenario_sha256", Sha256Hex(base_scenario_bytes));
  return p;
}

}  // namespace uvms::sil

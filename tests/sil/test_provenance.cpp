// SPDX-License-Identifier: Apache-2.0
// Provenance (sil/run/provenance.hpp): SHA-256 against the FIPS 180-4 / NIST example vectors, the
// keys and their order, the precision against this build's uvms_real_t, file reading errors.
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "run/provenance.hpp"
#include "uvms/types.h"

using uvms::sil::Provenance;

namespace {

std::vector<std::string> Keys(const Provenance &p) {
  std::vector<std::string> k;
  for (const auto &kv : p) k.push_back(kv.first);
  return k;
}

std::string Value(const Provenance &p, const std::string &key) {
  for (const auto &kv : p)
    if (kv.first == key) return kv.second;
  return "<absent>";
}

}  // namespace

TEST_CASE("SHA-256 of the FIPS 180-4 example messages") {
  using uvms::sil::Sha256Hex;
  CHECK(Sha256Hex("") == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  CHECK(Sha256Hex("abc") == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  CHECK(Sha256Hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq") ==
        "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  CHECK(Sha256Hex(std::string(1000000, 'a')) ==
        "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
  CHECK(Sha256Hex(std::string("a\0b", 3)) != Sha256Hex("a"));  // bytes, not a C string
}

TEST_CASE("build provenance: keys in order, nothing empty, precision of this build") {
  const Provenance p = uvms::sil::BuildProvenance();
  CHECK(Keys(p) == std::vector<std::string>{"version", "git_commit", "build_preset", "build_type",
                                            "controller_precision"});
  for (const auto &kv : p) CHECK_FALSE(kv.second.empty());
  CHECK(Value(p, "controller_precision") == (UVMS_REAL_IS_FLOAT ? "float" : "double"));
  CHECK(Value(uvms::sil::BuildProvenance(true), "controller_precision") == "float");
  const std::string commit = Value(p, "git_commit");
  const bool hex40 = commit.size() >= 40 &&
                     commit.find_first_not_of("0123456789abcdef") >= 40;
  CHECK((commit == "unknown" || (hex40 && (commit.size() == 40 || commit.substr(40) == "-dirty"))));
}

TEST_CASE("run and campaign provenance append the hashes and the overrides") {
  const Provenance r = uvms::sil::RunProvenance("abc", {"run.seed=3", "payload.mass_kg=5"});
  CHECK(Keys(r).size() == 7);
  CHECK(Keys(r)[5] == "scenario_sha256");
  CHECK(Value(r, "scenario_sha256") == uvms::sil::Sha256Hex("abc"));
  CHECK(Value(r, "scenario_sets") == "run.seed=3\npayload.mass_kg=5");
  CHECK(Value(uvms::sil::RunProvenance("abc", {}), "scenario_sets") == "");
  const Provenance c = uvms::sil::CampaignProvenance("camp", {"x.y=1"}, "base");
  const std::vector<std::string> ck = Keys(c);
  CHECK(std::vector<std::string>(ck.begin() + 5, ck.end()) ==
        std::vector<std::string>{"campaign_sha256", "campaign_sets", "scenario_sha256"});
  CHECK(Value(c, "campaign_sha256") == uvms::sil::Sha256Hex("camp"));
  CHECK(Value(c, "scenario_sha256") == uvms::sil::Sha256Hex("base"));
}

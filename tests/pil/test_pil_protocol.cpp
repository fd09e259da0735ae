// SPDX-License-Identifier: Apache-2.0
// The PIL framing (sil/pil/pil_protocol.h) on the host: the CRC equals the harness's CRC-32,
// frames round-trip whole and byte by byte, and every corruption or desynchronisation (a
// flipped bit anywhere, a truncated frame, junk between frames, a bad header, a split
// delivery) is detected, never delivered, and the next intact frame is found again.
#include <catch2/catch.hpp>

#include <cstring>
#include <memory>
#include <random>
#include <vector>

#include "msg/codec.h"
#include "pil/pil_protocol.h"

namespace {

std::vector<uint8_t> Frame(uint8_t type, uint32_t seq, const std::vector<uint8_t> &payload) {
  std::vector<uint8_t> out(PIL_MAX_FRAME);
  const size_t n = pil_frame_encode(type, seq, payload.data(), payload.size(), out.data(),
                                    out.size());
  REQUIRE(n == PIL_HEADER_BYTES + payload.size() + PIL_CRC_BYTES);
  out.resize(n);
  return out;
}

std::vector<uint8_t> Payload(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<uint8_t> p(n);
  for (auto &b : p) b = uint8_t(rng());
  return p;
}

struct Received {
  uint8_t type;
  uint32_t seq;
  std::vector<uint8_t> payload;
};

// Feeds bytes as the target and the bridge do (feed, then drain with next).
std::vector<Received> FeedAll(pil_rx_t &rx, const std::vector<uint8_t> &bytes) {
  auto f = std::make_unique<pil_frame_t>();
  std::vector<Received> got;
  for (uint8_t b : bytes) {
    int ok = pil_rx_feed(&rx, b, f.get());
    while (ok) {
      got.push_back({f->type, f->seq, std::vector<uint8_t>(f->payload, f->payload + f->len)});
      ok = pil_rx_next(&rx, f.get());
    }
  }
  return got;
}

std::unique_ptr<pil_rx_t> NewRx() {
  auto rx = std::make_unique<pil_rx_t>();
  pil_rx_init(rx.get());
  return rx;
}

}  // namespace

TEST_CASE("PilCrcIsTheHarnessCrc32", "[pil]") {
  // The standard check value of CRC-32/IEEE: "123456789" -> 0xCBF43926.
  const uint8_t check[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  CHECK(pil_crc32(0, check, sizeof check) == 0xCBF43926u);
  const auto p = Payload(1000, 1);
  CHECK(pil_crc32(0, p.data(), p.size()) == uvms_crc32(p.data(), p.size()));
  // Incremental update equals the one-shot value.
  CHECK(pil_crc32(pil_crc32(0, p.data(), 400), p.data() + 400, 600) == uvms_crc32(p.data(), p.size()));
}

TEST_CASE("PilFramesRoundTripInOrder", "[pil]") {
  auto rx = NewRx();
  std::vector<uint8_t> stream;
  const std::vector<size_t> sizes = {0, 1, 8, 188, 552, PIL_MAX_PAYLOAD};
  for (size_t i = 0; i < sizes.size(); ++i) {
    const auto f = Frame(uint8_t(PIL_SENSORS), uint32_t(100 + i), Payload(sizes[i], uint32_t(i)));
    stream.insert(stream.end(), f.begin(), f.end());
  }
  const auto got = FeedAll(*rx, stream);
  REQUIRE(got.size() == sizes.size());
  for (size_t i = 0; i < sizes.size(); ++i) {
    CHECK(got[i].type == PIL_SENSORS);
    CHECK(got[i].seq == 100 + i);
    CHECK(got[i].payload == Payload(sizes[i], uint32_t(i)));
  }
  CHECK(rx->crc_errors == 0);
  CHECK(rx->header_errors == 0);
  CHECK(rx->bytes_dropped == 0);
}

TEST_CASE("PilEncodeRejectsOversizePayloadAndSmallBuffer", "[pil]") {
  std::vector<uint8_t> out(PIL_MAX_FRAME + 10);
  const auto big = Payload(PIL_MAX_PAYLOAD + 1, 2);
  CHECK(pil_frame_encode(PIL_CONFIG, 1, big.data(), big.size(), out.data(), out.size()) == 0);
  const auto p = Payload(100, 3);
  CHECK(pil_frame_encode(PIL_CONFIG, 1, p.data(), p.size(), out.data(), 100) == 0);
}

TEST_CASE("PilEverySingleBitFlipIsDetectedAndTheNextFrameSurvives", "[pil]") {
  const auto a = Frame(PIL_OUTPUT, 7, Payload(64, 4));
  const auto b = Frame(PIL_OUTPUT, 8, Payload(64, 5));
  for (size_t bit = 0; bit < a.size() * 8; ++bit) {
    auto bad = a;
    bad[bit / 8] ^= uint8_t(1u << (bit % 8));
    std::vector<uint8_t> stream = bad;
    stream.insert(stream.end(), b.begin(), b.end());
    auto rx = NewRx();
    const auto got = FeedAll(*rx, stream);
    INFO("bit " << bit);
    // The corrupted frame is never delivered; the intact one after it always is.
    REQUIRE(got.size() == 1);
    CHECK(got[0].seq == 8);
    CHECK(got[0].payload == Payload(64, 5));
    if (bit >= 32) CHECK(pil_rx_errors(rx.get()) >= 1);  // past the magic: an error counted
  }
}

TEST_CASE("PilTruncatedFrameThenIntactFrameResynchronises", "[pil]") {
  // A frame cut short (a lost tail: desynchronisation) swallows the start of the next frame
  // as its own tail; the CRC fails, the receiver rescans and finds the next-but-one frame.
  const auto a = Frame(PIL_SENSORS, 1, Payload(188, 6));
  const auto b = Frame(PIL_SENSORS, 2, Payload(188, 7));
  const auto c = Frame(PIL_SENSORS, 3, Payload(188, 8));
  std::vector<uint8_t> stream(a.begin(), a.begin() + 100);
  stream.insert(stream.end(), b.begin(), b.end());
  stream.insert(stream.end(), c.begin(), c.end());
  auto rx = NewRx();
  const auto got = FeedAll(*rx, stream);
  REQUIRE(!got.empty());
  CHECK(got.back().seq == 3);
  for (const auto &g : got) CHECK(g.seq != 1);  // the truncated frame is never delivered
  CHECK(rx->crc_errors >= 1);
  // Frame 2 is recovered too: it was still in the buffer when frame 1 failed.
  CHECK(got.size() == 2);
}

TEST_CASE("PilJunkAndBadHeadersBetweenFramesAreSkipped", "[pil]") {
  const auto a = Frame(PIL_CONFIG_ACK, 10, Payload(8, 9));
  const auto b = Frame(PIL_HELLO, 11, Payload(20, 10));
  std::vector<uint8_t> stream = Payload(300, 11);  // junk
  stream.insert(stream.end(), a.begin(), a.end());
  // A fake magic with an impossible length, then one with an unknown type.
  const uint8_t fake1[] = {'U', 'V', 'P', 'L', PIL_OUTPUT, PIL_PROTOCOL_VERSION, 0xFF, 0xFF};
  const uint8_t fake2[] = {'U', 'V', 'P', 'L', 99, PIL_PROTOCOL_VERSION, 4, 0, 0, 0, 0, 0};
  stream.insert(stream.end(), fake1, fake1 + sizeof fake1);
  stream.insert(stream.end(), fake2, fake2 + sizeof fake2);
  stream.insert(stream.end(), b.begin(), b.end());
  auto rx = NewRx();
  const auto got = FeedAll(*rx, stream);
  REQUIRE(got.size() == 2);
  CHECK(got[0].seq == 10);
  CHECK(got[1].seq == 11);
  CHECK(rx->header_errors >= 2);
  CHECK(rx->bytes_dropped >= 300);
}

TEST_CASE("PilRandomCorruptionNeverDeliversAWrongFrame", "[pil]") {
  // 2000 frames with random payloads; in 30 % of them a random byte is flipped, dropped or
  // inserted. Every frame delivered must be one that was sent, intact (its sequence number
  // names it), and every intact frame must be delivered: a damaged frame never takes its
  // intact neighbours down with it.
  std::mt19937 rng(42);
  std::vector<std::vector<uint8_t>> payloads;
  std::vector<uint8_t> stream;
  std::vector<uint32_t> intact;
  for (uint32_t i = 0; i < 2000; ++i) {
    payloads.push_back(Payload(size_t(rng() % 600), i + 100));
    auto f = Frame(PIL_SENSORS, i, payloads.back());
    const uint32_t what = rng() % 10;
    if (what == 0) f[rng() % f.size()] ^= uint8_t(1 + rng() % 255);        // corrupt a byte
    else if (what == 1) f.erase(f.begin() + long(rng() % f.size()));       // lose a byte
    else if (what == 2)  // an extra byte inside the frame (one before it is mere junk)
      f.insert(f.begin() + 1 + long(rng() % (f.size() - 1)), uint8_t(rng()));
    else intact.push_back(i);
    stream.insert(stream.end(), f.begin(), f.end());
  }
  auto rx = NewRx();
  const auto got = FeedAll(*rx, stream);
  std::vector<uint32_t> delivered;
  for (const auto &g : got) delivered.push_back(g.seq);
  CHECK(delivered == intact);
  uint32_t last = 0;
  bool first = true;
  for (const auto &g : got) {
    REQUIRE(g.seq < payloads.size());
    CHECK(g.payload == payloads[g.seq]);
    if (!first) CHECK(g.seq > last);  // in order, no duplicates
    last = g.seq;
    first = false;
  }
  CHECK(pil_rx_errors(rx.get()) > 0);
}

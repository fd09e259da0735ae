/* SPDX-License-Identifier: Apache-2.0 */
/* pil_protocol.c: CRC-32 and the PIL framing (pil_protocol.h). Host and Cortex-M4F alike:
 * no allocation, no recursion, every loop bounded by a frame size. */
#include "pil/pil_protocol.h"

#include <string.h>

/* CRC-32 reflected, poly 0xEDB88320, one nibble at a time (16-entry table in flash). */
static const uint32_t kCrcNibble[16] = {
    0x00000000u, 0x1DB71064u, 0x3B6E20C8u, 0x26D930ACu, 0x76DC4190u, 0x6B6B51F4u,
    0x4DB26158u, 0x5005713Cu, 0xEDB88320u, 0xF00F9344u, 0xD6D6A3E8u, 0xCB61B38Cu,
    0x9B64C2B0u, 0x86D3D2D4u, 0xA00AE278u, 0xBDBDF21Cu};

uint32_t pil_crc32(uint32_t crc, const uint8_t *data, size_t n) {
  uint32_t c = ~crc;
  for (size_t i = 0; i < n; ++i) {
    c ^= data[i];
    c = kCrcNibble[c & 0xFu] ^ (c >> 4);
    c = kCrcNibble[c & 0xFu] ^ (c >> 4);
  }
  return ~c;
}

static void put_u16(uint8_t *p, uint32_t v) {
  p[0] = (uint8_t)(v & 0xFFu);
  p[1] = (uint8_t)((v >> 8) & 0xFFu);
}
static void put_u32(uint8_t *p, uint32_t v) {
  put_u16(p, v & 0xFFFFu);
  put_u16(p + 2, v >> 16);
}
static uint32_t get_u16(const uint8_t *p) { return (uint32_t)p[0] | ((uint32_t)p[1] << 8); }
static uint32_t get_u32(const uint8_t *p) { return get_u16(p) | (get_u16(p + 2) << 16); }

size_t pil_frame_encode(uint8_t type, uint32_t seq, const void *payload, size_t len,
                        uint8_t *out, size_t cap) {
  const size_t total = PIL_HEADER_BYTES + len + PIL_CRC_BYTES;
  if (out == NULL || len > PIL_MAX_PAYLOAD || cap < total || (len > 0 && payload == NULL))
    return 0;
  out[0] = PIL_MAGIC0;
  out[1] = PIL_MAGIC1;
  out[2] = PIL_MAGIC2;
  out[3] = PIL_MAGIC3;
  out[4] = type;
  out[5] = (uint8_t)PIL_PROTOCOL_VERSION;
  put_u16(out + 6, (uint32_t)len);
  put_u32(out + 8, seq);
  put_u32(out + 12, pil_crc32(0u, out + 4, 8u));
  if (len > 0) memcpy(out + PIL_HEADER_BYTES, payload, len);
  put_u32(out + PIL_HEADER_BYTES + len, pil_crc32(0u, out + 4, PIL_HEADER_BYTES - 4u + len));
  return total;
}

void pil_rx_init(pil_rx_t *rx) { memset(rx, 0, sizeof *rx); }

uint32_t pil_rx_errors(const pil_rx_t *rx) { return rx->header_errors + rx->crc_errors; }

static const uint8_t kMagic[4] = {PIL_MAGIC0, PIL_MAGIC1, PIL_MAGIC2, PIL_MAGIC3};

/* Discard the first byte of the candidate, then everything up to the next possible start of
   the magic (a byte equal to its first byte). */
static void drop_candidate_start(pil_rx_t *rx) {
  size_t skip = 1;
  while (skip < rx->len && rx->buf[skip] != kMagic[0]) ++skip;
  rx->bytes_dropped += (uint32_t)skip;
  memmove(rx->buf, rx->buf + skip, rx->len - skip);
  rx->len -= skip;
}

static int known_type(uint8_t t) { return t >= (uint8_t)PIL_HELLO && t <= (uint8_t)PIL_QUIT; }

/* Take a frame from the front of the buffer if one is complete; resynchronise on errors. Each
   pass either waits for more bytes, delivers a frame or drops at least one byte: at most
   PIL_MAX_FRAME passes. */
int pil_rx_next(pil_rx_t *rx, pil_frame_t *frame) {
  for (size_t pass = 0; pass <= PIL_MAX_FRAME && rx->len > 0; ++pass) {
    const size_t have_magic = rx->len < 4u ? rx->len : 4u;
    if (memcmp(rx->buf, kMagic, have_magic) != 0) {
      drop_candidate_start(rx);
      continue;
    }
    if (rx->len < PIL_HEADER_BYTES) return 0;
    const uint32_t len = get_u16(rx->buf + 6);
    if (get_u32(rx->buf + 12) != pil_crc32(0u, rx->buf + 4, 8u) || !known_type(rx->buf[4]) ||
        rx->buf[5] != (uint8_t)PIL_PROTOCOL_VERSION || len > PIL_MAX_PAYLOAD) {
      ++rx->header_errors;
      drop_candidate_start(rx);
      continue;
    }
    const size_t total = PIL_HEADER_BYTES + len + PIL_CRC_BYTES;
    if (rx->len < total) return 0;
    const uint32_t crc = get_u32(rx->buf + PIL_HEADER_BYTES + len);
    if (crc != pil_crc32(0u, rx->buf + 4, PIL_HEADER_BYTES - 4u + len)) {
      ++rx->crc_errors;
      drop_candidate_start(rx);
      continue;
    }
    frame->type = rx->buf[4];
    frame->seq = get_u32(rx->buf + 8);
    frame->len = (uint16_t)len;
    memcpy(frame->payload, rx->buf + PIL_HEADER_BYTES, len);
    ++rx->frames;
    /* Bytes after the frame (possible after a resynchronisation) stay for the next call. */
    memmove(rx->buf, rx->buf + total, rx->len - total);
    rx->len -= total;
    return 1;
  }
  return 0;
}

int pil_rx_feed(pil_rx_t *rx, uint8_t byte, pil_frame_t *frame) {
  if (rx->len >= PIL_MAX_FRAME) drop_candidate_start(rx); /* unreachable: next() keeps len <
                                                              PIL_MAX_FRAME; stay safe */
  rx->buf[rx->len++] = byte;
  return pil_rx_next(rx, frame);
}

/* SPDX-License-Identifier: Apache-2.0 */
/*
 * pil_protocol.h: the processor-in-the-loop link between the host bridge
 * (uvms-controller-pil, sil/pil/pil_bridge_main.c) and the Cortex-M4F image
 * (sil/pil/target/pil_m4f.c) running in QEMU mps2-an386. Plain C11, no LCM, no
 * allocation: compiled into both sides.
 *
 * Transport: two host FIFOs opened by the image through semihosting (SYS_OPEN/READ/WRITE,
 * ~51 µs per exchange, TOOLCHAIN.md): host -> target ("in") and target -> host ("out"). A byte
 * stream, so the framing below detects corruption and desynchronisation on its own.
 *
 * Frame (every multi-byte field little-endian, like both ends):
 *
 *   offset  size  field
 *   0       4     magic "UVPL" (0x55 0x56 0x50 0x4C)
 *   4       1     type (pil_frame_type_t)
 *   5       1     version (PIL_PROTOCOL_VERSION)
 *   6       2     payload length L (<= PIL_MAX_PAYLOAD)
 *   8       4     sequence number
 *   12      4     header CRC: CRC-32 of bytes 4 .. 11
 *   16      L     payload (one record below, copied as bytes)
 *   16+L    4     frame CRC: CRC-32 (IEEE 802.3, as sil/msg/codec.h) of bytes 4 .. 16+L-1
 *
 * Receiver (pil_rx_feed): hunts for the magic; a header whose CRC fails or with an unknown
 * type or version or an oversize length, or a frame CRC mismatch, drops the first byte of the
 * candidate frame and searches again from the next byte (resynchronisation), counting the
 * event. So a corrupted frame is lost, never misread, and the frames after it are found again.
 * The header CRC makes a corrupted length field fail at once: the receiver never waits for
 * bytes that a bogus length claims (a stall until the sender's retransmissions filled it).
 *
 * Exchange (lockstep, the host leads): the host sends CONFIG, SENSORS or QUIT with a new
 * sequence number; the target answers CONFIG with CONFIG_ACK and SENSORS with OUTPUT, both
 * carrying the request's sequence number. The target never steps twice for one sequence
 * number: a repeated request (a retransmission) gets the cached answer again. When the target
 * drops bytes (bad header or CRC) it sends NAK; the host retransmits the pending request on
 * NAK or after a timeout, and ignores answers whose sequence number or type is not the
 * pending one (desynchronisation: counted, never used). At start the target sends HELLO
 * (sequence 0) with the protocol version and its record sizes, which the host checks against
 * its own: a record layout that differs between the two compilers is caught before any use.
 *
 * Records: fixed-layout C structs of int64 (first, 8-aligned), int32/uint32 and IEEE-754
 * float fields only: no padding (asserted below), identical on x86-64 SysV and AAPCS. Every
 * real is float: the host rounds the LCM doubles exactly as sil/msg/codec.c's mappings do in the
 * float build ((float) of the double; time_s = (float)(utime · 1e-6) computed in double), so
 * the firmware in the image sees bit for bit the inputs the host float build sees.
 */
#ifndef UVMS_PIL_PROTOCOL_H
#define UVMS_PIL_PROTOCOL_H

#include <stddef.h>
#include <stdint.h>

#include "msg/config_table.h" /* the configuration record's fields */
#include "msg/record_table.h" /* the sensors and output records' fields */

#ifdef __cplusplus
extern "C" {
#endif

#define PIL_PROTOCOL_VERSION 3u  /* 2: fault-handling limits and telemetry; 3: config record in
                                    the order of sil/msg/config_table.h */
#define PIL_MAGIC0 0x55u /* 'U' */
#define PIL_MAGIC1 0x56u /* 'V' */
#define PIL_MAGIC2 0x50u /* 'P' */
#define PIL_MAGIC3 0x4Cu /* 'L' */
#define PIL_HEADER_BYTES 16u
#define PIL_CRC_BYTES 4u
#define PIL_MAX_PAYLOAD 2048u
#define PIL_MAX_FRAME (PIL_HEADER_BYTES + PIL_MAX_PAYLOAD + PIL_CRC_BYTES)

typedef enum {
  PIL_HELLO = 1,      /* target -> host: pil_hello_rec_t, sequence 0, once at start */
  PIL_CONFIG = 2,     /* host -> target: pil_config_rec_t */
  PIL_CONFIG_ACK = 3, /* target -> host: pil_config_ack_rec_t */
  PIL_SENSORS = 4,    /* host -> target: pil_sensors_rec_t */
  PIL_OUTPUT = 5,     /* target -> host: pil_output_rec_t */
  PIL_NAK = 6,        /* target -> host: pil_nak_rec_t (bytes were dropped: resend) */
  PIL_QUIT = 7        /* host -> target: empty; the image exits 0 */
} pil_frame_type_t;

/* ---- records ------------------------------------------------------------------------------ */

/* The controller configuration: the fields of lcmtypes/controller_config_t.lcm except utime,
 * tick and crc32, same names and shapes, reals in float, integers widened to int32, in the
 * order of the table of configuration fields (sil/msg/config_table.h), which also drives the
 * host's filling (pil_host.c) and the target's mapping (pil_map.c), so the three cannot drift. */
#define PIL_DECLARE_REAL_(name, dims) float name dims;
#define PIL_DECLARE_INT_(name) int32_t name;
#define PIL_DECLARE_ROW_(name, dims, unit, doc) float name dims; /* [unit] */
#define PIL_CONFIG_FIELD_(map, shape, fw, lcm, ...) \
  UVMS_CFG_WIRE_##map(PIL_DECLARE_REAL_, PIL_DECLARE_INT_, shape, lcm)
typedef struct {
  UVMS_CONFIG_TABLE(PIL_CONFIG_FIELD_)
} pil_config_rec_t;

/* One tick's sensors: uvms_ctrl_sensors_t's fields (same names) with float reals.
 * X(name, dims, unit, doc) rows of sil/msg/record_table.h, after time_s: float. */
#define PIL_SENSOR_FIELDS(X) X(time_s, , "s", "time since run start") UVMS_SENSOR_FIELDS(X)
typedef struct {
  int64_t tick;                  /* tick k */
  PIL_SENSOR_FIELDS(PIL_DECLARE_ROW_)
  uint32_t thruster_usable_mask; /* bit j = thruster j usable */
  uint32_t reserved;             /* 0; makes the size a multiple of 8 (no tail padding) */
} pil_sensors_rec_t;

/* One step's outputs: uvms_ctrl_command_t's fields, then uvms_ctrl_telemetry_t's reals (same
 * names), all float: rows of sil/msg/record_table.h. */
#define PIL_COMMAND_FIELDS(X) UVMS_ACTUATOR_FIELDS(X) UVMS_REFERENCE_FIELDS(X)
#define PIL_TELEMETRY_FIELDS(X) UVMS_TELEMETRY_FIELDS(X)
/* The telemetry's integers after its reals, copied as they are: X(type, name, doc). */
#define PIL_TELEMETRY_INTS(X)                                                     \
  X(uint32_t, uncontrollable_axes, "telemetry's UVMS_AXIS_* bits")               \
  X(int32_t, alloc_rank, "telemetry's allocation rank 0..6")                     \
  X(uint32_t, sensor_rejected_ticks, "telemetry's consecutive rejected records")
#define PIL_DECLARE_TYPED_(type, name, doc) type name;
typedef struct {
  int64_t tick;   /* tick of the sensors this answers */
  int32_t status; /* uvms_status_t of uvms_ctrl_step */
  uint32_t flags; /* UVMS_FLAG_* */
  PIL_COMMAND_FIELDS(PIL_DECLARE_ROW_)
  PIL_TELEMETRY_FIELDS(PIL_DECLARE_ROW_)
  PIL_TELEMETRY_INTS(PIL_DECLARE_TYPED_)
} pil_output_rec_t;

typedef struct {
  int32_t status;       /* uvms_status_t of uvms_ctrl_init (UVMS_ERR_RANGE: mapping failed) */
  int32_t config_error; /* uvms_cfg_field_t */
} pil_config_ack_rec_t;

typedef struct {
  uint32_t version;            /* PIL_PROTOCOL_VERSION */
  uint32_t config_rec_bytes;   /* sizeof(pil_config_rec_t) on the target */
  uint32_t sensors_rec_bytes;  /* sizeof(pil_sensors_rec_t) */
  uint32_t output_rec_bytes;   /* sizeof(pil_output_rec_t) */
  uint32_t max_payload;        /* PIL_MAX_PAYLOAD */
} pil_hello_rec_t;

typedef struct {
  uint32_t header_errors; /* target's receiver counters since start (pil_rx_t) */
  uint32_t crc_errors;
  uint32_t bytes_dropped;
} pil_nak_rec_t;

/* No padding anywhere: the byte image of a record is the same on both compilers. */
#ifdef __cplusplus
#define PIL_STATIC_ASSERT_ static_assert
#else
#define PIL_STATIC_ASSERT_ _Static_assert
#endif
#define PIL_F32_COUNT_(name, dims, unit, doc) +(sizeof(((pil_output_rec_t *)0)->name) / 4u)
PIL_STATIC_ASSERT_(sizeof(float) == 4, "IEEE-754 binary32 floats");
PIL_STATIC_ASSERT_(sizeof(pil_config_rec_t) % 4u == 0 && sizeof(pil_config_rec_t) <= PIL_MAX_PAYLOAD,
               "config record");
PIL_STATIC_ASSERT_(sizeof(pil_sensors_rec_t) == 8u + 4u * (1u + 3u + 4u + 3u + 3u + 7u + 7u + 8u + 8u) + 8u,
               "sensors record has no padding");
PIL_STATIC_ASSERT_(sizeof(pil_output_rec_t) ==
                   16u + 4u * (0u PIL_COMMAND_FIELDS(PIL_F32_COUNT_) PIL_TELEMETRY_FIELDS(PIL_F32_COUNT_)) + 12u,
               "output record has no padding");
PIL_STATIC_ASSERT_(sizeof(pil_output_rec_t) <= PIL_MAX_PAYLOAD, "output record fits a frame");

/* ---- CRC and frames ----------------------------------------------------------------------- */

/** CRC-32 (IEEE 802.3, reflected, poly 0xEDB88320; the value sil/msg/codec.h's uvms_crc32 gives)
 *  of n bytes, updated from crc (start with 0). Nibble table: no RAM, 2 lookups per byte. */
uint32_t pil_crc32(uint32_t crc, const uint8_t *data, size_t n);

/**
 * @brief Encode one frame.
 * @param[in]  type, seq  frame type and sequence number
 * @param[in]  payload    len bytes (may be NULL when len is 0)
 * @param[out] out        cap bytes of room
 * @return the frame's size in bytes (PIL_HEADER_BYTES + len + PIL_CRC_BYTES), or 0 if len
 *         exceeds PIL_MAX_PAYLOAD or cap is too small (nothing written then).
 */
size_t pil_frame_encode(uint8_t type, uint32_t seq, const void *payload, size_t len,
                        uint8_t *out, size_t cap);

/** A received frame (payload copied out of the receiver's buffer). */
typedef struct {
  uint8_t type;
  uint32_t seq;
  uint16_t len;
  uint8_t payload[PIL_MAX_PAYLOAD];
} pil_frame_t;

/** Streaming receiver state (caller-owned; zero it with pil_rx_init). */
typedef struct {
  uint8_t buf[PIL_MAX_FRAME];
  size_t len;             /* bytes of the candidate frame held in buf */
  uint32_t frames;        /* valid frames delivered */
  uint32_t header_errors; /* candidates with a bad header CRC, type, version or length */
  uint32_t crc_errors;    /* candidates with a CRC mismatch */
  uint32_t bytes_dropped; /* bytes discarded while hunting for a frame */
} pil_rx_t;

void pil_rx_init(pil_rx_t *rx);

/**
 * @brief Feed one received byte.
 * @return 1 when this byte completed a valid frame (copied into *frame), 0 otherwise. Errors
 *         are only counted (rx->header_errors, crc_errors, bytes_dropped); the receiver
 *         resynchronises by itself. Bounded work: at most PIL_MAX_FRAME steps per byte.
 */
int pil_rx_feed(pil_rx_t *rx, uint8_t byte, pil_frame_t *frame);

/**
 * @brief Take a further complete frame already held in the receiver (after a delivery or a
 *        resynchronisation the buffer may hold more than one). Call it after every frame
 *        pil_rx_feed delivered, until it returns 0.
 * @return 1 with *frame filled, 0 when no complete frame is buffered.
 */
int pil_rx_next(pil_rx_t *rx, pil_frame_t *frame);

/** Sum of the receiver's error counters (header + CRC errors): a change means a frame was lost. */
uint32_t pil_rx_errors(const pil_rx_t *rx);

#ifdef __cplusplus
}
#endif
#endif /* UVMS_PIL_PROTOCOL_H */

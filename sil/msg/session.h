/* SPDX-License-Identifier: Apache-2.0 */
/*
 * session.h: a run's session identifier (docs/FAULTS.md "Sessions").
 *
 * Every message of a run carries the same 64-bit session (the `session` field of every
 * lcmtypes/ message). `uvms run` draws it at random when the run starts, unless --session fixes
 * it, and hands it to both nodes on their command lines; each node stamps it on what it sends
 * and drops (and counts) whatever carries another. So two runs that share an LCM URL cannot
 * exchange messages, and a status from another run cannot stop a controller. It is an
 * identifier, not a secret: it travels in clear on the bus and is written in the log.
 * UVMS_SESSION_NONE (0) is never drawn: it means "not fixed yet" (a controller started by hand
 * adopts the session of the first configuration it accepts).
 */
#ifndef UVMS_SIL_SESSION_H
#define UVMS_SIL_SESSION_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define UVMS_SESSION_NONE 0
/* Characters of a formatted session: 16 lowercase hex digits and the NUL. */
#define UVMS_SESSION_TEXT_BYTES 17

/* Draw a nonzero session from the kernel's random source (getrandom). Returns 0, or -1 when the
   random source failed (errno says why; *session is then UVMS_SESSION_NONE). */
int uvms_session_draw(int64_t *session);

/* Parse 1 to 16 hex digits (no prefix, no sign, nothing after) naming a nonzero session.
   Returns 1 and sets *session, or 0 (and *session = UVMS_SESSION_NONE) when `text` is not one. */
int uvms_session_parse(const char *text, int64_t *session);

/* The session as 16 lowercase hex digits (the form uvms_session_parse reads back). */
void uvms_session_format(int64_t session, char text[UVMS_SESSION_TEXT_BYTES]);

#ifdef __cplusplus
}
#endif
#endif /* UVMS_SIL_SESSION_H */

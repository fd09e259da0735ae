/* SPDX-License-Identifier: Apache-2.0 */
/*
 * sensor_sequence.h: a deterministic, recorded-style sensor sequence for driving the
 * controller without a plant (float-vs-double comparison, host and target benchmarks).
 * The vehicle drifts and turns slowly, the joints follow the configured cycloid with a small
 * lag, the motors spin and draw current. Pure function of (config, tick): no randomness.
 */
#ifndef UVMS_SENSOR_SEQUENCE_H
#define UVMS_SENSOR_SEQUENCE_H

#include "uvms/controller.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Tick period [s] and trajectory duration [s] the sequence assumes (SPEC §3.5). */
#define UVMS_SEQ_TICK_S 0.03
#define UVMS_SEQ_DURATION_S 60.0

/** @brief Sensor record of tick k for a controller configured with cfg. */
void uvms_sensor_sequence(const uvms_ctrl_config_t *cfg, int tick, uvms_ctrl_sensors_t *s);

#ifdef __cplusplus
}
#endif
#endif

// SPDX-License-Identifier: Apache-2.0
// plant_messages.hpp: the plant's truth as LCM messages (sensors_t, truth_t; lcmtypes/).
#pragma once

#include <cstdint>
#include <string>

#include "codec.h"
#include "uvms_plant/plant.hpp"

namespace uvms::sil {

/// Simulated time of tick k as LCM utime [µs].
std::int64_t TickUtime(long k, double tick_s);

/// The sensors message of tick k from the truth (exact values: noise and the health mask are
/// the fault injector's, sil/faults.hpp).
void FillSensors(const plant::Truth &t, long k, std::int64_t utime, uvms_sensors_t &s);

/// The truth message of tick k. m.closest_pair points into `pair`, which must outlive m.
void FillTruthMsg(const plant::Truth &t, long k, std::int64_t utime, const std::string &pair,
                  uvms_truth_t &m);

}  // namespace uvms::sil

#include "sensor_sim/duty_cycle_modulator.h"

namespace adahrs::sensor_sim {

DutyCycleModulator::DutyCycleModulator(double frame_cnt,
                                       double initial_end_cnt,
                                       double initial_grid_phase_cnt)
    : frame_cnt_(frame_cnt),
      last_end_cnt_(initial_end_cnt),
      grid_phase_cnt_(initial_grid_phase_cnt) {}

}  // namespace adahrs::sensor_sim

// The golden replay on the host (int of 32 bits): the transcript on stdout.
#include <stdio.h>

#include "golden_replay.h"

uint8_t golden_replay_program_byte(uint16_t index) { return golden_replay_program[index]; }

void golden_replay_put_char(char c) { (void)putchar(c); }

int main(void) {
  (void)golden_replay_run();
  return (fflush(stdout) == 0) ? 0 : 1;
}

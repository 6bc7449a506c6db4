// The golden replay on an ATmega2560 (int of 16 bits) under simavr: the transcript on USART0,
// which simavr prints line by line; the program's bytes are read from program memory. Before the
// run, the RAM between the static data and the stack is painted; after it, the untouched part is
// reported ("ram_free"), the stack's headroom at its deepest. Ends by sleeping with interrupts off,
// which stops simavr.
#include <avr/interrupt.h>
#include <avr/io.h>
#include <avr/pgmspace.h>
#include <avr/sleep.h>
#include <stdint.h>

#include "golden_replay.h"

#define PAINT_BYTE 0xC5u

extern uint8_t __heap_start;  // end of .data and .bss (avr-libc linker script)

uint8_t golden_replay_program_byte(uint16_t index) {
  return pgm_read_byte(&golden_replay_program[index]);
}

void golden_replay_put_char(char c) {
  while ((UCSR0A & (uint8_t)(1u << UDRE0)) == 0u) {
  }
  UDR0 = (uint8_t)c;
}

// Paints from the end of the static data up to a margin below the current stack pointer.
static void PaintRam(void) {
  uint8_t* p = &__heap_start;
  const uint8_t* const top = (const uint8_t*)SP - 32;
  while (p < top) {
    *p = PAINT_BYTE;
    ++p;
  }
}

static uint16_t UntouchedRam(void) {
  const uint8_t* p = &__heap_start;
  uint16_t count = 0u;
  while (*p == PAINT_BYTE) {
    ++count;
    ++p;
  }
  return count;
}

int main(void) {
  PaintRam();
  UCSR0B = (uint8_t)(1u << TXEN0);
  (void)golden_replay_run();
  golden_replay_put_line_u32("ram_free", UntouchedRam());
  cli();
  sleep_enable();
  sleep_cpu();
  return 0;
}

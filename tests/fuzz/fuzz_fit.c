/* libFuzzer harness for the ISO 286 fit-string parser. */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "iso286.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  char text[256];
  if (size >= sizeof text) size = sizeof text - 1;
  memcpy(text, data, size);
  text[size] = '\0';
  fb_fit f;
  fb_diag d;
  fb_status st = fb_iso286_fit(&f, text, &d);
  if (st != FB_OK && d.msg[0] == '\0') __builtin_trap();
  if (st == FB_OK && !(f.clearance_max >= f.clearance_min)) __builtin_trap();
  return 0;
}

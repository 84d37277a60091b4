/* libFuzzer harness for the case-file parser: any bytes as a case file must
 * give FB_OK or an error with a message, never a crash, hang or leak. */
#include <stddef.h>
#include <stdint.h>

#include "casefile.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  fb_case c;
  fb_diag d;
  fb_status st = fb_casefile_load_text(&c, "fuzz.ini", (const char *)data, size, &d);
  if (st != FB_OK && d.msg[0] == '\0') __builtin_trap(); /* every error says what */
  return 0;
}

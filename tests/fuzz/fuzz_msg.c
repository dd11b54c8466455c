/* libFuzzer harness: the nodes' message decoder (src/stream/ss_msg.h) on any bytes, as
 * a subscriber meets them: the first byte picks the type, the rest is the message.
 * One scratch is kept across inputs, as a subscriber keeps it. Asserts the documented
 * results: a refusal has a reason; sizing alone (no scratch) agrees with a decode; a
 * message decoded encodes again into at most as many bytes (strings cut at a NUL),
 * which decode again. */
#include <assert.h>
#include <string.h>

#include "ss_msg.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  static ss_msg_scratch scratch;
  static ss_msg_scratch again;
  ss_msg_any view, sized, view2;
  if (size == 0) return 0;
  int type = data[0] % SS_MSG_TYPES;
  const uint8_t *buf = data + 1;
  size_t len = size - 1;
  char why[256];
  memset(why, 'x', sizeof why);
  int st = ss_msg_decode(type, buf, len, &view, &scratch, why, sizeof why);
  int st_sized = ss_msg_decode(type, buf, len, &sized, NULL, NULL, 0);
  assert(st == SS_MSG_OK || st == SS_MSG_E_MALFORMED || st == SS_MSG_E_NOMEM);
  assert(st == SS_MSG_E_NOMEM || st == st_sized);
  if (st != SS_MSG_OK) {
    assert(why[0] != '\0' && memchr(why, '\0', sizeof why) != NULL);
    return 0;
  }
  ss_msg_buf out = {0};
  assert(ss_msg_encode(type, &view, &out) == SS_MSG_OK);
  assert(out.len <= len);
  assert(ss_msg_decode(type, out.data, out.len, &view2, &again, NULL, 0) == SS_MSG_OK);
  ss_msg_buf_free(&out);
  return 0;
}

/* Text made safe for a terminal or a text report (textsafe.h): every
 * control character of data escaped, everything else byte for byte, through
 * the string function, the stream (whatever the chunks it is written in),
 * and a POSIX shell word (fb_cli_shell_word, src/cli/cli.c is not in the
 * library: its rule is fb_text_unit's, tested here). */
#include <string.h>

#include "fb_test.h"
#include "textsafe.h"

/* what an escaping writer must give for one input */
typedef struct {
  const char *in;
  const char *out;
} pair;

static const pair cases[] = {
    {"plain text, 1.5 m/s", "plain text, 1.5 m/s"},
    {"tab\there\nnext line", "tab\there\nnext line"},             /* TAB and LF are text */
    {"\x1b[2J clear", "\\x1b[2J clear"},                          /* CSI: erase display */
    {"\x1b]52;c;SGVsbG8=\x07", "\\x1b]52;c;SGVsbG8=\\x07"},     /* OSC 52: the clipboard */
    {"a\rb", "a\\x0db"},                                          /* CR rewrites a line */
    {"del\x7f", "del\\x7f"},                                      /* DEL */
    {"c1 \xc2\x9b" "2J", "c1 \\u009b2J"},                         /* C1 CSI, UTF-8 encoded */
    {"caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80", "caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80"},
    {"lone \x9b byte", "lone \\x9b byte"},                        /* C1 in Latin-1 */
    {"bad \xff\xfe", "bad \\xff\\xfe"},                           /* never UTF-8 */
    {"overlong \xc0\xaf", "overlong \\xc0\\xaf"},                 /* RFC 3629: no overlong */
    {"surrogate \xed\xa0\x80", "surrogate \\xed\\xa0\\x80"},      /* nor a surrogate */
    {"cut \xe2\x82", "cut \\xe2\\x82"},                           /* a sequence cut short */
};

static void test_escape_string(void **state) {
  (void)state;
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    char out[256];
    assert_string_equal(fb_text_escape(out, sizeof out, cases[i].in), cases[i].out);
  }
  /* a small buffer cuts at a whole escape, never inside one */
  char small[5];
  fb_text_escape(small, sizeof small, "ab\x1b[2J");
  assert_string_equal(small, "ab");
}

/* the stream gives the same bytes whatever the sizes of the writes (a UTF-8
 * character split between two writes stays one character) */
static void test_stream_any_chunks(void **state) {
  (void)state;
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
    for (size_t chunk = 1; chunk <= 4; chunk++) {
      char *buf = NULL;
      size_t len = 0;
      FILE *mem = open_memstream(&buf, &len);
      FILE *safe = fb_text_safe_stream(mem, 0);
      assert_non_null(safe);
      setvbuf(safe, NULL, _IONBF, 0); /* each fwrite reaches the cookie as it is */
      const char *in = cases[i].in;
      for (size_t k = 0; k < strlen(in); k += chunk) {
        const size_t n = strlen(in + k) < chunk ? strlen(in + k) : chunk;
        assert_int_equal(fwrite(in + k, 1, n, safe), n);
      }
      assert_int_equal(fclose(safe), 0);
      fclose(mem);
      if (strcmp(buf, cases[i].out) != 0)
        fail_msg("case %zu in chunks of %zu: '%s', expected '%s'", i, chunk, buf, cases[i].out);
      free(buf);
    }
}

/* a write error of the stream below is the safe stream's */
static void test_stream_reports_errors(void **state) {
  (void)state;
  FILE *full = fopen("/dev/full", "w");
  if (!full) skip();
  setvbuf(full, NULL, _IONBF, 0);
  FILE *safe = fb_text_safe_stream(full, 1);
  assert_non_null(safe);
  fputs("text that cannot be written\n", safe);
  assert_true(fflush(safe) != 0 || ferror(safe));
  fclose(safe);
}

/* the unit rule shell words and other writers use */
static void test_unit_rule(void **state) {
  (void)state;
  size_t len;
  assert_int_equal(fb_text_unit("a", 1, &len), 0);
  assert_int_equal(len, 1);
  assert_int_equal(fb_text_unit("\xc3\xa9x", 3, &len), 0);
  assert_int_equal(len, 2);
  assert_int_equal(fb_text_unit("\x1b", 1, &len), 1);
  assert_int_equal(len, 1);
  assert_int_equal(fb_text_unit("\xc2\x9b", 2, &len), 1);
  assert_int_equal(len, 2);
  assert_int_equal(fb_text_unit("\n", 1, &len), 0);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_escape_string),
      cmocka_unit_test(test_stream_any_chunks),
      cmocka_unit_test(test_stream_reports_errors),
      cmocka_unit_test(test_unit_rule),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}

/* The rows files of a sweep (points[.shard-I-of-N].jsonl): rows read back
 * and checked, a killed writer's broken row dropped, rows appended durably,
 * and the names of the files beside a rows file. Shared by a sweep
 * (sweep_run.c) and merge (sweep_merge.c). */
#ifndef FB_SWEEP_ROWS_H
#define FB_SWEEP_ROWS_H

#include <stddef.h>

/* Rows as read: malloc'ed JSON lines, each ending in '\n'. */
typedef struct {
  char **rows;
  size_t n, cap;
} fb_sweep_rowset;

/* Adds a copy of line; 0 when out of memory. */
int fb_sweep_rows_add(fb_sweep_rowset *r, const char *line);

/* Frees the rows and empties r. */
void fb_sweep_rows_free(fb_sweep_rowset *r);

/* Reads the rows of a JSON-lines file into r, each checked field by field
 * (fb_study_row_parse). With repair (a sweep resuming its own file) a broken
 * or partial line (a killed writer) is dropped, to be computed again, and the
 * file rewritten without it (said on stderr, "fourbar sweep: ..."); without
 * repair (merge) the first one is an error naming file, line and rule in err
 * (err_size bytes). Returns 0 (a missing file reads as no rows, with why in
 * err) or -1 on an error. */
int fb_sweep_rows_read(const char *path, fb_sweep_rowset *r, int repair, char *err,
                       size_t err_size);

/* Appends line to fd whole (retrying short writes and EINTR), then fsync:
 * 0, or -1 with errno set. */
int fb_sweep_rows_append(int fd, const char *line);

/* The file beside a rows file with the suffix in place of ".jsonl":
 * points[.X].jsonl -> points[.X]<suffix> (".provenance.json", ".csv"). */
void fb_sweep_rows_beside(char *out, size_t size, const char *rows_path, const char *suffix);

#endif

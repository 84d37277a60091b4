/* "Did you mean": the nearest of a list of names to a misspelt one, for the
 * messages of unknown commands and case-file keys. */
#ifndef FB_SUGGEST_H
#define FB_SUGGEST_H

/* Edit distance between a and b: the fewest single-character insertions,
 * deletions, substitutions and swaps of two adjacent characters that turn
 * one into the other (optimal string alignment distance; Damerau, Comm.
 * ACM 7(3), 1964: the four errors of most misspellings). Names longer than
 * FB_SUGGEST_MAX_LEN characters give FB_SUGGEST_FAR. */
int fb_edit_distance(const char *a, const char *b);

#define FB_SUGGEST_MAX_LEN 63
#define FB_SUGGEST_FAR 99

/* The largest distance at which a name of length n is still taken for a
 * misspelling: 1 for up to 4 characters, 2 up to 8, then one per 4 more
 * characters (a typo a word, roughly); nearer names are suggested. */
int fb_suggest_bound(const char *word);

/* The name of names[0 .. n-1] nearest to word by fb_edit_distance when it is
 * within fb_suggest_bound(word), else NULL (ties: the first). */
const char *fb_suggest(const char *word, const char *const *names, int n);

#endif

/* Text from outside a writer's own literals (a case's name, a joint's name
 * from the mechanism's description) made safe inside XML: the one rule
 * every XML, SDF, MJCF, SVG or HTML text writer uses for such text.
 *
 * XML 1.0 (W3C, fifth edition): a comment may not contain "--" nor end in
 * '-' (section 2.5, production [15]); an attribute value in double quotes
 * may not contain '<', '&' or '"' (2.3, [10]); and no text may hold a
 * control character other than TAB, LF and CR (2.2, [2], not even as a
 * character reference). */
#ifndef FB_XMLTEXT_H
#define FB_XMLTEXT_H

#include <stddef.h>

/* Longest name a writer escapes inline (FB_XML_ATTR) [bytes, with the NUL]. */
#define FB_XML_NAME 256

/* Writes in into out (size bytes, always NUL-terminated; cut at a whole
 * character reference when out is too small) for an attribute value in
 * double or single quotes or for element text: & < > " ' as &amp; &lt;
 * &gt; &quot; &apos;, a control character other than TAB, LF and CR as
 * '?'. Returns out. */
char *fb_xml_escape(char *out, size_t size, const char *in);

/* fb_xml_escape in a buffer of its own (FB_XML_NAME bytes), for a printf
 * argument; the buffer lives until the end of the enclosing block (C11
 * 6.5.2.5). */
#define FB_XML_ATTR(s) fb_xml_escape((char[FB_XML_NAME]){0}, FB_XML_NAME, (s))

/* Writes in into out (size bytes, always NUL-terminated) as the text of an
 * XML comment: each '-' that follows a '-' gets a space before it ("x--y"
 * becomes "x- -y"), a '-' at the end a space after it, a control character
 * other than TAB, LF and CR becomes '?'. Returns out. */
char *fb_xml_comment_text(char *out, size_t size, const char *in);

#endif
